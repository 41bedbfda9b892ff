#pragma once
// The receding horizon's state: the plan so far (its footsteps, objective, bound, status
// and window records), the stance the next window starts from, and the snapshots taken
// at each window's start that a retry backs up to. Private to planner/planning.
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "planner/formulation/miqp_formulation.h"
#include "planner/formulation/plan.h"
#include "planner/planning/internal/plan_context.h"
#include "planner/search/branch_and_bound.h"

namespace mfp {

struct HorizonState {
  // The start stance (plan.footsteps[0 .. n-1], in gait order), status optimal.
  explicit HorizonState(const PlanContext& context);

  // Where the horizon stood when a window started.
  struct Snapshot {
    std::vector<Eigen::Vector3d> stance, history;
    std::vector<double> stance_yaw;
    int phase = 0, planned = 0;
    double yaw = 0.0, objective = 0.0, bound = 0.0;
    size_t footsteps = 0;
  };

  // Another window is wanted: the goal is not reached, steps and windows are left.
  bool WantsAnotherWindow() const;
  void TakeSnapshot() { snapshots.push_back(Here()); }
  // Where the horizon stands now.
  Snapshot Here() const {
    return Snapshot{stance, history, stance_yaw, phase, planned, yaw, plan.objective, plan.bound, plan.footsteps.size()};
  }
  // Back to the start of the window that just failed, or, with past_failed_window, to
  // the start of the window before it (when there is one); its snapshot is dropped
  // (taken again when the window is planned).
  void BackUp(bool past_failed_window);
  // A window's MIQP was built: counts it; the first window's fills the plan's size fields.
  void CountWindow(const MiqpFormulation& formulation);
  // A window's search ended: its record joins the plan's, its work the plan's counts.
  void RecordWindow(const WindowRecord& record);
  // Adds a window's plan to the plan (status, objective, bound), keeps its untrimmed
  // steps (a suffix of trimmed steps leaves the feet where they are), moves the stance
  // to their end and returns how many were kept (also in the window's record, the last).
  // used: the MIQP that result.x solves; steps: its footsteps (start stance first).
  int Accept(const MiqpFormulation& used, const BranchAndBoundResult& result, const std::vector<Footstep>& steps);
  // The window's untrimmed new steps that Accept would keep (those up to its last untrimmed one).
  int KeptSteps(const MiqpFormulation& used, const BranchAndBoundResult& result) const;
  // After an accepted window: the way its stance has left (RemainingWay). A stance that
  // leaves less than the best so far becomes the best point; one that leaves min_gain_m
  // less than the stance that last did so resets windows_without_progress, which
  // otherwise counts this window.
  void NoteProgress(double remaining_m, double min_gain_m);
  // Back to the best point when the plan stands behind it (a plan ending short of the
  // goal keeps the steps that made progress); false when it stands there already.
  bool ReturnToBest();
  // Where each leg stood after the plan's first `count` footsteps.
  std::vector<Eigen::Vector3d> FeetAfter(size_t count) const;
  // "window k", k the number of windows solved so far (the current one), for messages.
  std::string WindowName() const { return "window " + std::to_string(plan.windows); }

  const PlanContext& context;
  Plan plan;
  std::vector<Eigen::Vector3d> stance;    // the next window's start, in gait order
  std::vector<Eigen::Vector3d> history;   // where those feet stood one step earlier
  std::vector<double> stance_yaw;         // the yaw each stance foot was placed with [rad]
  int phase = 0;                          // gait phase of the next step
  int planned = 0;                        // new footsteps accepted so far
  double yaw = 0.0;                       // body yaw of the stance [rad]
  int accepted_windows = 0;               // windows whose steps were kept, for the time budget
  double start_progress_m = 0.0;          // route progress of the start stance (guided)
  std::vector<Snapshot> snapshots;        // one per window started and not backed out of
  std::string polish_note;  // the first window whose polished plan was not used, and why
  // Why the windows ended short of the goal, a short key for PlanStop::reason (time_limit,
  // no_progress, stuck, window_failed, window_infeasible, window_inexact; empty: the step
  // or window budget ran out).
  std::string end_reason;
  // Progress (NoteProgress): the best point so far (the start stance at first), the way
  // it had left, the window that reached it, and the accepted windows since the last gain.
  Snapshot best;
  std::vector<Footstep> best_footsteps;
  double best_remaining_m = 0.0;
  int best_window = 0;
  double gain_anchor_m = 0.0;  // the way left at the last gain
  int windows_without_progress = 0;

 private:
  void Restore(const Snapshot& s);
  void UpdateGoalReached();
};

}  // namespace mfp

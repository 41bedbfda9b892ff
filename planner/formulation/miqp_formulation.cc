#include "planner/formulation/miqp_formulation.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "base/check.h"
#include "planner/formulation/body_region_faces.h"
#include "planner/formulation/centre_of_contacts.h"
#include "planner/formulation/internal/cost.h"
#include "planner/formulation/internal/footprint_step_boxes.h"
#include "planner/formulation/internal/miqp_encoder.h"
#include "planner/formulation/internal/region_choice.h"
#include "planner/formulation/internal/region_union_hull.h"
#include "planner/formulation/internal/step_expressions.h"
#include "planner/formulation/internal/trimming.h"
#include "planner/formulation/step_limits.h"
#include "planner/formulation/workspace_box.h"
#include "planner/formulation/yaw_change_limit.h"
#include "planner/miqp/miqp_builder.h"

namespace mfp {
namespace {

double WrapToPi(double a) { return std::remainder(a, 2.0 * M_PI); }

// One-of groups in plan order (a configuration's yaw segments, then its steps' regions),
// so that branching rules that follow the group order decide the plan from its start
// outwards; with kSegmentsFirst every configuration's segments come before any region.
std::vector<std::vector<int>> OneOfGroups(const FootstepVariables& vars, int n, int num_steps, GroupOrder order) {
  std::vector<std::vector<int>> groups;
  const int num_configurations = static_cast<int>(vars.segment.size());
  const bool segments_first = order == GroupOrder::kSegmentsFirst;
  if (segments_first) {
    for (int cfg = 0; cfg < num_configurations; ++cfg) {
      if (!vars.segment[cfg].empty()) groups.push_back(vars.segment[cfg]);
    }
  }
  for (int cfg = 0; cfg < num_configurations; ++cfg) {
    if (!segments_first && !vars.segment[cfg].empty()) groups.push_back(vars.segment[cfg]);
    for (int i = std::max(n, cfg * n); i < std::min(num_steps, (cfg + 1) * n); ++i) {
      std::vector<int> members;
      for (int h : vars.region[i]) {
        if (h >= 0) members.push_back(h);
      }
      if (!members.empty()) groups.push_back(members);
    }
    if (cfg < static_cast<int>(vars.body_region.size()) && !vars.body_region[cfg].empty()) {
      groups.push_back(vars.body_region[cfg]);
    }
  }
  return groups;
}

}  // namespace

MiqpFormulation::MiqpFormulation(const FootstepProblem& problem, const FormulationOptions& options,
                                 const Deadline& deadline)
    : problem_(problem), options_(options) {
  MFP_CHECK(problem_.robot != nullptr);
  const RobotModel& robot = *problem_.robot;
  n_ = robot.num_legs();
  // Programmer errors only: user input reaches the formulation through CheckPlanRequest
  // (planner/planning/request_check.h), which names each problem to the user; what is
  // left to check here is what the planner builds (windows, histories) and the options'
  // ranges, which the planner: reader enforces.
  MFP_CHECK_MSG(static_cast<int>(problem_.start_feet_world_m.size()) == n_,
                "start stance has " + std::to_string(problem_.start_feet_world_m.size()) + " feet, robot '" +
                    robot.name + "' has " + std::to_string(n_) + " legs");
  for (const Eigen::Vector3d& f : problem_.start_feet_world_m) MFP_CHECK(f.allFinite());
  MFP_CHECK(std::isfinite(problem_.start_yaw_rad) && std::isfinite(problem_.goal_x_m) &&
            std::isfinite(problem_.goal_y_m) && std::isfinite(problem_.goal_yaw_rad));
  MFP_CHECK(problem_.history_feet_world_m.empty() || static_cast<int>(problem_.history_feet_world_m.size()) == n_);
  MFP_CHECK(problem_.start_step_yaw_rad.empty() || static_cast<int>(problem_.start_step_yaw_rad.size()) == n_);
  MFP_CHECK(problem_.num_new_steps >= 1);
  MFP_CHECK(!problem_.regions.empty());
  MFP_CHECK(options_.yaw_segment_rad > 0.01 && options_.yaw_segment_rad <= M_PI);
  MFP_CHECK(options_.yaw_margin_rad >= 0.0 && options_.yaw_margin_rad <= M_PI);
  num_steps_ = n_ + problem_.num_new_steps;
  num_configurations_ = (num_steps_ + n_ - 1) / n_;
  // Goal yaw unwrapped to within pi of the start so the yaw range is the short way round.
  problem_.goal_yaw_rad =
      problem_.start_yaw_rad + WrapToPi(problem_.goal_yaw_rad - problem_.start_yaw_rad);
  yaw_ = MakeYawGrid(problem_.start_yaw_rad, problem_.goal_yaw_rad, robot.max_yaw_change_rad, num_configurations_, options_);

  Build(deadline);
}

int MiqpFormulation::LegOfStep(int step) const { return mfp::LegOfStep(problem_, step); }

Eigen::Vector2d MiqpFormulation::GoalFoot(int leg) const { return mfp::GoalFoot(problem_, leg); }

void MiqpFormulation::Build(const Deadline& deadline) {
  const RobotModel& robot = *problem_.robot;
  out_of_time_ = deadline.Expired();
  if (out_of_time_) return;
  MiqpBuilder b;
  const StepExpressions e(problem_, vars_);
  MiqpEncoder encoder(e, &b);
  const Box3 box = MakeWorkspaceBox(problem_.regions, problem_.start_feet_world_m);
  AddFootstepPositions(box, num_steps_, n_, &b, &vars_);
  AddCentreOfContacts(e, box, num_steps_, &b, &vars_);
  AddYawVariables(yaw_, &b, &vars_);
  for (int cfg = 1; cfg < num_configurations_; ++cfg) {
    AddYawChords(e, yaw_, cfg, options_.yaw_encoding, &b, &vars_);
    AddYawChangeLimit(encoder, robot, cfg);
  }
  for (int i = n_; i < num_steps_; ++i) AddStepLimits(encoder, robot, i);
  const std::vector<double> max_move_xy = MaxMovesXY(e, robot, num_steps_);
  AddTrimming(e, robot, max_move_xy, num_steps_, options_.monotone_trimming, &b, &vars_);
  if (options_.trimmed_configurations_hold_yaw) {
    AddTrimmedConfigurationsHoldYaw(e, robot, num_configurations_, vars_, &b);
  }
  // The footprint's moves (its polygon's diameter) reach far past where its rows let a
  // later step be: its regions are pruned by the rows' boxes too.
  const std::vector<Eigen::AlignedBox2d> step_boxes =
      robot.reach_shape == ReachShape::kFootprint && options_.prune_unreachable_regions
          ? FootprintStepBoxes(e, b, robot, num_steps_)
          : std::vector<Eigen::AlignedBox2d>{};
  RegionChoiceRows regions =
      AddRegionChoice(e, problem_, options_, box, max_move_xy, step_boxes, num_steps_, &b, &vars_, deadline);
  out_of_time_ = regions.out_of_time || deadline.Expired();
  if (out_of_time_) return;
  region_rows_ = std::move(regions.rows);
  infeasible_reason_ = std::move(regions.infeasible_reason);
  AddBodyRegionChoice(encoder, problem_, options_, ChordPointError(LargestSegment(yaw_.breakpoints)), box, num_steps_,
                      &b, &vars_);
  AddCost(e, problem_, num_steps_, num_configurations_, vars_, &b);
  miqp_ = b.Build();
  miqp_.sos1_groups = OneOfGroups(vars_, n_, num_steps_, options_.group_order);
}

Miqp MiqpFormulation::WithRegionsRelaxedFrom(int first_step) const {
  first_step = std::max(first_step, n_);
  if (first_step >= num_steps_) return miqp_;
  Miqp out = miqp_;
  std::vector<bool> dropped(miqp_.num_rows(), false);
  for (int i = first_step; i < num_steps_; ++i) {
    for (int row = region_rows_[i].first; row < region_rows_[i].second; ++row) dropped[row] = true;
  }
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<double> row_lo, row_hi;
  out.row_names.clear();
  for (int row = 0; row < miqp_.num_rows(); ++row) {
    if (dropped[row]) continue;
    const int out_row = static_cast<int>(row_lo.size());
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(miqp_.A, row); it; ++it) {
      triplets.emplace_back(out_row, static_cast<int>(it.col()), it.value());
    }
    row_lo.push_back(miqp_.row_lower(row));
    row_hi.push_back(miqp_.row_upper(row));
    out.row_names.push_back(miqp_.row_names[row]);
  }
  for (int i = first_step; i < num_steps_; ++i) {
    if (region_rows_[i].first < 0) continue;  // reaches no region: the model is infeasible anyway
    std::vector<const ConvexRegion*> reachable;
    for (size_t r = 0; r < problem_.regions.size(); ++r) {
      const int h = vars_.region[i][r];
      if (h < 0) continue;
      reachable.push_back(&problem_.regions[r]);
      out.var_lower(h) = out.var_upper(h) = 0.0;
      const int copy = vars_.region_copy[i][r];  // convex-hull encoding only
      for (int axis = 0; copy >= 0 && axis < 3; ++axis) out.var_lower(copy + axis) = out.var_upper(copy + axis) = 0.0;
    }
    const RegionUnionHull hull = HullOfRegions(reachable);
    for (int k = 0; k < hull.A.rows(); ++k) {
      const int out_row = static_cast<int>(row_lo.size());
      if (hull.A(k, 0) != 0.0) triplets.emplace_back(out_row, vars_.x[i], hull.A(k, 0));
      if (hull.A(k, 1) != 0.0) triplets.emplace_back(out_row, vars_.y[i], hull.A(k, 1));
      row_lo.push_back(-kInfinity);
      row_hi.push_back(hull.b(k));
      out.row_names.push_back("union_hull_" + std::to_string(i) + "_" + std::to_string(k));
    }
    out.var_lower(vars_.z[i]) = std::max(out.var_lower(vars_.z[i]), hull.z_lower_m);
    out.var_upper(vars_.z[i]) = std::min(out.var_upper(vars_.z[i]), hull.z_upper_m);
  }
  out.A.resize(static_cast<Eigen::Index>(row_lo.size()), miqp_.num_variables());
  out.A.setFromTriplets(triplets.begin(), triplets.end());
  out.row_lower = Eigen::Map<const Eigen::VectorXd>(row_lo.data(), static_cast<Eigen::Index>(row_lo.size()));
  out.row_upper = Eigen::Map<const Eigen::VectorXd>(row_hi.data(), static_cast<Eigen::Index>(row_hi.size()));
  return out;
}

bool MiqpFormulation::SnapYawToOneSegment(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                          Eigen::VectorXd* x_ptr) const {
  Eigen::VectorXd& x = *x_ptr;
  MFP_CHECK(x.size() == miqp_.num_variables());
  // Accuracy of a relaxation point: chords and breakpoints are met to about this.
  constexpr double kTolerance = 1e-6;
  bool changed = false;
  for (int cfg = 1; cfg < num_configurations_; ++cfg) {
    const std::vector<int>& seg = vars_.segment[cfg];
    const int K = static_cast<int>(seg.size());
    bool integral = true;
    for (int k = 0; k < K; ++k) integral = integral && std::min(x(seg[k]), 1.0 - x(seg[k])) <= 1e-9;
    if (integral) continue;
    const std::vector<double>& bp = yaw_.configuration_breakpoints[cfg];
    const double theta = x(vars_.theta[cfg]), s = x(vars_.s[cfg]), c = x(vars_.c[cfg]);
    int chosen = -1;
    for (int k = 0; k < K; ++k) {
      if (upper(seg[k]) < 0.5 || theta < bp[k] - kTolerance || theta > bp[k + 1] + kTolerance) continue;
      const double t = std::clamp(theta, bp[k], bp[k + 1]);
      if (std::abs(s - ChordOf(true, bp[k], bp[k + 1]).At(t)) > kTolerance ||
          std::abs(c - ChordOf(false, bp[k], bp[k + 1]).At(t)) > kTolerance) {
        continue;
      }
      if (chosen < 0 || x(seg[k]) > x(seg[chosen])) chosen = k;
    }
    if (chosen < 0) continue;
    bool allowed = true;  // the other segments must be allowed to be 0
    for (int k = 0; k < K; ++k) allowed = allowed && (k == chosen || lower(seg[k]) < 0.5);
    if (!allowed) continue;
    for (int k = 0; k < K; ++k) {
      x(seg[k]) = k == chosen ? 1.0 : 0.0;
      if (!vars_.segment_theta[cfg].empty()) x(vars_.segment_theta[cfg][k]) = k == chosen ? theta : 0.0;
    }
    changed = true;
  }
  return changed;
}

std::vector<Footstep> MiqpFormulation::ExtractFootsteps(const Eigen::VectorXd& x) const {
  MFP_CHECK(x.size() == miqp_.num_variables());
  std::vector<Footstep> steps;
  for (int i = 0; i < num_steps_; ++i) {
    Footstep f;
    f.index = i;
    f.leg = LegOfStep(i);
    if (i < n_) {
      f.position_world_m = problem_.start_feet_world_m[i];
      f.yaw_rad = problem_.start_yaw_rad;
      const int r = FindRegionBelow(problem_.regions, f.position_world_m.x(), f.position_world_m.y(), 1e-3);
      f.region_id = r >= 0 ? problem_.regions[r].id : -1;
    } else {
      f.position_world_m = Eigen::Vector3d(x(vars_.x[i]), x(vars_.y[i]), x(vars_.z[i]));
      f.yaw_rad = x(vars_.theta[i / n_]);
      double best = -1.0;
      for (size_t r = 0; r < problem_.regions.size(); ++r) {
        const int h = vars_.region[i][r];
        if (h >= 0 && x(h) > best) {
          best = x(h);
          f.region_id = problem_.regions[r].id;
        }
      }
    }
    steps.push_back(f);
  }
  return steps;
}

int MiqpFormulation::CountUntrimmedSteps(const Eigen::VectorXd& x) const {
  int count = 0;
  for (int i = n_; i < num_steps_; ++i) count += x(vars_.trim[i]) < 0.5 ? 1 : 0;
  return count;
}

std::vector<Eigen::VectorXd> MiqpFormulation::RoundAlongPlan(const Eigen::VectorXd& relaxed) const {
  MFP_CHECK(relaxed.size() == miqp_.num_variables());
  int first_trimmed = num_steps_;
  for (int i = num_steps_ - 1; i >= n_; --i) {
    if (relaxed(vars_.trim[i]) >= 0.5) first_trimmed = i;
  }
  std::vector<Eigen::VectorXd> proposals;
  for (int trim_from : {first_trimmed, num_steps_}) {
    Eigen::VectorXd rounded;
    if (RoundWithTrimming(relaxed, trim_from, &rounded)) proposals.push_back(rounded);
    if (first_trimmed == num_steps_) break;  // both proposals would be the same
  }
  return proposals;
}

bool MiqpFormulation::RoundWithTrimming(const Eigen::VectorXd& relaxed, int first_trimmed,
                                        Eigen::VectorXd* rounded) const {
  *rounded = relaxed;
  // Yaw: the segment that contains the relaxed yaw.
  for (int cfg = 1; cfg < num_configurations_; ++cfg) {
    const int K = static_cast<int>(vars_.segment[cfg].size());
    const int chosen = SegmentHolding(yaw_.configuration_breakpoints[cfg], relaxed(vars_.theta[cfg]));
    for (int k = 0; k < K; ++k) (*rounded)(vars_.segment[cfg][k]) = k == chosen ? 1.0 : 0.0;
  }
  for (int i = n_; i < num_steps_; ++i) (*rounded)(vars_.trim[i]) = i >= first_trimmed ? 1.0 : 0.0;
  // Regions: a trimmed step keeps the region of the foot it stays on. Otherwise, among
  // the regions whose polygon holds the relaxed foot, the one with the largest weight;
  // when none holds it, the largest weight overall.
  std::vector<int> chosen_region(num_steps_, -1);
  for (int i = 0; i < n_; ++i) {
    const Eigen::Vector3d& f = problem_.start_feet_world_m[i];
    chosen_region[i] = FindRegionBelow(problem_.regions, f.x(), f.y(), 1e-3);
  }
  for (int i = n_; i < num_steps_; ++i) {
    const Eigen::Vector3d f(relaxed(vars_.x[i]), relaxed(vars_.y[i]), relaxed(vars_.z[i]));
    int best = -1;
    const int kept = chosen_region[i - n_];
    if ((*rounded)(vars_.trim[i]) > 0.5 && kept >= 0 && vars_.region[i][kept] >= 0) {
      best = kept;
    } else {
      // Regions that hold the foot first, then by weight, then (where weights tie, as
      // they do for steps whose region choice was relaxed to a hull, all of weight 0)
      // the nearer first.
      std::tuple<bool, double, double> best_key(false, -kInfinity, -kInfinity);
      for (size_t r = 0; r < problem_.regions.size(); ++r) {
        const int h = vars_.region[i][r];
        if (h < 0) continue;
        const double violation = RegionViolation(problem_.regions[r], f);
        const std::tuple<bool, double, double> key(violation <= 1e-6, relaxed(h), -violation);
        if (best < 0 || key > best_key) {
          best_key = key;
          best = static_cast<int>(r);
        }
      }
    }
    if (best < 0) return false;
    chosen_region[i] = best;
    for (size_t r = 0; r < problem_.regions.size(); ++r) {
      const int h = vars_.region[i][r];
      if (h >= 0) (*rounded)(h) = static_cast<int>(r) == best ? 1.0 : 0.0;
    }
  }
  // Body regions: the one that holds the configuration's body boxes at the relaxed point.
  for (int cfg = 1; cfg < static_cast<int>(vars_.body_region.size()) && !vars_.body_region[cfg].empty(); ++cfg) {
    const int chosen = BodyRegionHolding(problem_, vars_, relaxed, cfg, num_steps_);
    for (size_t r = 0; r < vars_.body_region[cfg].size(); ++r) {
      (*rounded)(vars_.body_region[cfg][r]) = static_cast<int>(r) == chosen ? 1.0 : 0.0;
    }
  }
  return true;
}

}  // namespace mfp

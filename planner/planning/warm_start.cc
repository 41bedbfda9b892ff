#include "planner/planning/internal/warm_start.h"

#include <limits>
#include <utility>

#include "planner/qp/fixed_integer_qp.h"

namespace mfp {

WarmStart WarmStartFrom(const MiqpFormulation& formulation, const std::vector<Footstep>& previous,
                        double match_tolerance_m) {
  const int n = formulation.num_legs();
  const FootstepProblem& problem = formulation.problem();
  const FootstepVariables& vars = formulation.vars();
  WarmStart warm;
  if (static_cast<int>(previous.size()) <= n) return warm;

  // Each leg's footsteps in the previous plan, in plan order, and where its start foot is.
  std::vector<std::vector<const Footstep*>> by_leg(static_cast<size_t>(n));
  for (const Footstep& f : previous) {
    if (f.leg < 0 || f.leg >= n) return warm;
    by_leg[static_cast<size_t>(f.leg)].push_back(&f);
  }
  std::vector<size_t> next(static_cast<size_t>(n));  // per leg: its first footstep ahead
  for (int i = 0; i < n; ++i) {
    const int leg = formulation.LegOfStep(i);
    const std::vector<const Footstep*>& steps = by_leg[static_cast<size_t>(leg)];
    double best = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < steps.size(); ++k) {
      const double d = (steps[k]->position_world_m - problem.start_feet_world_m[static_cast<size_t>(i)]).norm();
      if (d <= best) {
        best = d;
        next[static_cast<size_t>(leg)] = k + 1;
      }
    }
    if (!(best <= match_tolerance_m)) return warm;
  }
  warm.stance_matched = true;

  // A point of the window's variables with every new foot and configuration yaw placed
  // where the previous plan (or its extrapolation) puts them.
  const Miqp& miqp = formulation.miqp();
  Eigen::VectorXd point = Eigen::VectorXd::Zero(miqp.num_variables());
  bool followed_any = false;
  for (int i = n; i < formulation.num_steps(); ++i) {
    const int leg = formulation.LegOfStep(i);
    const std::vector<const Footstep*>& steps = by_leg[static_cast<size_t>(leg)];
    size_t& k = next[static_cast<size_t>(leg)];
    Eigen::Vector3d foot;
    double yaw = 0.0;
    bool extrapolated = false;
    if (k < steps.size()) {
      foot = steps[k]->position_world_m;
      yaw = steps[k]->yaw_rad;
      followed_any = true;
    } else {
      // Past the previous plan's end: the leg repeats its last step.
      const Footstep& last = *steps.back();
      const Footstep& before = steps.size() >= 2 ? *steps[steps.size() - 2] : last;
      const size_t beyond = k - steps.size() + 1;
      foot = last.position_world_m + static_cast<double>(beyond) * (last.position_world_m - before.position_world_m);
      yaw = last.yaw_rad + static_cast<double>(beyond) * (last.yaw_rad - before.yaw_rad);
      extrapolated = true;
    }
    ++k;
    point(vars.x[i]) = foot.x();
    point(vars.y[i]) = foot.y();
    point(vars.z[i]) = foot.z();
    point(vars.trim[i]) = extrapolated ? 1.0 : 0.0;
    const int cfg = formulation.ConfigurationOfStep(i);
    if (i % n == 0 && vars.theta[cfg] >= 0) point(vars.theta[cfg]) = yaw;
  }
  if (!followed_any) return warm;
  // Trimming must be a suffix: a followed step after an extrapolated one un-trims.
  for (int i = formulation.num_steps() - 2; i >= n; --i) {
    if (point(vars.trim[i + 1]) < 0.5) point(vars.trim[i]) = 0.0;
  }
  warm.proposals = formulation.RoundAlongPlan(point);
  // And with the last configuration trimmed, in case its steps fit no longer.
  const int last = formulation.num_steps() - n;
  if (last > n && point(vars.trim[last]) < 0.5) {
    for (int i = last; i < formulation.num_steps(); ++i) point(vars.trim[i]) = 1.0;
    for (Eigen::VectorXd& x : formulation.RoundAlongPlan(point)) warm.proposals.push_back(std::move(x));
  }
  return warm;
}

std::optional<Eigen::VectorXd> SolveWarmStart(const MiqpFormulation& formulation,
                                              const std::vector<Eigen::VectorXd>& proposals,
                                              RelaxationSolver& solver, const Deadline& deadline,
                                              double feasibility_tolerance) {
  RelaxationRequest request;
  request.deadline = deadline;
  FixedAssignmentOptions options;
  options.feasibility_tolerance = feasibility_tolerance;
  options.max_solve_s = 1.0;  // no one QP longer than a second
  options.acceptable = [&formulation](const Eigen::VectorXd& x) { return formulation.CountUntrimmedSteps(x) > 0; };
  return BestFixedAssignment(formulation.miqp(), proposals, solver, request, options);
}

}  // namespace mfp

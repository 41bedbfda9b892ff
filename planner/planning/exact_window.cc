#include "planner/planning/internal/exact_window.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>

#include "planner/planning/internal/goal_keeping.h"
#include "planner/qp/fixed_integer_qp.h"

namespace mfp {

namespace {
// Beyond the chords' error: the search's integrality and row tolerances let a solution's
// (s, c) stray from the chord by about 1e-6 x the offset; 2e-6 m covers it.
constexpr double kSolutionTolerance_m = 2e-6;

// window_x (a point of the window's MIQP) carried over to the shrunk MIQP by variable
// name; nullopt when an integer set to 1 has no counterpart (a region the shrunk reach
// pruned). Variables of the shrunk MIQP without one start at 0.
std::optional<Eigen::VectorXd> CarryOver(const Miqp& from, const Miqp& to, const Eigen::VectorXd& x) {
  std::unordered_map<std::string, int> index;
  for (int j = 0; j < from.num_variables(); ++j) index.emplace(from.var_names[j], j);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(to.num_variables());
  int carried_ones = 0;
  for (int j = 0; j < to.num_variables(); ++j) {
    const auto it = index.find(to.var_names[j]);
    if (it == index.end()) continue;
    out(j) = x(it->second);
    if (to.is_integer[j] && std::round(out(j)) == 1.0) ++carried_ones;
  }
  int ones = 0;
  for (int j = 0; j < from.num_variables(); ++j) ones += from.is_integer[j] && std::round(x(j)) == 1.0 ? 1 : 0;
  if (carried_ones != ones) return std::nullopt;
  return out;
}

// The window's assignment completed on the shrunk MIQP, by `deadline` (the plan's,
// extended by polish.completion_overrun, with its stop flag).
std::optional<Eigen::VectorXd> CompleteOnShrunk(const MiqpFormulation& formulation, const MiqpFormulation& shrunk,
                                                const Eigen::VectorXd* window_x, RelaxationSolver& solver,
                                                const Deadline& deadline, double feasibility_tolerance) {
  if (window_x == nullptr || window_x->size() != formulation.miqp().num_variables()) return std::nullopt;
  const std::optional<Eigen::VectorXd> assignment = CarryOver(formulation.miqp(), shrunk.miqp(), *window_x);
  if (!assignment) return std::nullopt;
  RelaxationRequest request;
  request.warm_start = *assignment;
  request.deadline = deadline;
  FixedAssignmentOptions options;
  options.feasibility_tolerance = feasibility_tolerance;
  return BestFixedAssignment(shrunk.miqp(), {*assignment}, solver, request, options);
}

}  // namespace

ExactReplan ReplanWithinChordError(const MiqpFormulation& formulation, const std::vector<RelaxationSolver*>& solvers,
                                   const BranchAndBoundOptions& bnb, const PolishOptions& polish,
                                   const Eigen::VectorXd* window_x, const GoalSpec* keep_goal) {
  ExactReplan out;
  out.shrink_m = ChordErrorBound(formulation) + kSolutionTolerance_m;
  out.robot = std::make_unique<RobotModel>(*formulation.problem().robot);
  std::ostringstream note;
  note.precision(3);
  note << "re-planned with l_bnd and d_lim shrunk by " << out.shrink_m << " m (the chords' error)";
  if (out.robot->l_bnd_m <= out.shrink_m || out.robot->d_lim_m <= out.shrink_m) {
    note << ": the boxes vanish";
    out.note = note.str();
    return out;
  }
  out.robot->l_bnd_m -= out.shrink_m;
  out.robot->d_lim_m -= out.shrink_m;
  for (LegModel& leg : out.robot->legs) {
    for (ReachFace& face : leg.footprint_faces) face.offset_m = std::max(1e-6, face.offset_m - out.shrink_m);
  }
  FootstepProblem problem = formulation.problem();
  problem.robot = out.robot.get();
  // Its build belongs to the completion's time when the search has none (below).
  const Deadline completion = bnb.deadline.ExtendedBy(polish.completion_overrun_s);
  out.formulation = std::make_unique<MiqpFormulation>(problem, formulation.options(), completion);
  if (out.formulation->out_of_time()) {
    note << ": " << (completion.Stopped() ? "stopped" : "out of time") << " while its MIQP was built";
    out.note = note.str();
    return out;
  }
  if (!out.formulation->infeasible_reason().empty()) {
    note << ": " << out.formulation->infeasible_reason();
    out.note = note.str();
    return out;
  }
  const MiqpFormulation& shrunk = *out.formulation;
  const RoundingHeuristic rounding = [&shrunk](const Eigen::VectorXd& relaxed) { return shrunk.RoundAlongPlan(relaxed); };
  BranchAndBoundOptions search = bnb;
  search.root_heuristic = nullptr;  // a window's root heuristics belong to its own formulation
  search.first_plan_heuristic = nullptr;
  if (search.equivalent_point) {  // the window's snap belongs to its own formulation
    search.equivalent_point = [&shrunk](const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, Eigen::VectorXd* x) {
      return shrunk.SnapYawToOneSegment(lower, upper, x);
    };
  }
  search.recertify_within = keep_goal != nullptr ? GoalKeeping(shrunk, *keep_goal) : nullptr;
  out.result = SolveBranchAndBound(shrunk.miqp(), solvers, search, rounding);
  // Polished against the true boxes when the two MIQPs share their variables (the
  // shrunk solution is then a point of the true one), else against the shrunk boxes.
  const bool same_layout = shrunk.miqp().num_variables() == formulation.miqp().num_variables() &&
                           shrunk.miqp().var_names == formulation.miqp().var_names &&
                           shrunk.vars().region == formulation.vars().region &&
                           shrunk.vars().theta == formulation.vars().theta && shrunk.vars().trim == formulation.vars().trim;
  // Only when the caller's time is up: with time left, a window without an exact plan is
  // better retried by the caller (a longer look from the window before), which the
  // completion would pre-empt with a plan that may go nowhere.
  if (!HasPlan(out.result.status) && out.result.status != SolveStatus::kInfeasible && search.deadline.Expired()) {
    if (std::optional<Eigen::VectorXd> x =
            CompleteOnShrunk(formulation, shrunk, window_x, *solvers.front(), completion, search.feasibility_tolerance)) {
      out.result.objective = shrunk.miqp().Objective(*x);
      out.result.x = std::move(*x);
      out.result.status = SolveStatus::kFeasible;
      out.result.gap = kInfinity;
      note << ": the window's own choices completed";
    }
  }
  if (!HasPlan(out.result.status)) {
    note << ": " << ToString(out.result.status) << " after " << out.result.nodes << " nodes";
    out.note = note.str();
    return out;
  }
  out.planned = true;
  out.polished = PolishWindow(same_layout ? formulation : shrunk, out.result.x, polish);
  if (!out.polished.report.exact) {
    // The shrunk MIQP's own footsteps meet the true boxes by construction.
    out.polished.footsteps = shrunk.ExtractFootsteps(out.result.x);
    out.polished.report.exact = true;
    out.polished.report.message.clear();
  }
  note << ": " << ToString(out.result.status) << ", objective " << out.result.objective;
  out.note = note.str();
  return out;
}

}  // namespace mfp

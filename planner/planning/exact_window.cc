#include "planner/planning/exact_window.h"

#include <sstream>

namespace mfp {

namespace {
// Beyond the chords' error: the search's integrality and row tolerances let a solution's
// (s, c) stray from the chord by about 1e-6 x the offset; 2e-6 m covers it.
constexpr double kSolutionTolerance_m = 2e-6;
}  // namespace

ExactReplan ReplanWithinChordError(const MiqpFormulation& formulation, const std::vector<RelaxationSolver*>& solvers,
                                   const BranchAndBoundOptions& bnb, const PolishOptions& polish) {
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
  FootstepProblem problem = formulation.problem();
  problem.robot = out.robot.get();
  out.formulation = std::make_unique<MiqpFormulation>(problem, formulation.options());
  if (!out.formulation->infeasible_reason().empty()) {
    note << ": " << out.formulation->infeasible_reason();
    out.note = note.str();
    return out;
  }
  const MiqpFormulation& shrunk = *out.formulation;
  const RoundingHeuristic rounding = [&shrunk](const Eigen::VectorXd& relaxed) { return shrunk.RoundAlongPlan(relaxed); };
  BranchAndBoundOptions search = bnb;
  search.root_heuristic = nullptr;  // a window's root heuristic belongs to its own formulation
  if (search.equivalent_point) {  // the window's snap belongs to its own formulation
    search.equivalent_point = [&shrunk](const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, Eigen::VectorXd* x) {
      return shrunk.SnapYawToOneSegment(lower, upper, x);
    };
  }
  out.result = SolveBranchAndBound(shrunk.miqp(), solvers, search, rounding);
  if (!HasPlan(out.result.status)) {
    note << ": " << ToString(out.result.status) << " after " << out.result.nodes << " nodes";
    out.note = note.str();
    return out;
  }
  out.planned = true;
  // Polished against the true boxes when the two MIQPs share their variables (the
  // shrunk solution is then a point of the true one), else against the shrunk boxes.
  const bool same_layout = shrunk.miqp().num_variables() == formulation.miqp().num_variables() &&
                           shrunk.miqp().var_names == formulation.miqp().var_names &&
                           shrunk.vars().region == formulation.vars().region &&
                           shrunk.vars().theta == formulation.vars().theta && shrunk.vars().trim == formulation.vars().trim;
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

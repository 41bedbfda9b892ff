#include "planner/formulation/internal/region_choice.h"

#include <sstream>

#include "planner/formulation/internal/miqp_encoder.h"
#include "planner/formulation/region_faces.h"

namespace mfp {
namespace {

// Adds the rows of H => A f <= b for one step and region in the chosen encoding.
void AddRegionRows(const StepExpressions& e, const ConvexRegion& region, RegionEncoding encoding, const Box3& box,
                   int i, int r, int h, MiqpBuilder* b, FootstepVariables* vars) {
  const std::string tag = std::to_string(i) + "_" + std::to_string(region.id);
  if (encoding == RegionEncoding::kBigM) {
    MiqpEncoder encoder(e, b);
    AddRegionFaces(encoder, region, i, h, box);
    return;
  }
  // Disaggregated copies f_ir with A_r f_ir <= b_r H_ir and box bounds scaled by H.
  const int first = b->num_variables();
  vars->region_copy[i][r] = first;
  for (int axis = 0; axis < 3; ++axis) {
    const double lo_a = std::min(0.0, box.lo(axis)), hi_a = std::max(0.0, box.hi(axis));
    const int v = b->AddVariable("F_" + tag + "_" + "xyz"[axis], lo_a, hi_a, false);
    b->AddRow("F_lo_" + tag + "_" + "xyz"[axis], LinExpr::Var(v) - LinExpr::Var(h, box.lo(axis)), 0.0, kInfinity);
    b->AddRow("F_hi_" + tag + "_" + "xyz"[axis], LinExpr::Var(v) - LinExpr::Var(h, box.hi(axis)), -kInfinity, 0.0);
  }
  for (int row = 0; row < region.A.rows(); ++row) {
    LinExpr af;
    for (int axis = 0; axis < 3; ++axis) af += LinExpr::Var(first + axis, region.A(row, axis));
    b->AddRow("hull_" + tag + "_" + std::to_string(row), af - LinExpr::Var(h, region.b(row)), -kInfinity, 0.0);
  }
}

}  // namespace

RegionChoiceRows AddRegionChoice(const StepExpressions& e, const FootstepProblem& problem,
                                 const FormulationOptions& options, const Box3& box,
                                 const std::vector<double>& max_move_xy,
                                 const std::vector<Eigen::AlignedBox2d>& step_boxes, int num_steps, MiqpBuilder* b,
                                 FootstepVariables* vars, const Deadline& deadline) {
  const int n = e.num_legs();
  const int N = num_steps;
  const RobotModel& robot = *problem.robot;
  const int R = static_cast<int>(problem.regions.size());
  vars->region.assign(N, std::vector<int>(R, -1));
  vars->region_copy.assign(N, std::vector<int>(R, -1));
  // Moves of each leg so far bound how far step i can be from that leg's start foot.
  std::vector<double> reach_xy(N, 0.0), reach_z(N, 0.0);
  for (int i = n; i < N; ++i) {
    reach_xy[i] = (i - n < n ? 0.0 : reach_xy[i - n]) + max_move_xy[i];
    reach_z[i] = (i - n < n ? 0.0 : reach_z[i - n]) + robot.dz_max_m;
  }
  RegionChoiceRows out;
  out.rows.assign(N, {-1, -1});
  for (int i = n; i < N; ++i) {
    if (deadline.Expired()) {
      out.out_of_time = true;
      return out;
    }
    const Eigen::Vector3d& start_foot = problem.start_feet_world_m[(i - n) % n];
    const int first_region_row = b->num_rows();
    LinExpr one_region;
    std::vector<int> members;
    for (int r = 0; r < R; ++r) {
      const ConvexRegion& region = problem.regions[r];
      if (options.prune_unreachable_regions) {
        Box3 rb;
        for (const Eigen::Vector3d& v : region.vertices_world_m) rb.Add(v);
        const double tol = region.plane_tolerance_m + 1e-6;
        const bool reachable =
            rb.lo.x() <= start_foot.x() + reach_xy[i] && rb.hi.x() >= start_foot.x() - reach_xy[i] &&
            rb.lo.y() <= start_foot.y() + reach_xy[i] && rb.hi.y() >= start_foot.y() - reach_xy[i] &&
            rb.lo.z() - tol <= start_foot.z() + reach_z[i] && rb.hi.z() + tol >= start_foot.z() - reach_z[i];
        if (!reachable) continue;
        if (!step_boxes.empty() && step_boxes[i]
                                       .intersection(Eigen::AlignedBox2d(rb.lo.head<2>() - Eigen::Vector2d::Constant(tol),
                                                                         rb.hi.head<2>() + Eigen::Vector2d::Constant(tol)))
                                       .isEmpty()) {
          continue;
        }
      }
      const int h = b->AddBinary("H_" + std::to_string(i) + "_" + std::to_string(region.id));
      vars->region[i][r] = h;
      members.push_back(h);
      one_region += LinExpr::Var(h);
      AddRegionRows(e, region, options.region_encoding, box, i, r, h, b, vars);
    }
    if (members.empty()) {
      std::ostringstream msg;
      msg << "step " << i << " (leg " << LegOfStep(problem, i) << ") cannot reach any region";
      out.infeasible_reason = msg.str();
      // Keep the model well formed: the empty choice row is left out; the planner
      // reports the reason instead of solving.
      continue;
    }
    b->AddRow(StepName("one_region", i), one_region, 1.0, 1.0);
    if (options.region_encoding == RegionEncoding::kConvexHull) {
      for (int axis = 0; axis < 3; ++axis) {
        LinExpr sum = e.Position(i, axis);
        for (int r = 0; r < R; ++r) {
          if (vars->region_copy[i][r] >= 0) sum -= LinExpr::Var(vars->region_copy[i][r] + axis);
        }
        b->AddRow(std::string("hull_sum_") + "xyz"[axis] + "_" + std::to_string(i), sum, 0.0, 0.0);
      }
    }
    out.rows[i] = {first_region_row, b->num_rows()};
  }
  return out;
}

}  // namespace mfp

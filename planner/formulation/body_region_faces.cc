#include "planner/formulation/body_region_faces.h"

#include <cmath>
#include <string>
#include <tuple>

#include "base/check.h"
#include "planner/formulation/internal/step_expressions.h"

namespace mfp {

bool UsesBodyRegions(const FootstepProblem& problem, const FormulationOptions& options) {
  return options.body_regions && !problem.body_regions.empty() && problem.robot->body.known();
}

std::vector<Eigen::Vector2d> BodyCornersBody(const BodyExtent& body) {
  return {body.min_m, {body.max_m.x(), body.min_m.y()}, body.max_m, {body.min_m.x(), body.max_m.y()}};
}

void AddBodyRegionFaces(StepEncoder& e, const BodyExtent& body, const FreeRegion2d& region, int region_index, int i,
                        int indicator, double chord_error, double margin_m, const Box3& box) {
  const std::vector<Eigen::Vector2d> corners = BodyCornersBody(body);
  for (Eigen::Index f = 0; f < region.A.rows(); ++f) {
    const Eigen::Vector2d a = region.A.row(f).transpose();
    const StepExpr ap = a.x() * e.CentreOfContacts(i, 0) + a.y() * e.CentreOfContacts(i, 1);
    double ap_max = 0.0;  // largest a . p over the box
    for (int axis = 0; axis < 2; ++axis) ap_max += std::max(a(axis) * box.lo(axis), a(axis) * box.hi(axis));
    for (size_t k = 0; k < corners.size(); ++k) {
      const Eigen::Vector2d& c = corners[k];
      // a . R(theta) k = (R(theta) k')_x with k' = R(-alpha) k, alpha the angle of a: one
      // rotated offset, as the polisher's rows take it (subtracted).
      const Eigen::Vector2d turned_back(a.dot(c), a.x() * c.y() - a.y() * c.x());
      const StepExpr expr = ap - e.Rotated(i, -turned_back, 0);
      const double upper = region.b(f) - margin_m - chord_error * c.norm();
      // The chords' (s, c) lie in their bounds' box, within sqrt(2) of the origin.
      const double big_m = ap_max + std::sqrt(2.0) * c.norm() - upper;
      const std::string name = "body_" + std::to_string(i) + "_" + std::to_string(region_index) + "_" +
                               std::to_string(f) + "_" + std::to_string(k);
      e.AddImpliedRow(RowKind::kBodyRegion, name, indicator, expr, upper, big_m);
    }
  }
}

void AddBodyRegionChoice(StepEncoder& e, const FootstepProblem& problem, const FormulationOptions& options,
                         double chord_error, const Box3& box, int num_steps, MiqpBuilder* b, FootstepVariables* vars) {
  const int n = e.num_legs();
  const int B = (num_steps + n - 1) / n;
  vars->body_region.assign(B, {});
  if (!UsesBodyRegions(problem, options)) return;
  const int R = static_cast<int>(problem.body_regions.size());
  for (int cfg = 1; cfg < B; ++cfg) {
    vars->body_region[cfg] = AddExactlyOneBinaries("G", "one_body_region", cfg, R, b);
    for (int i = cfg * n; i < std::min(num_steps, (cfg + 1) * n); ++i) {
      for (int r = 0; r < R; ++r) {
        AddBodyRegionFaces(e, problem.robot->body, problem.body_regions[r], r, i, vars->body_region[cfg][r], chord_error,
                           options.body_margin_m, box);
      }
    }
  }
}

int BodyRegionHolding(const FootstepProblem& problem, const FootstepVariables& vars, const Eigen::VectorXd& x, int cfg,
                      int num_steps) {
  if (cfg >= static_cast<int>(vars.body_region.size()) || vars.body_region[cfg].empty()) return -1;
  const int n = problem.robot->num_legs();
  std::vector<Eigen::Vector2d> corners;
  for (int i = cfg * n; i < std::min(num_steps, (cfg + 1) * n); ++i) {
    for (const Eigen::Vector2d& c : BodyFootprint(problem.robot->body, x(vars.px[i]), x(vars.py[i]), x(vars.theta[cfg]))) {
      corners.push_back(c);
    }
  }
  int best = -1;
  std::tuple<bool, double, double> best_key;
  for (int r = 0; r < static_cast<int>(vars.body_region[cfg].size()); ++r) {
    const double excess = RegionExcess(problem.body_regions[r], corners);
    const std::tuple<bool, double, double> key(excess <= 0.0, x(vars.body_region[cfg][r]), -excess);
    if (best < 0 || key > best_key) {
      best_key = key;
      best = r;
    }
  }
  return best;
}

}  // namespace mfp

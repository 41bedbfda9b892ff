#include "planner/planning/plan_validation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Geometry>

#include "base/check.h"
#include "planner/formulation/centre_of_contacts.h"
#include "planner/formulation/step_encoder.h"
#include "planner/formulation/step_limits.h"
#include "planner/planning/footstep_planner.h"

namespace mfp {
namespace {

// A plan's footsteps as a StepEncoder for the constraint families: every quantity is a
// value (positions before the plan wrap to the start stance; r_nom,j turns the leg's
// offset by the exact R(yaw) of the yaw step j reports), and each row written records
// its excess over its bounds, the largest per kind.
class FootstepRowExcess final : public StepEncoder {
 public:
  FootstepRowExcess(const RobotModel& robot, const std::vector<Footstep>& steps)
      : robot_(robot), steps_(steps), n_(robot.num_legs()) {
    excess_.fill(-std::numeric_limits<double>::infinity());
  }

  int num_legs() const override { return n_; }
  int LegOfStep(int j) const override { return steps_[static_cast<size_t>(std::max(j, 0))].leg; }
  StepExpr Position(int j, int axis) const override { return LinExpr::Constant(Pos(j)(axis)); }
  StepExpr CentreOfContacts(int i, int axis) const override { return LinExpr::Constant(Centre(i)(axis)); }
  StepExpr NominalFoot(int j, int axis) const override {
    const Eigen::Vector2d p = Centre(j);
    const Footstep& step = steps_[std::max(j, 0)];
    return LinExpr::Constant(NominalFootXY(robot_, step.leg, p.x(), p.y(), step.yaw_rad)(axis));
  }
  StepExpr Rotated(int i, const Eigen::Vector2d& offset_body_m, int axis) const override {
    const double yaw = steps_[static_cast<size_t>(i)].yaw_rad;
    const Eigen::Vector2d turned = Eigen::Rotation2Dd(yaw) * offset_body_m;
    return LinExpr::Constant(turned(axis));
  }
  std::pair<double, double> YawBounds(int j) const override {
    const double yaw = steps_[static_cast<size_t>(std::max(j, 0))].yaw_rad;
    return {yaw, yaw};
  }
  StepExpr Yaw(int cfg) const override {
    return LinExpr::Constant(steps_[std::min<size_t>(cfg * n_, steps_.size() - 1)].yaw_rad);
  }
  void AddRow(RowKind kind, const std::string& name, const StepExpr& expr, double lower, double upper) override {
    MFP_CHECK_MSG(expr.lin.terms.empty() && expr.rotations.empty(), name + ": a plan's rows are values");
    const double v = expr.lin.constant;
    double& worst = excess_[static_cast<size_t>(kind)];
    worst = std::max({worst, v - upper, lower - v});
  }
  void AddImpliedRow(RowKind kind, const std::string& name, int /*indicator*/, const StepExpr& expr, double upper,
                     double /*big_m*/) override {
    AddRow(kind, name, expr, -kInfinity, upper);
  }

  // Largest excess of the rows of a kind written so far; -infinity when none.
  double excess(RowKind kind) const { return excess_[static_cast<size_t>(kind)]; }

 private:
  Eigen::Vector3d Pos(int j) const {
    while (j < 0) j += n_;  // before the plan: the start stance
    return steps_[j].position_world_m;
  }
  // The centre of contacts of the n latest footsteps ending at j.
  Eigen::Vector2d Centre(int j) const {
    return mfp::CentreOfContacts<Eigen::Vector2d>(j, n_, [&](int k) { return Eigen::Vector2d(Pos(k).head<2>()); });
  }

  const RobotModel& robot_;
  const std::vector<Footstep>& steps_;
  int n_;
  std::array<double, kNumRowKinds> excess_;
};

// How far step i (i >= n) is beyond each of its limits [m, rad]; <= 0 where it holds.
// region_missing: its region id names no region.
struct StepExcess {
  double region = 0.0, reference = 0.0, reachability = 0.0, height = 0.0, yaw_change = 0.0;
  bool region_missing = false;
};

StepExcess ExcessOfStep(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                        const std::vector<ConvexRegion>& footholds, const std::vector<Footstep>& steps, int i) {
  StepExcess e;
  FootstepRowExcess rows(robot, steps);
  AddStepLimits(rows, robot, i);
  e.reference = rows.excess(RowKind::kReferenceBox);
  e.reachability = rows.excess(RowKind::kReachability);
  e.height = rows.excess(RowKind::kHeightChange);
  // The region and the yaw change per step (not per configuration: a plan whose steps of
  // one configuration report different yaws is caught here).
  const Eigen::Vector3d f = steps[i].position_world_m;
  const ConvexRegion* region = nullptr;
  for (const ConvexRegion& r : regions) {
    if (r.id == steps[i].region_id) region = &r;
  }
  for (const ConvexRegion& r : footholds) {
    if (region == nullptr && r.id == steps[i].region_id) region = &r;
  }
  e.region_missing = region == nullptr;
  e.region = region == nullptr ? 0.0 : RegionViolation(*region, f);
  e.yaw_change = std::abs(steps[i].yaw_rad - steps[i - 1].yaw_rad) - robot.max_yaw_change_rad;
  return e;
}

}  // namespace

ExactExcess MeasureExactExcess(const RobotModel& robot, const std::vector<ConvexRegion>& regions, const Plan& plan) {
  ExactExcess out;
  const int n = robot.num_legs();
  for (int i = n; i < static_cast<int>(plan.footsteps.size()); ++i) {
    const StepExcess e = ExcessOfStep(robot, regions, plan.footholds, plan.footsteps, i);
    out.region_m = std::max(out.region_m, e.region);
    out.reference_box_m = std::max(out.reference_box_m, e.reference);
    out.reachability_box_m = std::max(out.reachability_box_m, e.reachability);
    out.height_m = std::max(out.height_m, e.height);
    out.yaw_change_rad = std::max(out.yaw_change_rad, e.yaw_change);
  }
  return out;
}

std::vector<std::string> ValidatePlan(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                      const Plan& plan, const GoalSpec& goal,
                                      const ValidationTolerances& tol) {
  std::vector<std::string> errors;
  const int n = robot.num_legs();
  const auto& steps = plan.footsteps;
  const int N = static_cast<int>(steps.size());
  auto report = [&](int i, const std::string& what, double excess) {
    std::ostringstream msg;
    msg << "step " << i << " (leg " << (i < N ? steps[i].leg : -1) << "): " << what;
    if (excess > 0) msg << " off by " << excess;
    errors.push_back(msg.str());
  };
  if (N < n) {
    errors.push_back("plan has " + std::to_string(N) + " footsteps, fewer than the " + std::to_string(n) + " of a stance");
    return errors;
  }
  for (int i = 0; i < N; ++i) {
    if (steps[i].leg != robot.gait[i % n]) report(i, "leg out of gait order (expected " + std::to_string(robot.gait[i % n]) + ")", 0);
    if (steps[i].index != i) report(i, "index field is " + std::to_string(steps[i].index), 0);
    if (!steps[i].position_world_m.allFinite() || !std::isfinite(steps[i].yaw_rad)) report(i, "non-finite value", 0);
  }
  if (!errors.empty()) return errors;
  for (int i = n; i < N; ++i) {
    const StepExcess e = ExcessOfStep(robot, regions, plan.footholds, steps, i);
    if (e.region_missing) {
      report(i, "region id " + std::to_string(steps[i].region_id) + " does not exist", 0);
    } else if (e.region > tol.position_m) {
      report(i, "outside region " + std::to_string(steps[i].region_id), e.region);
    }
    // Reference polygon about r_nom,i and reach polygon about r_nom,i-n (the box's l_bnd and
    // d_lim, or the leg's footprint polygon at the step's yaw).
    const double box_tol = tol.position_m;
    const bool footprint = robot.reach_shape == ReachShape::kFootprint;
    if (e.reference > box_tol) report(i, footprint ? "reference footprint polygon" : "reference box l_bnd", e.reference);
    if (e.reachability > box_tol) {
      report(i, footprint ? "reach footprint polygon" : "reachability box d_lim", e.reachability);
    }
    if (e.height > tol.position_m) report(i, "height change dz_max", e.height);
    if (e.yaw_change > tol.yaw_rad) report(i, "yaw change", e.yaw_change);
  }
  if (plan.reaches_goal) {
    const GoalDistances d = DistancesToGoal(robot, steps, goal);
    for (int k = 0; k < n; ++k) {
      const double foot = d.foot_m[k];
      if (foot > goal.tolerance_m + tol.position_m) report(N - n + k, "final foot far from its goal spot", foot - goal.tolerance_m);
    }
    if (d.yaw_rad > goal.yaw_tolerance_rad + tol.yaw_rad) report(N - 1, "final yaw far from the goal yaw", d.yaw_rad - goal.yaw_tolerance_rad);
  }
  return errors;
}

}  // namespace mfp

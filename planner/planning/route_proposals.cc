#include "planner/planning/internal/route_proposals.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "planner/robot/robot_model.h"

namespace mfp {
namespace {

// Heading of the route at arc length s [rad], from a chord a few centimetres long.
double RouteHeading(const RouteGuide& guide, double s_m, double fallback_rad) {
  const Eigen::Vector2d a = RoutePoint(guide, s_m - 0.05);
  const Eigen::Vector2d b = RoutePoint(guide, s_m + 0.05);
  const Eigen::Vector2d d = b - a;
  return d.norm() > 1e-6 ? std::atan2(d.y(), d.x()) : fallback_rad;
}

}  // namespace

std::vector<Eigen::VectorXd> RouteProposals(const MiqpFormulation& formulation, const RouteGuide& guide,
                                            double progress_m, const RouteProposalOptions& options) {
  std::vector<Eigen::VectorXd> proposals;
  if (!guide.connected || guide.route.size() < 2) return proposals;
  const FootstepProblem& problem = formulation.problem();
  const RobotModel& robot = *problem.robot;
  const FootstepVariables& vars = formulation.vars();
  const int n = formulation.num_legs();
  const double start_yaw = problem.start_yaw_rad;
  const double max_turn = options.yaw_rate_fraction * robot.max_yaw_change_rad;
  // A stance off the route by more than l_bnd (a window that swerved round a corner) walks
  // back toward it at the proposal's speed: a body put on the route at once would move
  // each foot farther than a step reaches, and no proposal would fit.
  const Eigen::Vector2d from = StanceCentreXY(problem.start_feet_world_m);
  const bool off_route = (from - RoutePoint(guide, progress_m)).norm() > robot.l_bnd_m;
  // Yaw targets: held, the route's heading ahead, the goal's.
  enum class YawTarget { kHold, kRoute, kGoal };
  for (double fraction : options.advance_fractions) {
    const double advance = fraction * robot.d_lim_m;
    for (YawTarget target : {YawTarget::kHold, YawTarget::kRoute, YawTarget::kGoal}) {
      Eigen::VectorXd point = Eigen::VectorXd::Zero(formulation.miqp().num_variables());
      for (int i = n; i < formulation.num_steps(); ++i) {
        // The body has moved (i - n + 1) / n configurations' worth when step i lands.
        const double configurations = static_cast<double>(i - n + 1) / n;
        const double s = std::min(guide.length_m, progress_m + advance * configurations);
        const int cfg = formulation.ConfigurationOfStep(i);
        double aim = start_yaw;
        if (target == YawTarget::kRoute) aim = RouteHeading(guide, s, start_yaw);
        if (target == YawTarget::kGoal) aim = problem.goal_yaw_rad;
        const double turn = std::clamp(std::remainder(aim - start_yaw, 2 * M_PI), -max_turn * cfg, max_turn * cfg);
        const double yaw = start_yaw + turn;
        Eigen::Vector2d body = RoutePoint(guide, s);
        const double walk = advance * configurations;
        if (off_route && (body - from).norm() > walk) body = from + walk * (body - from).normalized();
        const int leg = formulation.LegOfStep(i);
        const Eigen::Vector2d foot = NominalFootXY(robot, leg, body.x(), body.y(), yaw);
        point(vars.x[i]) = foot.x();
        point(vars.y[i]) = foot.y();
        // Height: that of the region nearest the spot in plan view (RoundAlongPlan's
        // region choice weighs the height rows too).
        double nearest = std::numeric_limits<double>::infinity();
        double z = problem.start_feet_world_m[static_cast<size_t>(i % n)].z();
        for (size_t r = 0; r < problem.regions.size(); ++r) {
          if (vars.region[i][r] < 0) continue;
          const double d = PlanDistanceToRegion(problem.regions[r], foot);
          if (d < nearest) {
            nearest = d;
            z = problem.regions[r].HeightAt(foot.x(), foot.y());
          }
        }
        point(vars.z[i]) = z;
        if (vars.theta[cfg] >= 0) point(vars.theta[cfg]) = yaw;
      }
      for (Eigen::VectorXd& x : formulation.RoundAlongPlan(point)) {
        const bool seen = std::any_of(proposals.begin(), proposals.end(), [&](const Eigen::VectorXd& p) {
          for (int j = 0; j < p.size(); ++j) {
            if (formulation.miqp().is_integer[j] && std::round(p(j)) != std::round(x(j))) return false;
          }
          return true;
        });
        if (!seen) proposals.push_back(std::move(x));
      }
    }
  }
  return proposals;
}

}  // namespace mfp

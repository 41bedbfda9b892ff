#pragma once
// Small hand-made robots shared by the unit tests.
#include <string>

#include "planner/robot/robot_model.h"

namespace mfp {

// Four legs at (+-0.1, +-0.1) m about the centre of contacts, gait 0, 1, 2, 3,
// dz_max 0.1 m, yaw change 0.3 rad, and the given reach boxes [m].
inline RobotModel SquareQuadruped(double d_lim_m, double l_bnd_m) {
  RobotModel robot;
  robot.name = "test_quadruped";
  const double o[4][2] = {{0.1, 0.1}, {0.1, -0.1}, {-0.1, 0.1}, {-0.1, -0.1}};
  for (int k = 0; k < 4; ++k) {
    LegModel leg;
    leg.name = "leg" + std::to_string(k);
    leg.nominal_offset_body_m = Eigen::Vector2d(o[k][0], o[k][1]);
    robot.legs.push_back(leg);
  }
  robot.gait = {0, 1, 2, 3};
  robot.d_lim_m = d_lim_m;
  robot.l_bnd_m = l_bnd_m;
  robot.dz_max_m = 0.1;
  robot.max_yaw_change_rad = 0.3;
  return robot;
}

}  // namespace mfp

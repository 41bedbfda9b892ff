#pragma once
// The nominal foot of a leg (seed paper eq. 3): the centre of contacts p plus the leg's
// nominal offset o (body frame) rotated by the body yaw,
//   r_nom = p + R(yaw) o = (p_x + o_x c - o_y s,  p_y + o_x s + o_y c),
// written in (s, c) = (sin yaw, cos yaw). One definition for every user: the formulation
// puts in its chord variables (T = LinExpr), the goal stance, nominal stances and plan
// validation exact values (T = double).
#include <Eigen/Core>

namespace mfp {

template <class T>
T NominalFootX(const T& p_x, const T& s, const T& c, const Eigen::Vector2d& offset_body_m) {
  return p_x + offset_body_m.x() * c - offset_body_m.y() * s;
}

template <class T>
T NominalFootY(const T& p_y, const T& s, const T& c, const Eigen::Vector2d& offset_body_m) {
  return p_y + offset_body_m.x() * s + offset_body_m.y() * c;
}

}  // namespace mfp

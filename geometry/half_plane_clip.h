#pragma once
// One Sutherland-Hodgman clip of a convex polygon against a half-plane, shared by the
// region geometry (free regions, polygon differences, inset unions) and the convex
// floor cover's side slack.
#include <Eigen/Core>
#include <vector>

namespace mfp {

// The part of a convex polygon where n . p <= c.
std::vector<Eigen::Vector2d> KeepBelowLine(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& n,
                                           double c);
// The same into *out, a buffer the caller keeps (cleared first; must not be polygon).
void KeepBelowLineInto(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& n, double c,
                       std::vector<Eigen::Vector2d>* out);

}  // namespace mfp

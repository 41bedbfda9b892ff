#include "bench/course_generator.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "bench/course_checker.h"
#include "io/body_obstacles.h"
#include "planner/robot/body_clearance.h"

namespace mfp {

namespace {

constexpr double kThick = 0.1;  // slab thickness [m]

struct Gen {
  const RobotModel& robot;
  std::mt19937_64 rng;
  double margin, reach, footprint, dz;
  std::vector<TerrainBox> boxes;
  int count = 0;
  // The course's finest feature the map must resolve: the narrowest gap between
  // footholds, and the least width a foothold keeps beyond its edge margins [m].
  double finest_m = kCourseMaxResolution * kCourseVoxelsPerFeature;
  void Feature(double size_m) { finest_m = std::min(finest_m, size_m); }

  double U(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }

  // A box whose top face is centred at (x, y, top) in a frame turned by heading.
  void Box(double x, double y, double top, double along, double across, double heading, double roll = 0,
           double pitch = 0, double thick = kThick) {
    TerrainBox b;
    b.name = "b" + std::to_string(count++);
    const Eigen::Matrix3d r = (Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    b.center_world_m = Eigen::Vector3d(x, y, top) - r * Eigen::Vector3d(0, 0, thick / 2);
    b.size_m = Eigen::Vector3d(along, across, thick);
    b.rpy_rad = Eigen::Vector3d(roll, pitch, heading);
    boxes.push_back(b);
  }
  // A point at along-coordinate s and lateral t on a segment from (x0, y0) with heading h.
  static Eigen::Vector2d At(double x0, double y0, double h, double s, double t) {
    return Eigen::Vector2d(x0 + s * std::cos(h) - t * std::sin(h), y0 + s * std::sin(h) + t * std::cos(h));
  }
  void Platform(const Eigen::Vector2d& c, double top = 0.0) { Box(c.x(), c.y(), top, 2 * footprint, 2 * footprint, 0); }

  // Foot tracks: the legs' lateral offsets for a body heading along the route, merged
  // where stones of width w would touch. Returns (centre, width) pairs.
  std::vector<std::pair<double, double>> Tracks(double w) {
    std::vector<double> ys;
    for (const auto& leg : robot.legs) ys.push_back(leg.nominal_offset_body_m.y());
    std::sort(ys.begin(), ys.end());
    std::vector<std::pair<double, double>> out;
    double lo = ys[0], hi = ys[0];
    for (size_t i = 1; i <= ys.size(); ++i) {
      if (i < ys.size() && ys[i] - hi < w + 0.05) {
        hi = ys[i];
        continue;
      }
      out.push_back({(lo + hi) / 2, hi - lo + w});
      if (i < ys.size()) lo = hi = ys[i];
    }
    return out;
  }
  // Gaps a foot can step across while every route pose keeps a spot within 0.9 l_bnd.
  double MaxGap() { return std::max(0.01, 2 * (0.9 * robot.l_bnd_m - margin) - 0.005); }
  double MinGap() { return std::min(0.04, 0.5 * MaxGap()); }

  // Stepping stones along each track over along-coordinates [s0, s1] of a segment.
  void Stones(double x0, double y0, double h, double s0, double s1) {
    const double w = 2 * margin + U(0.03, 0.1);
    Feature(MinGap());
    Feature(w - 2 * margin);
    for (const auto& [t, width] : Tracks(w)) {
      double s = s0 + U(MinGap(), MaxGap());
      while (s < s1) {
        double len = U(2 * margin + 0.03, std::max(2 * margin + 0.04, 0.25 * footprint));
        len = std::min(len, s1 - s);
        if (len < 2 * margin + 0.02) break;
        Feature(len - 2 * margin);
        const double jitter = U(-0.3, 0.3) * (width - 2 * margin) / 2 * 0.3;
        const Eigen::Vector2d c = At(x0, y0, h, s + len / 2, t + jitter);
        Box(c.x(), c.y(), U(0.0, 0.5 * dz), len, width, h);
        s += len + U(MinGap(), MaxGap());
      }
    }
  }
  // A slab of the route's width over [s0, s1].
  void Slab(double x0, double y0, double h, double s0, double s1, double top, double roll = 0, double pitch = 0) {
    const Eigen::Vector2d c = At(x0, y0, h, (s0 + s1) / 2, 0);
    Box(c.x(), c.y(), top, s1 - s0, 2 * footprint, h, roll, pitch);
  }
};

// Every pose along the route has, for every leg, a spot on the true surface within
// 0.9 l_bnd (body frame) of the nominal foot: the planner's reference box (l_bnd) about
// the configuration's nominal spot, and consecutive poses 0.5 d_lim apart, within reach.
// Body poses along the route, consecutive ones at most 0.5 d_lim and 0.5 max_yaw_change apart.
std::vector<Pose2D> RoutePoses(const RobotModel& robot, const std::vector<Pose2D>& route) {
  std::vector<Pose2D> poses;
  for (size_t k = 0; k + 1 < route.size(); ++k) {
    const Pose2D& a = route[k];
    const Pose2D& b = route[k + 1];
    const double d = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
    const double dyaw = std::abs(std::remainder(b.yaw_rad - a.yaw_rad, 2 * M_PI));
    const int m = std::max(1, static_cast<int>(std::ceil(std::max(d / (0.5 * robot.d_lim_m),
                                                                  dyaw / (0.5 * robot.max_yaw_change_rad)))));
    for (int j = 0; j < m; ++j) {
      const double u = static_cast<double>(j) / m;
      poses.push_back({a.x_m + u * (b.x_m - a.x_m), a.y_m + u * (b.y_m - a.y_m),
                       a.yaw_rad + u * std::remainder(b.yaw_rad - a.yaw_rad, 2 * M_PI)});
    }
  }
  poses.push_back(route.back());
  return poses;
}

bool RouteHolds(const RobotModel& robot, const TerrainDescription& terrain, const std::vector<Pose2D>& route,
                double margin) {
  const double half = 0.9 * robot.l_bnd_m;
  const double step = half / 3;
  for (const Pose2D& pose : RoutePoses(robot, route)) {
    const Eigen::Rotation2Dd rot(pose.yaw_rad);
    for (int i = 0; i < robot.num_legs(); ++i) {
      const Eigen::Vector2d nom = NominalFootXY(robot, i, pose.x_m, pose.y_m, pose.yaw_rad);
      bool found = false;
      for (double dx = -half; dx <= half + 1e-9 && !found; dx += step) {
        for (double dy = -half; dy <= half + 1e-9 && !found; dy += step) {
          const Eigen::Vector2d p = nom + rot * Eigen::Vector2d(dx, dy);
          for (const TerrainBox& box : terrain.boxes) {
            const Eigen::Matrix3d r = BoxRotation(box);
            if (r(2, 2) < 0.5) continue;
            // Height of the box's top plane at p; only boxes whose top face lies over p count.
            const Eigen::Vector3d n = r.col(2);
            const Eigen::Vector3d ctop = box.center_world_m + n * box.size_m.z() / 2;
            const double z = ctop.z() - (n.x() * (p.x() - ctop.x()) + n.y() * (p.y() - ctop.y())) / n.z();
            const Eigen::Vector3d q = r.transpose() * (Eigen::Vector3d(p.x(), p.y(), z) - box.center_world_m);
            if (std::abs(q.x()) > box.size_m.x() / 2 - margin || std::abs(q.y()) > box.size_m.y() / 2 - margin) continue;
            if (FootOnTrueSurface(terrain, Eigen::Vector3d(p.x(), p.y(), z), margin, robot.max_slope_rad, 1e-4)) {
              found = true;
              break;
            }
          }
        }
      }
      if (!found) return false;
    }
  }
  return true;
}

constexpr double kWallTop = 0.5;    // walls' top above the floor [m]
constexpr double kWallThick = 0.6;  // walls' height (from below the floor) [m]
constexpr double kWallWidth = 0.05; // walls' thickness [m]

// A wall from a to b (plan view) on the floor at z = 0.
void Wall(Gen& g, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d c = 0.5 * (a + b), d = b - a;
  g.Box(c.x(), c.y(), kWallTop, d.norm() + kWallWidth, kWallWidth, std::atan2(d.y(), d.x()), 0, 0, kWallThick);
}
// A floor slab over [x0, x1] x [y0, y1] with its top at z = 0.
void Floor(Gen& g, double x0, double x1, double y0, double y1) {
  g.Box(0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.0, x1 - x0, y1 - y0, 0);
}

// The body-clearance kinds (course_generator.h); false when the robot's body does not
// allow the kind (a door needs a body longer than wide, or wider than long).
bool BodyCourse(Gen& g, CourseKind kind, const RobotModel& robot, std::vector<Pose2D>* route) {
  const BodyExtent& body = robot.body;
  if (!body.known()) return false;
  const double P = g.footprint;
  // The body's circumradius about the centre of contacts: room to turn.
  const double turn_r = std::max({body.min_m.norm(), body.max_m.norm(), Eigen::Vector2d(body.min_m.x(), body.max_m.y()).norm(),
                                  Eigen::Vector2d(body.max_m.x(), body.min_m.y()).norm()});
  const double half_w = std::max(std::abs(body.min_m.y()), std::abs(body.max_m.y()));
  const double half_l = std::max(std::abs(body.min_m.x()), std::abs(body.max_m.x()));
  const double clear = g.U(0.05, 0.12);
  switch (kind) {
    case CourseKind::kPocket: {
      const double inner = std::max(P, half_w + clear);     // pocket's inner half-width
      const double a = std::max(P, half_l) + g.U(0.1, 0.3);  // pocket's mouth
      const double b = a + 2 * std::max(P, half_l) + g.U(0.1, 0.3);  // its back wall
      const double side = inner + kWallWidth + std::max(P, turn_r) + clear;  // the way around
      const double gx = b + kWallWidth + std::max(P, turn_r) + g.U(0.1, 0.3);
      Floor(g, -P, gx + P, -side - P, side + P);
      Wall(g, {a, -inner - kWallWidth / 2}, {b, -inner - kWallWidth / 2});
      Wall(g, {a, inner + kWallWidth / 2}, {b, inner + kWallWidth / 2});
      Wall(g, {b + kWallWidth / 2, -inner - kWallWidth}, {b + kWallWidth / 2, inner + kWallWidth});
      *route = {{0, 0, 0}, {0, -side, 0}, {gx, -side, 0}, {gx, 0, 0}};
      return true;
    }
    case CourseKind::kBaffles: {
      const double gap = 2 * std::max(P, half_w + clear);  // each baffle's opening
      const double yc = gap + std::max(P, half_w) + 0.05;  // corridor half-width
      const double s = 2 * std::max(P, half_l + clear) + kWallWidth;  // baffle spacing
      const double gx = 4 * s;
      Floor(g, -P, gx + P, -yc, yc);
      Wall(g, {-P, -yc - kWallWidth / 2}, {gx + P, -yc - kWallWidth / 2});
      Wall(g, {-P, yc + kWallWidth / 2}, {gx + P, yc + kWallWidth / 2});
      route->push_back({0, 0, 0});
      for (int k = 1; k <= 3; ++k) {
        const double side = (k % 2 == 1) ? 1.0 : -1.0;  // the opening's side
        const double x = k * s;
        Wall(g, {x, -side * yc}, {x, side * (yc - gap)});
        const double y = side * (yc - gap / 2);
        route->push_back({x - s / 2, y, 0});
        route->push_back({x + s / 2, y, 0});
      }
      route->push_back({gx, 0, 0});
      return true;
    }
    case CourseKind::kDoorway:
    case CourseKind::kClosedDoor: {
      const double lo = std::min(2 * half_w, 2 * half_l), hi = std::max(2 * half_w, 2 * half_l);
      if (kind == CourseKind::kDoorway && hi - lo < 0.06) return false;
      // A closed door is narrower than the body's short side at every heading (the feet
      // still step through it).
      const double door = kind == CourseKind::kDoorway ? lo + g.U(0.35, 0.65) * (hi - lo) : g.U(0.3, 0.6) * lo;
      // Facing so that the long side lies across the door (along y).
      const double yaw = half_l > half_w ? M_PI / 2 : 0.0;
      const double pass = half_l > half_w ? 0.0 : M_PI / 2;
      const double room = std::max(P, turn_r) + clear;
      const double wx = room + g.U(0.05, 0.2), gx = wx + room + g.U(0.05, 0.2);
      const double ya = std::max(P, turn_r) + 0.2;
      Floor(g, -room, gx + room, -ya, ya);
      Wall(g, {wx, -ya}, {wx, -door / 2 - kWallWidth / 2});
      Wall(g, {wx, door / 2 + kWallWidth / 2}, {wx, ya});
      *route = {{0, 0, yaw}, {0, 0, pass}, {gx, 0, pass}, {gx, 0, yaw}};
      return true;
    }
    case CourseKind::kCorridor: {
      const double h = std::max(P, turn_r) + clear;  // corridor half-width
      const double cx = h + g.U(1.0, 2.0) * std::max(P, half_l) + 0.3;
      const double gy = h + g.U(1.0, 2.0) * std::max(P, half_l) + 0.3;
      Floor(g, -h, cx + h, -h, h);
      Floor(g, cx - h, cx + h, h, gy + h);
      const double w = kWallWidth / 2;
      Wall(g, {-h, -h - w}, {cx + h + w, -h - w});
      Wall(g, {cx + h + w, -h - w}, {cx + h + w, gy + h});
      Wall(g, {-h, h + w}, {cx - h - w, h + w});
      Wall(g, {cx - h - w, h + w}, {cx - h - w, gy + h});
      *route = {{0, 0, 0}, {cx, 0, 0}, {cx, 0, M_PI / 2}, {cx, gy, M_PI / 2}};
      return true;
    }
    default: return false;
  }
}

}  // namespace

bool BodyRouteClear(const RobotModel& robot, const TerrainDescription& terrain, const std::vector<Pose2D>& route,
                    double ground_z_m) {
  const std::vector<BodyObstacle> boxes = BoxBodyObstacles(terrain.boxes);
  for (const Pose2D& pose : RoutePoses(robot, route)) {
    if (BodyOverlapShare(robot.body, boxes, pose.x_m, pose.y_m, pose.yaw_rad, ground_z_m) > 0.0) return false;
  }
  return true;
}

double MaxFootTravel(const RobotModel& robot) {
  const int n = robot.num_legs();
  return (2 * std::sqrt(2.0) + 1.0) * robot.d_lim_m * n / std::max(1, n - 1);
}

const std::vector<CourseKind>& AllCourseKinds() {
  static const std::vector<CourseKind> kinds = {
      CourseKind::kStones, CourseKind::kStonesTurn, CourseKind::kGaps,   CourseKind::kStairs,
      CourseKind::kTilted, CourseKind::kRough,      CourseKind::kBeams,  CourseKind::kDetour,
      CourseKind::kCutStones, CourseKind::kCutGaps, CourseKind::kWalledGoal, CourseKind::kPocket,
      CourseKind::kBaffles, CourseKind::kDoorway, CourseKind::kCorridor, CourseKind::kClosedDoor};
  return kinds;
}

std::string ToString(CourseKind kind) {
  switch (kind) {
    case CourseKind::kStones: return "stones";
    case CourseKind::kStonesTurn: return "stones_turn";
    case CourseKind::kGaps: return "gaps";
    case CourseKind::kStairs: return "stairs";
    case CourseKind::kTilted: return "tilted";
    case CourseKind::kRough: return "rough_turn";
    case CourseKind::kBeams: return "beams";
    case CourseKind::kDetour: return "wall_detour";
    case CourseKind::kCutStones: return "cut_stones";
    case CourseKind::kCutGaps: return "cut_gaps";
    case CourseKind::kWalledGoal: return "raised_goal";
    case CourseKind::kPocket: return "pocket";
    case CourseKind::kBaffles: return "baffles";
    case CourseKind::kDoorway: return "doorway";
    case CourseKind::kCorridor: return "corridor";
    case CourseKind::kClosedDoor: return "closed_door";
  }
  return "?";
}

namespace {

// One attempt at a course: its generator, the sizes every kind is laid out from, and what
// the kind's builder lays down besides the boxes: the route it was built along, and
// whether a route exists.
struct Attempt {
  Gen g;
  CourseKind kind;
  double P;        // half-side of a start or goal platform (the footprint) [m]
  double reach_r;  // the farthest nominal foot from the body's centre [m]
  double cut;      // a gap wider than any step can cross [m]
  double len = 0;  // the hard section's length [m]
  std::vector<Pose2D> route;
  bool exists = true;
};

// kStones and kCutStones.
void BuildStones(Attempt& a) {
  Gen& g = a.g;
  const double P = a.P;
  g.Platform({0, 0});
  g.Stones(0, 0, 0, P, P + a.len);
  double end = P + a.len;
  if (a.kind == CourseKind::kCutStones) {
    // Remove every stone in a band across the route; the goal side keeps the rest.
    const double c0 = P + g.U(0.3, 0.6) * a.len;
    std::vector<TerrainBox> kept;
    for (const TerrainBox& b : g.boxes) {
      const double bx0 = b.center_world_m.x() - b.size_m.x() / 2, bx1 = b.center_world_m.x() + b.size_m.x() / 2;
      if (bx1 < c0 || bx0 > c0 + a.cut) kept.push_back(b);
    }
    g.boxes = kept;
    a.exists = false;
  }
  g.Platform({end + P + g.U(g.MinGap(), g.MaxGap()), 0});
  const double gx = g.boxes.back().center_world_m.x();
  a.route = {{0, 0, 0}, {gx, 0, 0}};
}

void BuildStonesTurn(Attempt& a) {
  Gen& g = a.g;
  const double P = a.P;
  g.Platform({0, 0});
  g.Stones(0, 0, 0, P, P + a.len);
  const double cx = P + a.len + g.U(g.MinGap(), g.MaxGap()) + P;
  g.Platform({cx, 0});
  const double len2 = g.U(2.0, 3.5) * a.reach_r + 0.3;
  g.Stones(cx, 0, M_PI / 2, P, P + len2);
  const double gy = P + len2 + g.U(g.MinGap(), g.MaxGap()) + P;
  g.Platform({cx, gy});
  a.route = {{0, 0, 0}, {cx, 0, 0}, {cx, 0, M_PI / 2}, {cx, gy, M_PI / 2}};
}

// kGaps and kCutGaps.
void BuildGaps(Attempt& a) {
  Gen& g = a.g;
  const double P = a.P;
  g.Platform({0, 0});
  double s = P + g.U(g.MinGap(), g.MaxGap());
  const double end = P + a.len;
  const int cut_slab = a.kind == CourseKind::kCutGaps ? 1 : -1;
  int k = 0;
  while (s < end) {
    const double l = std::min(end - s, g.U(0.1, 0.35) + 2 * g.margin);
    g.Slab(0, 0, 0, s, s + l, 0.0);
    g.Feature(g.MinGap());
    g.Feature(l - 2 * g.margin);
    s += l + (k == cut_slab ? a.cut : g.U(g.MinGap(), g.MaxGap()));
    ++k;
  }
  a.exists = a.kind != CourseKind::kCutGaps || k < 2;  // the cut follows slab 1
  g.Platform({s + P, 0});
  a.route = {{0, 0, 0}, {s + P, 0, 0}};
}

void BuildStairs(Attempt& a) {
  Gen& g = a.g;
  const RobotModel& robot = g.robot;
  const double P = a.P;
  g.Platform({0, 0});
  double s = P, top = 0.0;
  const int n = 2 + static_cast<int>(g.U(0, 3));
  for (int k = 0; k < 2 * n; ++k) {
    const double rise = g.U(0.3, 0.6) * robot.dz_max_m * (k < n ? 1 : -1);
    // A riser of two voxels or fewer looks like a voxelised slope: the map sees the
    // stairs as a ramp whose edge floats over the lower tread.
    g.Feature(2 * std::abs(rise));
    const double l = g.U(std::max(0.1, robot.d_lim_m), 0.3) + 2 * g.margin;
    top += rise;
    g.Slab(0, 0, 0, s, s + l, top);
    s += l;
  }
  g.Platform({s + P, 0}, top);
  a.route = {{0, 0, 0}, {s + P, 0, 0}};
}

void BuildTilted(Attempt& a) {
  Gen& g = a.g;
  const RobotModel& robot = g.robot;
  const double P = a.P;
  g.Platform({0, 0});
  double s = P + 0.04;
  const double end = P + a.len;
  while (s < end) {
    const double l = g.U(0.2, 0.4);
    // Tilt so that the top face varies in height by at most 0.5 dz_max over its extent.
    const double pitch = std::min(0.5 * robot.max_slope_rad, std::asin(std::min(1.0, 0.5 * robot.dz_max_m / l)));
    const double roll = std::min(0.5 * robot.max_slope_rad, std::asin(std::min(1.0, 0.5 * robot.dz_max_m / (2 * P))));
    g.Slab(0, 0, 0, s, s + l, 0.0, g.U(-roll, roll), g.U(-pitch, pitch));
    s += l + 0.04;
  }
  g.Platform({s + P, 0});
  a.route = {{0, 0, 0}, {s + P, 0, 0}};
}

// An L-shaped field of abutting cells of random height; start and goal platforms flat.
void BuildRough(Attempt& a) {
  Gen& g = a.g;
  const RobotModel& robot = g.robot;
  const double P = a.P;
  g.Platform({0, 0});
  const double c = g.U(std::max(0.06, 2 * g.margin + 0.03), std::max(0.08, 0.3 * a.reach_r));
  g.Feature(c - 2 * g.margin);
  const double cx = P + a.len + P;  // corner
  const double len2 = g.U(2.0, 3.0) * a.reach_r + 0.3;
  const double gy = P + len2 + P;
  for (double x = P; x < cx + P - 1e-9; x += c) {
    for (double y = -P; y < P - 1e-9; y += c) g.Box(x + c / 2, y + c / 2, g.U(0, 0.5 * robot.dz_max_m), c, c, 0);
  }
  for (double x = cx - P; x < cx + P - 1e-9; x += c) {
    for (double y = P; y < gy - P - 1e-9; y += c) g.Box(x + c / 2, y + c / 2, g.U(0, 0.5 * robot.dz_max_m), c, c, 0);
  }
  g.Platform({cx, gy});
  a.route = {{0, 0, 0}, {cx, 0, 0}, {cx, 0, M_PI / 2}, {cx, gy, M_PI / 2}};
}

void BuildBeams(Attempt& a) {
  Gen& g = a.g;
  const double P = a.P;
  g.Platform({0, 0});
  const double w = 2 * g.margin + g.U(0.02, 0.05);
  const double top = g.U(0.0, 0.5 * g.robot.dz_max_m);
  g.Feature(w - 2 * g.margin);
  for (const auto& [t, width] : g.Tracks(w)) {
    const double s0 = P, s1 = P + a.len;
    const Eigen::Vector2d c = Gen::At(0, 0, 0, (s0 + s1) / 2, t);
    g.Box(c.x(), c.y(), top, s1 - s0, width, 0);
  }
  g.Platform({P + a.len + P, 0});
  a.route = {{0, 0, 0}, {P + a.len + P, 0, 0}};
}

void BuildDetour(Attempt& a) {
  Gen& g = a.g;
  const double P = a.P, cut = a.cut;
  const double dx = 2 * P + cut;
  const double ytop = P + g.U(0.1, 0.5);
  g.Platform({0, 0});
  g.Platform({dx, 0});
  g.Box(0, (P + ytop) / 2, 0, 2 * P, ytop - P, 0);                   // up from the start
  g.Box(dx / 2, ytop + P, 0, dx + 2 * P, 2 * P, 0);                  // across
  g.Box(dx, (P + ytop) / 2, 0, 2 * P, ytop - P, 0);                  // down to the goal
  const double pocket = 0.3 * cut;
  g.Box(P + pocket / 2, 0, 0, pocket, 2 * P, 0);                     // dead-end pocket toward the goal
  g.Box(P + 0.65 * cut, 0, 0.5, 0.5 * cut, 2 * P, 0, 0, 0, 0.6);     // the wall
  a.route = {{0, 0, 0}, {0, ytop + P, 0}, {dx, ytop + P, 0}, {dx, 0, 0}};
}

void BuildWalledGoal(Attempt& a) {
  Gen& g = a.g;
  const double P = a.P;
  g.Platform({0, 0});
  g.Slab(0, 0, 0, P, P + a.len, 0.0);
  g.Platform({P + a.len + P, 0}, 4 * g.robot.dz_max_m);
  a.route = {{0, 0, 0}, {P + a.len + P, 0, 0}};
  a.exists = false;
}

// Lays down the attempt's kind; throws when the robot's body does not allow a body kind.
void BuildKind(Attempt& a) {
  switch (a.kind) {
    case CourseKind::kStones:
    case CourseKind::kCutStones: BuildStones(a); break;
    case CourseKind::kStonesTurn: BuildStonesTurn(a); break;
    case CourseKind::kGaps:
    case CourseKind::kCutGaps: BuildGaps(a); break;
    case CourseKind::kStairs: BuildStairs(a); break;
    case CourseKind::kTilted: BuildTilted(a); break;
    case CourseKind::kRough: BuildRough(a); break;
    case CourseKind::kBeams: BuildBeams(a); break;
    case CourseKind::kDetour: BuildDetour(a); break;
    case CourseKind::kWalledGoal: BuildWalledGoal(a); break;
    case CourseKind::kPocket:
    case CourseKind::kBaffles:
    case CourseKind::kDoorway:
    case CourseKind::kCorridor:
    case CourseKind::kClosedDoor:
      if (!BodyCourse(a.g, a.kind, a.g.robot, &a.route)) {
        throw std::runtime_error("GenerateCourse: robot '" + a.g.robot.name + "' has no body box for a " +
                                 ToString(a.kind) + " course (or a door cannot need a turn)");
      }
      a.exists = a.kind != CourseKind::kClosedDoor;
      break;
  }
}

// The course as the attempt laid it down.
void TakeAttempt(const Attempt& a, Course* course) {
  course->terrain.boxes = a.g.boxes;
  // The map resolves the course: its voxel at most a sixth of the finest feature (a gap
  // always shows empty columns; a foothold keeps room for its foot centres after the
  // inset loses up to a voxel and a half of each edge to quantisation and the edge
  // uncertainty; a riser spans three voxels or more), as a robot meant for such a
  // course would map it.
  course->terrain.resolution_m =
      std::clamp(a.g.finest_m / kCourseVoxelsPerFeature, kCourseMinResolution, kCourseMaxResolution);
  course->start = a.route.front();
  course->goal = a.route.back();
  course->route_exists = a.exists;
  course->route = a.exists ? a.route : std::vector<Pose2D>{};
}

// Whether the course the attempt laid down keeps its promise: the body clears the route
// of a body kind, and a route that exists holds for the feet.
bool AttemptHolds(const Attempt& a, const Course& course) {
  const RobotModel& robot = a.g.robot;
  const CourseKind kind = a.kind;
  const bool body_kind = kind == CourseKind::kPocket || kind == CourseKind::kBaffles ||
                         kind == CourseKind::kDoorway || kind == CourseKind::kCorridor;
  if (body_kind && !BodyRouteClear(robot, course.terrain, a.route, 0.0)) return false;
  return !a.exists || RouteHolds(robot, course.terrain, a.route, course.edge_margin_m);
}

}  // namespace

Course GenerateCourse(const RobotModel& robot, const std::string& robot_path, CourseKind kind, uint64_t seed) {
  Course course;
  course.kind = kind;
  course.robot_path = robot_path;
  course.name = robot.name + "_" + ToString(kind) + "_" + std::to_string(seed);
  course.edge_margin_m = robot.foot_radius_m + kCourseEdgeMargin;
  double reach_r = 0.0;
  for (const auto& leg : robot.legs) reach_r = std::max(reach_r, leg.nominal_offset_body_m.norm());
  const double footprint = reach_r + 0.7 * robot.d_lim_m + course.edge_margin_m + 0.02;
  const double cut = 1.5 * MaxFootTravel(robot) + 0.1;
  for (int attempt = 0; attempt < 200; ++attempt) {
    Attempt a{Gen{robot, std::mt19937_64(seed * 1000003ULL + attempt), course.edge_margin_m, MaxFootTravel(robot),
                  footprint, robot.dz_max_m, {}},
              kind, footprint, reach_r, cut, /*len=*/0.0, /*route=*/{}, /*exists=*/true};
    a.len = a.g.U(2.0, 4.0) * reach_r + 0.3;  // the first draw after the generator's seeding
    BuildKind(a);
    TakeAttempt(a, &course);
    if (AttemptHolds(a, course)) return course;
  }
  throw std::runtime_error("GenerateCourse: no valid " + ToString(kind) + " course for seed " + std::to_string(seed));
}

Scenario CourseScenario(const Course& course, double time_limit_s) {
  Scenario scenario;
  scenario.name = course.name;
  scenario.robot_path = course.robot_path;
  scenario.terrain = course.terrain;
  scenario.start = course.start;
  scenario.goal = course.goal;
  scenario.time_limit_s = time_limit_s;
  return scenario;
}

std::string CourseToScenarioYaml(const Course& course, double time_limit_s) {
  std::ostringstream out;
  out.precision(6);
  out << "# Generated by mfp-bench --courses (bench/course_generator.cc): " << ToString(course.kind)
      << ", route " << (course.route_exists ? "exists" : "cut") << "\n";
  out << "name: " << course.name << "\nrobot: " << course.robot_path << "\nterrain:\n  resolution: "
      << course.terrain.resolution_m << "\n  boxes:\n";
  for (const TerrainBox& b : course.terrain.boxes) {
    out << "    - {name: " << b.name << ", center: [" << b.center_world_m.x() << ", " << b.center_world_m.y() << ", "
        << b.center_world_m.z() << "], size: [" << b.size_m.x() << ", " << b.size_m.y() << ", " << b.size_m.z()
        << "], rpy: [" << b.rpy_rad.x() << ", " << b.rpy_rad.y() << ", " << b.rpy_rad.z() << "]}\n";
  }
  out << "start: [" << course.start.x_m << ", " << course.start.y_m << ", " << course.start.yaw_rad << "]\n";
  out << "goal: [" << course.goal.x_m << ", " << course.goal.y_m << ", " << course.goal.yaw_rad << "]\n";
  out << "time_limit: " << time_limit_s << "\n";
  return out.str();
}

}  // namespace mfp

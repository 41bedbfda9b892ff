#include "bench/scan_walks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "bench/coverage_breakdown.h"
#include "io/map_file.h"
#include "io/robot_loader.h"
#include "io/scenario_yaml.h"
#include "planner/planning/footstep_planner.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "terrain/octomap/octomap_io.h"
#include "terrain/quality/leaf_set.h"

namespace mfp {
namespace {

// The raw voxels' answer to "can a foot stand here": columns of voxels seen from above
// (occupied, the voxel above known free) with `clearance_m` of no occupied voxel above.
class SeenVoxelJudge {
 public:
  SeenVoxelJudge(const OccupancyMap& map, double clearance_m)
      : r_(map.resolution_m), occupied_(map.leaves, r_), free_(map.free_leaves, r_),
        room_(std::max(1, static_cast<int>(std::ceil(clearance_m / r_ - 1e-9)))) {
    const LeafSet& occupied = occupied_;
    const LeafSet& free = free_;
    const int room = room_;
    std::unordered_map<int64_t, int> level_count;
    for (const OccupiedLeaf& leaf : map.leaves) {
      const int64_t n = int64_t{1} << occupied.LevelOf(leaf.size_m);
      const Eigen::Vector3d c = leaf.center_world_m.array() - 0.5 * leaf.size_m;
      const int64_t i0 = std::llround(c.x() / r_), j0 = std::llround(c.y() / r_), k = std::llround(c.z() / r_) + n - 1;
      for (int64_t i = i0; i < i0 + n; ++i) {
        for (int64_t j = j0; j < j0 + n; ++j) {
          if (!free.Contains(i, j, k + 1)) continue;
          bool clear = true;
          for (int d = 1; d <= room && clear; ++d) clear = !occupied.Contains(i, j, k + d);
          if (!clear) continue;
          tops_[VoxelColumnKey(i, j)].push_back(k);
          ++level_count[k];
        }
      }
    }
    int best = -1;
    for (const auto& [k, count] : level_count) {
      if (count > best) best = count, floor_k_ = k;
    }
    for (const auto& [key, ks] : tops_) {
      for (int64_t k : ks) {
        if (std::abs(k - floor_k_) <= 1) floor_cells_.push_back({key, k});
      }
    }
    std::sort(floor_cells_.begin(), floor_cells_.end());
  }

  // True when the column of p holds a seen surface whose top lies within one voxel plus
  // slack_m of p (slack: the plane tolerance of the region the foot stands in, as
  // voxel_quality.h judges region points).
  bool Stands(const Eigen::Vector3d& p, double slack_m) const {
    const auto it = tops_.find(VoxelColumnKey(Index(p.x()), Index(p.y())));
    if (it == tops_.end()) return false;
    for (int64_t k : it->second) {
      if (std::abs(p.z() - (k + 1) * r_) <= r_ + slack_m + 1e-9) return true;
    }
    return false;
  }
  // For a step off the seen voxels: the voxels of p's column from 1 m below p to 1 m
  // above it, bottom up, each as its top's height and what it is ('o' occupied, 'f' known
  // free, '.' unknown), with '*' after an occupied voxel seen from above with room; and
  // the seen tops of the eight neighbouring columns within 0.5 m of p.
  std::string ColumnText(const Eigen::Vector3d& p) const {
    const int64_t i = Index(p.x()), j = Index(p.y()), kp = Index(p.z());
    const int64_t span = static_cast<int64_t>(std::ceil(1.0 / r_));
    std::string text = "column";
    char item[48];
    for (int64_t k = kp - span; k <= kp + span; ++k) {
      const bool occupied = occupied_.Contains(i, j, k), free = free_.Contains(i, j, k);
      if (!occupied && !free) continue;
      const bool seen = occupied && IsTop(i, j, k);
      std::snprintf(item, sizeof(item), " %.2f%c%s", (k + 1) * r_, occupied ? 'o' : 'f', seen ? "*" : "");
      text += item;
    }
    text += "; neighbours' seen tops";
    for (int64_t di = -1; di <= 1; ++di) {
      for (int64_t dj = -1; dj <= 1; ++dj) {
        const auto it = tops_.find(VoxelColumnKey(i + di, j + dj));
        if ((di == 0 && dj == 0) || it == tops_.end()) continue;
        for (int64_t k : it->second) {
          if (std::abs((k + 1) * r_ - p.z()) > 0.5) continue;
          std::snprintf(item, sizeof(item), " (%+d,%+d) %.2f", static_cast<int>(di), static_cast<int>(dj), (k + 1) * r_);
          text += item;
        }
      }
    }
    return text;
  }
  // The floor's top in the column of xy, when the column is seen floor.
  bool FloorTop(const Eigen::Vector2d& xy, double* z) const {
    const auto it = tops_.find(VoxelColumnKey(Index(xy.x()), Index(xy.y())));
    if (it == tops_.end()) return false;
    for (int64_t k : it->second) {
      if (std::abs(k - floor_k_) <= 1) {
        *z = (k + 1) * r_;
        return true;
      }
    }
    return false;
  }
  // True when every column whose square comes closer than radius_m to xy is seen floor
  // within a voxel of the floor at xy: the disk lies on the seen floor, the floor being
  // the union of its columns' squares (the set erosion of voxel_quality.h's certifiable
  // floor); any sound extractor could certify a foot there. With level, every such column's
  // top is the one at xy: a disk across a one-voxel change of level (a contour of a sloped
  // floor, or a step of up to two voxels: the voxels cannot tell) is not certifiable.
  bool Certifiable(const Eigen::Vector2d& xy, double radius_m, bool level = false) const {
    double z0 = 0.0, z = 0.0;
    if (!FloorTop(xy, &z0)) return false;
    const int64_t ci = Index(xy.x()), cj = Index(xy.y());
    const int64_t cells = static_cast<int64_t>(std::ceil(radius_m / r_));
    const double tolerance_m = level ? 0.5 * r_ : r_ + 1e-9;
    for (int64_t i = ci - cells; i <= ci + cells; ++i) {
      for (int64_t j = cj - cells; j <= cj + cells; ++j) {
        if (SquareDistanceM(i, j, xy) >= radius_m - 1e-9) continue;
        if (!FloorTop({(i + 0.5) * r_, (j + 0.5) * r_}, &z) || std::abs(z - z0) > tolerance_m) return false;
      }
    }
    return true;
  }
  // Plan distance from xy to the square of column (i, j) (0 inside).
  double SquareDistanceM(int64_t i, int64_t j, const Eigen::Vector2d& xy) const {
    const double dx = std::max({i * r_ - xy.x(), 0.0, xy.x() - (i + 1) * r_});
    const double dy = std::max({j * r_ - xy.y(), 0.0, xy.y() - (j + 1) * r_});
    return std::hypot(dx, dy);
  }
  // Centre of a random floor cell.
  Eigen::Vector2d RandomFloorPoint(std::mt19937* rng) const {
    std::uniform_int_distribution<size_t> pick(0, floor_cells_.size() - 1);
    const int64_t key = floor_cells_[pick(*rng)].first;
    const int64_t i = (key >> 21) - (1 << 20), j = (key & ((int64_t{1} << 21) - 1)) - (1 << 20);
    return {(i + 0.5) * r_, (j + 0.5) * r_};
  }
  // What the raw voxels hold in the column of xy about a floor whose top is z0_m (the top
  // of voxel k0): the reason a column is or is not floor a foot at that height can use.
  const char* ColumnKind(const Eigen::Vector2d& xy, double z0_m) const {
    const int64_t i = Index(xy.x()), j = Index(xy.y()), k0 = std::llround(z0_m / r_) - 1;
    const auto it = tops_.find(VoxelColumnKey(i, j));
    if (it != tops_.end()) {
      for (int64_t k : it->second) {
        if (std::abs(k - k0) <= 1) return "floor";
      }
    }
    for (int d = 2; d <= room_; ++d) {
      if (occupied_.Contains(i, j, k0 + d)) return "obstacle above";
    }
    if (it != tops_.end()) return "surface 2+ voxels off";
    if (occupied_.Contains(i, j, k0 + 1) || occupied_.Contains(i, j, k0) || occupied_.Contains(i, j, k0 - 1)) {
      return "floor seen, no room/free above";
    }
    for (int d = 2; d <= 8; ++d) {
      if (occupied_.Contains(i, j, k0 - d)) return "drop (lower surface)";
    }
    if (free_.Contains(i, j, k0)) return free_.Contains(i, j, k0 - 1) ? "free below floor (hole)" : "erased";
    if (free_.Contains(i, j, k0 - 1)) return "free below floor (hole)";
    return "unseen";
  }
  // Distance from xy to the nearest cell centre (within max_m) where a foot is
  // certifiable at the floor height z0_m within a voxel; max_m + 1 when none.
  double NearestCertifiableM(const Eigen::Vector2d& xy, double z0_m, double radius_m, double max_m,
                             Eigen::Vector3d* nearest) const {
    const int64_t ci = Index(xy.x()), cj = Index(xy.y()), cells = static_cast<int64_t>(std::ceil(max_m / r_));
    double best = max_m + 1.0, z = 0.0;
    for (int64_t i = ci - cells; i <= ci + cells; ++i) {
      for (int64_t j = cj - cells; j <= cj + cells; ++j) {
        const Eigen::Vector2d c((i + 0.5) * r_, (j + 0.5) * r_);
        const double d = (c - xy).norm();
        if (d > max_m || d >= best) continue;
        if (!FloorTop(c, &z) || std::abs(z - z0_m) > r_ + 1e-9) continue;
        if (Certifiable(c, radius_m)) best = d, *nearest = {c.x(), c.y(), z};
      }
    }
    return best;
  }
  // Counts of ColumnKind over the columns whose squares come closer than radius_m to xy.
  std::map<std::string, int> KindsAround(const Eigen::Vector2d& xy, double z0_m, double radius_m) const {
    std::map<std::string, int> kinds;
    const int64_t ci = Index(xy.x()), cj = Index(xy.y()), cells = static_cast<int64_t>(std::ceil(radius_m / r_));
    for (int64_t i = ci - cells; i <= ci + cells; ++i) {
      for (int64_t j = cj - cells; j <= cj + cells; ++j) {
        if (SquareDistanceM(i, j, xy) < radius_m - 1e-9) ++kinds[ColumnKind({(i + 0.5) * r_, (j + 0.5) * r_}, z0_m)];
      }
    }
    return kinds;
  }
  // Occupied voxels of the columns whose centres lie in the body's plan box at the pose
  // that reach into its band (ground_z_m + bottom .. + top); *lowest_m: the lowest such
  // voxel's bottom above the ground.
  int BodyVoxels(const BodyExtent& body, const Pose2D& pose, double ground_z_m, double* lowest_m, int* columns = nullptr,
                 double* highest_m = nullptr) const {
    const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
    const double reach = std::max(body.max_m.norm(), body.min_m.norm());
    const int64_t i0 = Index(pose.x_m - reach), i1 = Index(pose.x_m + reach);
    const int64_t j0 = Index(pose.y_m - reach), j1 = Index(pose.y_m + reach);
    const int64_t k0 = static_cast<int64_t>(std::floor((ground_z_m + body.bottom_m) / r_));
    const int64_t k1 = static_cast<int64_t>(std::floor((ground_z_m + body.top_m) / r_));
    int count = 0, hit_columns = 0;
    double highest = -1e9;
    *lowest_m = 1e9;
    for (int64_t i = i0; i <= i1; ++i) {
      for (int64_t j = j0; j <= j1; ++j) {
        const double dx = (i + 0.5) * r_ - pose.x_m, dy = (j + 0.5) * r_ - pose.y_m;
        const double bx = c * dx + s * dy, by = -s * dx + c * dy;
        if (bx < body.min_m.x() || bx > body.max_m.x() || by < body.min_m.y() || by > body.max_m.y()) continue;
        const int before = count;
        for (int64_t k = k0; k <= k1; ++k) {
          if (!occupied_.Contains(i, j, k)) continue;
          ++count;
          *lowest_m = std::min(*lowest_m, k * r_ - ground_z_m);
        }
        if (count == before) continue;
        ++hit_columns;
        // The column's occupied voxels above the band, up to 2 m: a wall or furniture's height.
        for (int64_t k = k1; k <= k1 + static_cast<int64_t>(2.0 / r_); ++k) {
          if (occupied_.Contains(i, j, k)) highest = std::max(highest, (k + 1) * r_ - ground_z_m);
        }
      }
    }
    if (columns != nullptr) *columns = hit_columns;
    if (highest_m != nullptr) *highest_m = highest;
    return count;
  }
  // Whether certifiable floor (Certifiable at cell centres) joins the ends a and b by
  // hops of at most span_m in plan and dz_m in height: from any certifiable cell within
  // near_m of a to one within near_m of b. The cells searched lie in the box about a and
  // b grown by margin_m. What a sound extractor's regions could at best connect.
  // With end heights (not NaN), from and to cells whose floor lies within dz_m of them:
  // one foot's way, which changes height by at most dz_m a step.
  bool CertifiableFloorJoins(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double radius_m, double span_m,
                             double dz_m, double near_m, double margin_m, double a_z_m = std::nan(""),
                             double b_z_m = std::nan("")) const {
    const int64_t i0 = Index(std::min(a.x(), b.x()) - margin_m), i1 = Index(std::max(a.x(), b.x()) + margin_m);
    const int64_t j0 = Index(std::min(a.y(), b.y()) - margin_m), j1 = Index(std::max(a.y(), b.y()) + margin_m);
    const int64_t nx = i1 - i0 + 1, ny = j1 - j0 + 1;
    std::vector<float> top(static_cast<size_t>(nx * ny), std::nanf(""));  // NaN: not certifiable
    double z = 0.0;
    for (int64_t i = i0; i <= i1; ++i) {
      for (int64_t j = j0; j <= j1; ++j) {
        const Eigen::Vector2d c((i + 0.5) * r_, (j + 0.5) * r_);
        if (FloorTop(c, &z) && Certifiable(c, radius_m)) top[static_cast<size_t>((j - j0) * nx + (i - i0))] = static_cast<float>(z);
      }
    }
    const int64_t reach = static_cast<int64_t>(std::floor(span_m / r_));
    std::vector<std::pair<int64_t, int64_t>> hops;
    for (int64_t di = -reach; di <= reach; ++di) {
      for (int64_t dj = -reach; dj <= reach; ++dj) {
        if ((di != 0 || dj != 0) && std::hypot(di, dj) * r_ <= span_m) hops.push_back({di, dj});
      }
    }
    std::vector<char> seen(top.size(), 0);
    std::vector<int64_t> queue;
    auto centre = [&](int64_t id) { return Eigen::Vector2d((id % nx + i0 + 0.5) * r_, (id / nx + j0 + 0.5) * r_); };
    for (int64_t id = 0; id < nx * ny; ++id) {
      const float z = top[static_cast<size_t>(id)];
      if (!std::isnan(z) && (centre(id) - a).norm() <= near_m && !(std::abs(z - a_z_m) > dz_m + 1e-6)) {
        seen[static_cast<size_t>(id)] = 1;
        queue.push_back(id);
      }
    }
    for (size_t q = 0; q < queue.size(); ++q) {
      const int64_t id = queue[q], ci = id % nx, cj = id / nx;
      if ((centre(id) - b).norm() <= near_m && !(std::abs(top[static_cast<size_t>(id)] - b_z_m) > dz_m + 1e-6)) return true;
      for (const auto& [di, dj] : hops) {
        const int64_t ni = ci + di, nj = cj + dj;
        if (ni < 0 || nj < 0 || ni >= nx || nj >= ny) continue;
        const size_t n = static_cast<size_t>(nj * nx + ni);
        if (seen[n] || std::isnan(top[n]) || std::abs(top[n] - top[static_cast<size_t>(id)]) > dz_m + 1e-6) continue;
        seen[n] = 1;
        queue.push_back(static_cast<int64_t>(n));
      }
    }
    return false;
  }
  bool empty() const { return floor_cells_.empty(); }
  double resolution_m() const { return r_; }

 private:
  int64_t Index(double v) const { return static_cast<int64_t>(std::floor(v / r_)); }
  bool IsTop(int64_t i, int64_t j, int64_t k) const {
    const auto it = tops_.find(VoxelColumnKey(i, j));
    return it != tops_.end() && std::find(it->second.begin(), it->second.end(), k) != it->second.end();
  }
  double r_;
  LeafSet occupied_, free_;
  int room_;
  int64_t floor_k_ = 0;
  std::unordered_map<int64_t, std::vector<int64_t>> tops_;
  std::vector<std::pair<int64_t, int64_t>> floor_cells_;
};

// Radius of seen floor around a foot spot that makes it certifiable: the foot, 1 cm, and
// one voxel of edge uncertainty (issue 25's measure of what a sound extractor can cover).
double CertifyRadiusM(const RobotModel& robot, double resolution_m) { return robot.foot_radius_m + 0.01 + resolution_m; }

// The robot's nominal feet at a pose, each on seen floor (within a voxel of each other)
// and, when certify_radius_m > 0, on certifiable floor; empty when the stance does not fit.
std::vector<Eigen::Vector3d> FloorStance(const RobotModel& robot, const SeenVoxelJudge& judge, const Pose2D& pose,
                                         double resolution_m, double certify_radius_m) {
  std::vector<Eigen::Vector3d> feet;
  double lo = 1e9, hi = -1e9, z = 0.0;
  if (!judge.FloorTop({pose.x_m, pose.y_m}, &z)) return {};
  for (int leg = 0; leg < robot.num_legs(); ++leg) {
    const Eigen::Vector2d xy = NominalFootXY(robot, leg, pose.x_m, pose.y_m, pose.yaw_rad);
    if (!judge.FloorTop(xy, &z)) return {};
    if (certify_radius_m > 0.0 && !judge.Certifiable(xy, certify_radius_m)) return {};
    lo = std::min(lo, z), hi = std::max(hi, z);
    feet.emplace_back(xy.x(), xy.y(), z);
  }
  if (hi - lo > resolution_m + 1e-9) return {};
  return feet;
}

// Whether a stance whose every nominal foot stands on certifiable floor lies within
// shift_m and turn_rad of the pose (poses on a grid of half a voxel, at least 2 cm, and
// turns 0.05 rad apart): what a sound extractor could offer as a goal within the tolerances.
bool CertifiableStanceNear(const RobotModel& robot, const SeenVoxelJudge& judge, const Pose2D& pose, double shift_m,
                           double turn_rad) {
  const double r = judge.resolution_m(), step = std::max(0.02, 0.5 * r);
  const int n = static_cast<int>(std::floor(shift_m / step)), turns = static_cast<int>(std::floor(turn_rad / 0.05));
  for (int i = -n; i <= n; ++i) {
    for (int j = -n; j <= n; ++j) {
      if (std::hypot(i, j) * step > shift_m) continue;
      for (int t = -turns; t <= turns; ++t) {
        const Pose2D p{pose.x_m + i * step, pose.y_m + j * step, pose.yaw_rad + t * 0.05};
        if (!FloorStance(robot, judge, p, r, CertifyRadiusM(robot, r)).empty()) return true;
      }
    }
  }
  return false;
}

struct Walk {
  Pose2D start, goal;
  std::vector<Eigen::Vector3d> start_feet;
  int start_body_voxels = 0, goal_body_voxels = 0;  // occupied voxels in the body's band at each end
  double judge_step_m = 0.0;  // JudgeStep of the robot the walk was drawn for [m]
};

// The judge's step: sqrt(2) (d_lim + l_bnd) of the robot derived with the paper's box
// (`box_robot`), the box's diagonal reach, kept from stop 33 so that draws compare across
// stops and reach shapes. It is shorter than every derived footprint's chord through the
// nominal foot on both body axes (mfp-robot's chord_x, chord_y; docs/measurements.md, stop
// 35 reach8): a foot can truly swing that far with the body still. It is not the planner's
// step on a world axis, which the route graph uses (reach_polygon.h) [m].
double JudgeStep(const RobotModel& box_robot) { return std::sqrt(2.0) * (box_robot.d_lim_m + box_robot.l_bnd_m); }

// Whether certifiable floor joins the walk's ends by hops of step_m and dz_max, from and to
// certifiable floor within a step of each end's centre (the first step and a goal moved
// within its tolerance).
bool EndsJoined(const RobotModel& robot, const SeenVoxelJudge& judge, const Pose2D& start, const Pose2D& goal,
                double step_m) {
  return judge.CertifiableFloorJoins({start.x_m, start.y_m}, {goal.x_m, goal.y_m},
                                     CertifyRadiusM(robot, judge.resolution_m()), step_m, robot.dz_max_m, step_m, 1.5);
}

// The first leg (-1: none) whose own way certifiable floor does not join: from its start
// spot's floor height to its goal spot's, by hops of step_m (JudgeStep) that change height by at
// most dz_max (a foot's steps; the planner bounds each foot's height change so). Where a
// one-voxel change of level exceeds dz_max (20 cm voxels), a foot cannot change level:
// EndsJoined joins the ends from any level, this joins each foot from its own.
int LegNotJoinedAtItsHeight(const RobotModel& robot, const SeenVoxelJudge& judge, const Pose2D& start,
                            const Pose2D& goal, double step_m) {
  for (int leg = 0; leg < robot.num_legs(); ++leg) {
    const Eigen::Vector2d a = NominalFootXY(robot, leg, start.x_m, start.y_m, start.yaw_rad);
    const Eigen::Vector2d b = NominalFootXY(robot, leg, goal.x_m, goal.y_m, goal.yaw_rad);
    double za = 0.0, zb = 0.0;
    if (!judge.FloorTop(a, &za) || !judge.FloorTop(b, &zb)) continue;
    if (!judge.CertifiableFloorJoins(a, b, CertifyRadiusM(robot, judge.resolution_m()), step_m, robot.dz_max_m, step_m,
                                     1.5, za, zb)) {
      return leg;
    }
  }
  return -1;
}

// Occupied voxels in the body's band over its plan box at the pose, the body's ground
// being the mean height of the stance's feet (0 without a known body).
int BodyVoxelsAt(const RobotModel& robot, const SeenVoxelJudge& judge, const Pose2D& pose,
                 const std::vector<Eigen::Vector3d>& feet) {
  if (!robot.body.known() || feet.empty()) return 0;
  double ground = 0.0, lowest = 0.0;
  for (const Eigen::Vector3d& f : feet) ground += f.z() / static_cast<double>(feet.size());
  return judge.BodyVoxels(robot.body, pose, ground, &lowest);
}

// Draws o.walks walks for `robot` (the box-derived one: JudgeStep) into *walks; with
// o.joined_ends only walks whose ends certifiable floor joins, and the unjoined ones met on
// the way (up to o.walks) into *unjoined.
void DrawWalks(const RobotModel& robot, const SeenVoxelJudge& judge, double resolution_m, const ScanWalkOptions& o,
               unsigned seed, std::vector<Walk>* walks, std::vector<Walk>* unjoined) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI), length(o.min_length_m, o.max_length_m);
  const double certify = o.certifiable_ends ? CertifyRadiusM(robot, resolution_m) : 0.0;
  for (int attempt = 0; attempt < 200000 && static_cast<int>(walks->size()) < o.walks && !judge.empty(); ++attempt) {
    Walk w;
    const Eigen::Vector2d s = judge.RandomFloorPoint(&rng);
    w.start = {s.x(), s.y(), yaw(rng)};
    w.start_feet = FloorStance(robot, judge, w.start, resolution_m, certify);
    if (w.start_feet.empty()) continue;
    const double heading = yaw(rng), d = length(rng);
    w.goal = {s.x() + d * std::cos(heading), s.y() + d * std::sin(heading), yaw(rng)};
    const std::vector<Eigen::Vector3d> goal_feet = FloorStance(robot, judge, w.goal, resolution_m, certify);
    if (goal_feet.empty()) continue;
    w.start_body_voxels = BodyVoxelsAt(robot, judge, w.start, w.start_feet);
    w.goal_body_voxels = BodyVoxelsAt(robot, judge, w.goal, goal_feet);
    if (o.body_room_ends && w.start_body_voxels + w.goal_body_voxels > 0) continue;
    w.judge_step_m = JudgeStep(robot);
    if (!o.joined_ends ||
        (EndsJoined(robot, judge, w.start, w.goal, w.judge_step_m) &&
         (!o.legs_joined_ends || LegNotJoinedAtItsHeight(robot, judge, w.start, w.goal, w.judge_step_m) < 0))) {
      walks->push_back(w);
    } else if (static_cast<int>(unjoined->size()) < o.walks) {
      unjoined->push_back(w);
    }
  }
}

// Where one end's nominal feet stand: on no region, and of those on certifiable floor.
struct EndFeet {
  std::vector<std::string> details;  // per foot on no region, and the body's room
  int within_step = 0;  // of the feet off regions, with certifiable floor within d_lim of the spot
  bool certifiable_stance_near = false;  // a stance on certifiable floor within the goal tolerances
  int body_voxels = 0;               // occupied voxels in the body's band at the end pose
  int off_regions = 0;
  int certifiable = 0;     // of the feet off regions
  double farthest_m = 0.0; // of the feet off regions, from the nearest region (plan view)
};

struct WalkResult {
  SolveStatus status = SolveStatus::kInternalError;
  bool valid_to_goal = false, goal_moved = false;
  bool start_off_regions = false;  // a start foot on no region: invalid_start before issue 25
  int feet_off = 0;
  double time_s = 0.0;
  std::string message;
  std::string time_split;  // where the plan's time went: setup, then each window
  EndFeet start, goal;  // filled for walks that fail
  // For walks that fail: certifiable floor joins the ends by steps (CertifiableFloorJoins),
  // and level certifiable floor does (its level: no disk across a one-voxel change of level).
  bool certifiable_route = false;
  int leg_not_joined = -1;  // LegNotJoinedAtItsHeight, when certifiable_route
};

// A map of the cells around xy (half_cells each way; north up), three characters a cell:
// the extractor's fate in the layer within a voxel of z0_m (. none, n not in a patch, s
// steep, m small, d not decomposed, i inset off the patch, b inset beyond, u uncovered,
// C covered), that layer's height against z0_m in voxels (0, + one up, - one down, ^ / v
// more, blank: no surface in a layer there), and the raw voxels' column kind (F floor,
// O obstacle above, S surface 2+ voxels off, R floor without room, D drop, E erased, H
// hole, U unseen); '>' marks xy's cell. For finding why the extractor left floor out.
std::string CellMapText(const Eigen::Vector2d& xy, double z0_m, const RegionExtractionResult& result,
                        const SeenVoxelJudge& judge, int half_cells) {
  if (result.layers.empty() || result.cell_fates.size() != result.layers.size()) return "";
  const HeightMap& grid = result.layers.front();
  const double res = grid.resolution_m;
  const int col0 = static_cast<int>(std::floor((xy.x() - grid.origin_world_m.x()) / res));
  const int row0 = static_cast<int>(std::floor((xy.y() - grid.origin_world_m.y()) / res));
  static const char kFate[] = ".nsmdibuC";
  const std::map<std::string, char> kinds = {{"floor", 'F'}, {"obstacle above", 'O'}, {"surface 2+ voxels off", 'S'},
                                             {"floor seen, no room/free above", 'R'}, {"drop (lower surface)", 'D'},
                                             {"erased", 'E'}, {"free below floor (hole)", 'H'}, {"unseen", 'U'}};
  std::string text = "cell map about (" + std::to_string(xy.x()) + ", " + std::to_string(xy.y()) + "):";
  for (int row = row0 + half_cells; row >= row0 - half_cells; --row) {
    text += "\n       ";
    for (int col = col0 - half_cells; col <= col0 + half_cells; ++col) {
      char fate = '.', height = ' ';
      if (grid.Inside(row, col)) {
        const size_t cell = static_cast<size_t>(grid.Index(row, col));
        for (size_t l = 0; l < result.layers.size(); ++l) {
          const float h = result.layers[l].height_m[cell];
          if (std::isnan(h)) continue;
          const long dv = std::lround((h - z0_m) / res);
          if (std::abs(dv) > 1 && height != ' ') continue;
          height = dv == 0 ? '0' : dv == 1 ? '+' : dv == -1 ? '-' : dv > 1 ? '^' : 'v';
          fate = kFate[static_cast<int>(result.cell_fates[l][cell])];
        }
      }
      const Eigen::Vector2d c = grid.CellCenter(row, col);
      const auto kind = kinds.find(judge.ColumnKind(c, z0_m));
      text += row == row0 && col == col0 ? '>' : ' ';
      text += fate;
      text += height;
      text += kind == kinds.end() ? '?' : kind->second;
    }
  }
  return text;
}

double NearestRegionM(const std::vector<ConvexRegion>& regions, const Eigen::Vector2d& xy) {
  double best = 1e9;
  for (const ConvexRegion& r : regions) best = std::min(best, PlanDistanceToRegion(r, xy));
  return best;
}

EndFeet DiagnoseEnd(const RobotModel& robot, const std::vector<ConvexRegion>& regions, const SeenVoxelJudge& judge,
                    const RegionExtractionResult& result, const Pose2D& pose, int map_cells) {
  EndFeet end;
  // The ground under the body: the mean floor top of the feet that have one.
  double ground_sum = 0.0, z = 0.0;
  int on_floor = 0;
  for (int leg = 0; leg < robot.num_legs(); ++leg) {
    if (!judge.FloorTop(NominalFootXY(robot, leg, pose.x_m, pose.y_m, pose.yaw_rad), &z)) continue;
    ground_sum += z;
    ++on_floor;
  }
  const double ground = on_floor > 0 ? ground_sum / on_floor : 0.0;
  if (robot.body.known()) {
    double lowest = 0.0, highest = 0.0;
    int columns = 0;
    end.body_voxels = judge.BodyVoxels(robot.body, pose, ground, &lowest, &columns, &highest);
    if (end.body_voxels > 0) {
      char line[240];
      std::snprintf(line, sizeof(line),
                    "body: %d occupied voxels in its band (%.2f-%.2f m) in %d columns, lowest %.2f m above the feet, "
                    "those columns occupied up to %.2f m",
                    end.body_voxels, robot.body.bottom_m, robot.body.top_m, columns, lowest, highest);
      end.details.push_back(line);
    }
  }
  for (int leg = 0; leg < robot.num_legs(); ++leg) {
    const Eigen::Vector2d xy = NominalFootXY(robot, leg, pose.x_m, pose.y_m, pose.yaw_rad);
    const double d = NearestRegionM(regions, xy);
    if (d <= 1e-6) continue;
    ++end.off_regions;
    end.farthest_m = std::max(end.farthest_m, d);
    const double radius = CertifyRadiusM(robot, judge.resolution_m());
    const bool certifiable = judge.Certifiable(xy, radius);
    const bool level = certifiable && judge.Certifiable(xy, radius, true);
    end.certifiable += certifiable ? 1 : 0;
    double z0 = 0.0;
    if (!judge.FloorTop(xy, &z0)) continue;
    std::string kinds;
    for (const auto& [kind, count] : judge.KindsAround(xy, z0, radius)) {
      if (kind != "floor") kinds += (kinds.empty() ? "" : ", ") + kind + " " + std::to_string(count);
    }
    Eigen::Vector3d nearest(xy.x(), xy.y(), z0);
    const double nearest_m = judge.NearestCertifiableM(xy, z0, radius, 0.6, &nearest);
    end.within_step += nearest_m <= robot.d_lim_m ? 1 : 0;
    const int fate = FateUnder(Eigen::Vector3d(xy.x(), xy.y(), z0), result);
    const int nearest_fate = nearest_m <= 0.6 ? FateUnder(nearest, result) : -1;
    auto name = [](int f) { return f < 0 ? "no layer" : CellFateName(static_cast<CellFate>(f)); };
    char line[400];
    std::snprintf(line, sizeof(line),
                  "leg %d (%.2f, %.2f, %.2f): region %.2f m, certifiable %s, nearest certifiable %.2f m; fate %s, "
                  "nearest's %s%s%s",
                  leg, xy.x(), xy.y(), z0, d, !certifiable ? "no" : level ? "yes" : "yes (not level)", nearest_m,
                  name(fate), name(nearest_fate),
                  kinds.empty() ? "" : "; around: ", kinds.c_str());
    end.details.push_back(line);
    if (map_cells > 0) end.details.push_back(CellMapText(xy, z0, result, judge, map_cells));
  }
  return end;
}

std::string EndText(const char* name, const EndFeet& e) {
  char line[160];
  std::snprintf(line, sizeof(line), "%s: %d feet on no region (farthest %.2f m from one), %d of them on certifiable floor",
                name, e.off_regions, e.farthest_m, e.certifiable);
  return line;
}

bool Contains(const std::string& text, const char* part) { return text.find(part) != std::string::npos; }

// The cause of a failed walk, from its status and message, tagged with what a sound
// extractor could have offered there: for a start, certifiable floor within d_lim of each
// start foot on no region (the first step's box); for a goal, a stance on certifiable
// floor within the goal tolerances; for a route, certifiable floor joining the ends.
std::string FailureCause(const WalkResult& r) {
  if (r.feet_off > 0) return "footsteps off the seen voxels";
  auto start_tag = [](const EndFeet& e) {
    if (e.off_regions == 0) return " [every start foot on a region]";
    return e.within_step == e.off_regions ? " [certifiable floor within d_lim of every such foot]"
                                          : " [a foot with no certifiable floor within d_lim]";
  };
  auto goal_tag = [](const EndFeet& e) {
    return e.certifiable_stance_near ? " [a certifiable stance within the tolerances]"
                                     : " [no certifiable stance within the tolerances]";
  };
  if (Contains(r.message, "no region lies within one step") || Contains(r.message, "its first step")) {
    return std::string("start: a start foot's first step meets no region") + start_tag(r.start);
  }
  if (Contains(r.message, "m from the nearest region")) {
    return std::string("goal: farther than a leg's reach from every region") + goal_tag(r.goal);
  }
  if (Contains(r.message, "no stance on regions within")) {
    return std::string("goal: no stance on regions within the goal tolerances") + goal_tag(r.goal);
  }
  if (Contains(r.message, "no route for the body")) return "body: no route for the body";
  if (Contains(r.message, "regions reachable from the start end")) {
    return std::string("route: the reachable regions end short of the goal") +
           (!r.certifiable_route         ? " [certifiable floor does not join the ends]"
            : r.leg_not_joined < 0 ? " [certifiable floor joins the ends]"
                                   : " [certifiable floor joins the ends, not a foot's way from its start height]");
  }
  return "other: " + ToString(r.status);
}

// "setup S s; windows: steps/status/nodes search+polish s of its share, ..." for a walk's line.
std::string TimeSplit(const Plan& plan) {
  char line[160];
  std::snprintf(line, sizeof(line), "setup %.2f s, %d windows, %d nodes:", plan.setup_s, plan.windows, plan.nodes);
  std::string text = line;
  for (const WindowRecord& w : plan.window_records) {
    std::snprintf(line, sizeof(line), " [%d steps %s %d nodes, build %.2f search %.2f (heur %.2f) polish %.2f of %.2f s]",
                  w.new_steps, ToString(w.status).c_str(), w.nodes, w.build_s, w.search_s, w.heuristic_s, w.polish_s,
                  w.time_limit_s);
    text += line;
  }
  return text;
}

WalkResult RunWalk(const RobotModel& robot, Scenario scenario, const ScenarioTerrain& terrain,
                   const SeenVoxelJudge& judge, const RegionExtractionResult& diagnosis, const Walk& walk,
                   const ScanWalkOptions& o) {
  scenario.start = walk.start;
  scenario.goal = walk.goal;
  PlanRequest request = ScenarioRequest(scenario, robot, terrain);
  request.start_feet_world_m = walk.start_feet;
  request.time_limit_s = o.time_limit_s;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(scenario.options.solvers);
  const Plan plan = PlanFootsteps(robot, terrain.regions, request, scenario.options, solvers.workers());
  WalkResult r;
  for (const Eigen::Vector3d& f : request.start_feet_world_m) {
    bool on = false;
    for (const ConvexRegion& region : terrain.regions) on = on || RegionContains(region, f, scenario.options.start_tolerance_m);
    r.start_off_regions = r.start_off_regions || !on;
  }
  r.status = plan.status;
  r.goal_moved = plan.goal_moved;
  r.time_s = plan.solve_time_s;
  r.message = plan.message;
  r.time_split = TimeSplit(plan);
  for (size_t i = static_cast<size_t>(robot.num_legs()); i < plan.footsteps.size(); ++i) {
    const Footstep& step = plan.footsteps[i];
    double slack = 0.0;
    for (const ConvexRegion& region : terrain.regions) {
      if (region.id == step.region_id) slack = region.plane_tolerance_m;
    }
    if (!judge.Stands(step.position_world_m, slack)) {
      ++r.feet_off;
      if (o.verbose) {
        std::printf("    step %zu off the seen voxels: (%.3f, %.3f, %.3f), region %d (plane tolerance %.3f m); %s\n", i,
                    step.position_world_m.x(), step.position_world_m.y(), step.position_world_m.z(), step.region_id,
                    slack, judge.ColumnText(step.position_world_m).c_str());
      }
    }
  }
  r.valid_to_goal = HasPlan(plan.status) && plan.reaches_goal && r.feet_off == 0;
  if (!r.valid_to_goal) {
    r.start = DiagnoseEnd(robot, terrain.regions, judge, diagnosis, walk.start, o.cell_map_cells);
    r.goal = DiagnoseEnd(robot, terrain.regions, judge, diagnosis, walk.goal, o.cell_map_cells);
    r.goal.certifiable_stance_near = CertifiableStanceNear(robot, judge, walk.goal, scenario.options.goal_position_tolerance_m,
                                                           scenario.options.goal_heading_tolerance_rad);
    r.certifiable_route = EndsJoined(robot, judge, walk.start, walk.goal, walk.judge_step_m);
    if (r.certifiable_route) {
      r.leg_not_joined = LegNotJoinedAtItsHeight(robot, judge, walk.start, walk.goal, walk.judge_step_m);
    }
  }
  return r;
}

std::string BaseName(const std::string& path) { return path.substr(path.find_last_of('/') + 1); }

// The scan's regions, seen surface and body obstacles as LoadScenarioTerrain makes them,
// with the walks' extractor options; *diagnosis keeps the layers and each cell's fate
// (record_cell_fates: the regions do not depend on it) for the failed walks' causes.
ScenarioTerrain WalkTerrain(const Scenario& scenario, const RobotModel& robot, const ScanWalkOptions& o,
                            RegionExtractionResult* diagnosis) {
  RegionExtractorOptions options = ScenarioRegionOptions(scenario, robot);
  if (o.enclosed_unseen_radius_cells >= 0) options.enclosed_unseen_radius_cells = o.enclosed_unseen_radius_cells;
  if (o.convex_cover >= 0) options.convex_cover = o.convex_cover == 1;
  if (o.target_coverage >= 0.0) options.target_coverage = o.target_coverage;
  if (o.regions_per_m2 >= 0.0) options.regions_per_m2 = o.regions_per_m2;
  if (o.max_regions >= 0) options.max_regions = o.max_regions;
  options.record_cell_fates = true;
  RegionExtractionResult& result = *diagnosis;
  result = ExtractRegionsFromMapFile(scenario.map_path, options);
  ScenarioTerrain terrain;
  terrain.regions = result.regions;
  terrain.seen_surface = std::make_shared<const SeenSurface>(SeenSurfaceOfLayers(result.layers, result.moved_as_seen, result.filled));
  terrain.note = result.message;
  TakeBodyObstacles(result, &terrain);  // the map's obstacles to the body, as mfp-plan's
  return terrain;
}

// A failed walk's message names a place: a status that says where (a coordinate).
bool NamesPlace(const WalkResult& r) {
  for (size_t i = r.message.find('('); i != std::string::npos; i = r.message.find('(', i + 1)) {
    const char c = i + 1 < r.message.size() ? r.message[i + 1] : ' ';
    if (c == '-' || (c >= '0' && c <= '9')) return true;
  }
  return false;
}

// One population's walks (all walks, or the joined or unjoined ones) over the scans and robots.
struct Population {
  explicit Population(const char* population_name) : name(population_name) {}
  const char* name;
  int valid = 0, walks = 0;
  int failed_named = 0, failed = 0;  // failed walks whose status names a place
  std::map<std::string, int> causes;  // of the walks that failed
  std::map<std::string, int> statuses;  // of the walks that failed
};

// Plans the walks of one scan and robot, prints their row (and with o.verbose a line per walk).
void RunWalks(const std::string& scan, const RobotModel& robot, const Scenario& scenario, const ScenarioTerrain& terrain,
              const SeenVoxelJudge& judge, const RegionExtractionResult& diagnosis, const std::vector<Walk>& walks,
              const ScanWalkOptions& o, Population* population) {
  int valid = 0, moved = 0, feet_off = 0, start_off = 0, body_blocked = 0;
  size_t run = 0;  // walks planned (one with --walk-only)
  std::map<std::string, int> statuses;
  for (size_t k = 0; k < walks.size(); ++k) {
    if (o.only_walk >= 0 && static_cast<int>(k) != o.only_walk) continue;
    ++run;
    const Walk& w = walks[k];
    const WalkResult r = RunWalk(robot, scenario, terrain, judge, diagnosis, w, o);
    valid += r.valid_to_goal ? 1 : 0;
    body_blocked += w.start_body_voxels + w.goal_body_voxels > 0 ? 1 : 0;
    moved += r.goal_moved ? 1 : 0;
    start_off += r.start_off_regions ? 1 : 0;
    feet_off += r.feet_off;
    ++statuses[ToString(r.status)];
    if (!r.valid_to_goal) {
      ++population->causes[FailureCause(r)];
      ++population->statuses[ToString(r.status)];
      ++population->failed;
      population->failed_named += NamesPlace(r) ? 1 : 0;
    }
    if (o.verbose) {
      std::printf("  %s %s (%.2f, %.2f, %.2f) -> (%.2f, %.2f, %.2f): %s%s, %d feet off, %.1f s, body voxels "
                  "%d / %d: %s\n",
                  BaseName(scan).c_str(), robot.name.c_str(), w.start.x_m, w.start.y_m, w.start.yaw_rad, w.goal.x_m,
                  w.goal.y_m, w.goal.yaw_rad, ToString(r.status).c_str(), r.valid_to_goal ? " valid to goal" : "",
                  r.feet_off, r.time_s, w.start_body_voxels, w.goal_body_voxels, r.message.substr(0, 800).c_str());
      std::printf("    time: %s\n", r.time_split.c_str());
      if (!r.valid_to_goal) {
        std::printf("    cause: %s; %s; %s; certifiable floor joins the ends by steps: %s\n", FailureCause(r).c_str(),
                    EndText("start", r.start).c_str(), EndText("goal", r.goal).c_str(),
                    !r.certifiable_route ? "no"
                    : r.leg_not_joined < 0 ? "yes"
                                           : ("yes, but not leg " + std::to_string(r.leg_not_joined) +
                                              "'s way: certifiable floor within dz_max of its start spot's height does "
                                              "not reach its goal spot's").c_str());
        for (const std::string& d : r.start.details) std::printf("      start %s\n", d.c_str());
        for (const std::string& d : r.goal.details) std::printf("      goal %s\n", d.c_str());
      }
    }
  }
  std::string list;
  for (const auto& [name, count] : statuses) list += (list.empty() ? "" : ", ") + name + " " + std::to_string(count);
  std::printf("%-8s %-20s %-10s %5zu %6d %9d %6d %8d %9d  %s\n", population->name, BaseName(scan).c_str(),
              robot.name.c_str(), run, valid, start_off, moved, feet_off, body_blocked, list.c_str());
  std::fflush(stdout);
  population->valid += valid;
  population->walks += static_cast<int>(run);
}

void PrintPopulation(const Population& p) {
  std::printf("%s: valid to the goal: %d of %d walks; of the %d that failed, %d end with a status naming a place\n",
              p.name, p.valid, p.walks, p.failed, p.failed_named);
  std::string list;
  for (const auto& [name, count] : p.statuses) list += (list.empty() ? "" : ", ") + name + " " + std::to_string(count);
  std::printf("  failed statuses: %s\n", list.c_str());
  std::printf("  failures by cause (certifiable floor: seen floor within a voxel of the foot's height for the foot "
              "radius + 1 cm + one voxel around it, as the union of its columns' squares):\n");
  for (const auto& [cause, count] : p.causes) std::printf("  %3d  %s\n", count, cause.c_str());
}

}  // namespace

unsigned WalkDrawSeed(unsigned seed, const std::string& scan_path, const std::string& robot_name) {
  return seed ^ static_cast<unsigned>(std::hash<std::string>{}(BaseName(scan_path) + robot_name));
}

std::vector<std::pair<Pose2D, Pose2D>> DrawWalkEnds(const OccupancyMap& map, const std::string& scan_path,
                                                    const std::string& robot_path, const ScanWalkOptions& o) {
  const RobotModel robot = LoadRobot(robot_path, ReachShape::kBox);
  const SeenVoxelJudge judge(map, robot.stance_height_m + Scenario{}.options.body_clearance_margin_m);
  std::vector<Walk> walks, unjoined;
  DrawWalks(robot, judge, map.resolution_m, o, WalkDrawSeed(o.seed, scan_path, robot.name), &walks, &unjoined);
  std::vector<std::pair<Pose2D, Pose2D>> ends;
  for (const std::vector<Walk>* list : {&walks, &unjoined}) {
    for (const Walk& w : *list) ends.emplace_back(w.start, w.goal);
  }
  return ends;
}

int LegNotJoinedAtItsHeight(const OccupancyMap& map, const std::string& robot_path, const Pose2D& start,
                            const Pose2D& goal) {
  const RobotModel robot = LoadRobot(robot_path, ReachShape::kBox);
  const SeenVoxelJudge judge(map, robot.stance_height_m + Scenario{}.options.body_clearance_margin_m);
  return LegNotJoinedAtItsHeight(robot, judge, start, goal, JudgeStep(robot));
}

int BenchScanWalks(const std::vector<std::string>& scans, const std::vector<std::string>& robots,
                   const ScanWalkOptions& o) {
  std::printf("walks on real scans: %d per scan and robot, %.0f-%.0f m between %s stances%s, %.0f s each; "
              "valid = reaches the goal (or the goal moved within its tolerance) with every footstep on a voxel "
              "seen from above with room above it, within a voxel plus its region's plane tolerance (raw voxels)\n",
              o.walks, o.min_length_m, o.max_length_m, o.certifiable_ends ? "certifiable-floor" : "seen-floor",
              o.joined_ends ? " joined by certifiable floor (unjoined: a second population)" : "", o.time_limit_s);
  std::printf("%-8s %-20s %-10s %5s %6s %9s %6s %8s %9s  %s\n", "walks", "scan", "robot", "walks", "valid", "start_off",
              "moved", "feet_off", "body_ends", "statuses");
  Population drawn(o.joined_ends ? "joined" : "all"), unjoined_walks("unjoined");
  for (const std::string& scan : scans) {
    const OccupancyMap map = LoadMapFile(scan);
    for (const std::string& robot_path : robots) {
      // The draw and the judge use the box-derived robot (EndsJoined); the planner the
      // chosen reach shape.
      const RobotModel box_robot = LoadRobot(robot_path, ReachShape::kBox);
      const RobotModel robot = o.reach_shape ? LoadRobot(robot_path, *o.reach_shape) : LoadRobot(robot_path);
      Scenario scenario;
      scenario.map_path = scan;
      scenario.robot_path = robot_path;
      RegionExtractionResult diagnosis;
      const ScenarioTerrain terrain = WalkTerrain(scenario, robot, o, &diagnosis);
      const SeenVoxelJudge judge(map, robot.stance_height_m + scenario.options.body_clearance_margin_m);
      std::vector<Walk> walks, unjoined;
      DrawWalks(box_robot, judge, map.resolution_m, o, WalkDrawSeed(o.seed, scan, robot.name), &walks, &unjoined);
      RunWalks(scan, robot, scenario, terrain, judge, diagnosis, walks, o, &drawn);
      if (o.joined_ends) RunWalks(scan, robot, scenario, terrain, judge, diagnosis, unjoined, o, &unjoined_walks);
    }
  }
  PrintPopulation(drawn);
  if (o.joined_ends) PrintPopulation(unjoined_walks);
  return drawn.valid;
}

}  // namespace mfp

#include "planner/planning/internal/stance_route.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <queue>
#include <utility>

#include "geometry/plan_bounds.h"
#include "planner/robot/body_obstacle_index.h"
#include "planner/robot/reach_polygon.h"

namespace mfp {
namespace {

// A* expansions (and raster regions) between two deadline checks: a clock read per few
// hundred cheap steps.
constexpr int kChecksEvery = 256;


// Cells of a raster: 2 where a region holds the point, 1 where one lies within `radius`
// (a foot's reference box meets support there), 0 elsewhere.
struct SupportRaster {
  Eigen::Vector2d origin;
  double res = 0.02;
  int nx = 0, ny = 0;
  std::vector<uint8_t> cells;
  std::vector<float> heights;  // highest region through the cell's centre where it is 2 [m]
  long Index(const Eigen::Vector2d& p) const {
    const int i = static_cast<int>(std::floor((p.x() - origin.x()) / res));
    const int j = static_cast<int>(std::floor((p.y() - origin.y()) / res));
    if (i < 0 || j < 0 || i >= nx || j >= ny) return -1;
    return static_cast<long>(j) * nx + i;
  }
  int At(const Eigen::Vector2d& p) const {
    const long k = Index(p);
    return k < 0 ? 0 : cells[static_cast<size_t>(k)];
  }
};

// nullopt when the deadline passes first.
std::optional<SupportRaster> MakeSupportRaster(const std::vector<ConvexRegion>& regions, const Eigen::Vector2d& lo,
                                               const Eigen::Vector2d& hi, double res, double radius,
                                               const Deadline& deadline) {
  SupportRaster s;
  s.origin = lo;
  s.res = res;
  s.nx = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / res)));
  s.ny = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / res)));
  s.cells.assign(static_cast<size_t>(s.nx) * s.ny, 0);
  s.heights.assign(s.cells.size(), -std::numeric_limits<float>::infinity());
  for (const ConvexRegion& r : regions) {
    if (deadline.Expired()) return std::nullopt;
    const Eigen::AlignedBox2d bounds = PlanBounds(r);
    const Eigen::Vector2d rlo = bounds.min(), rhi = bounds.max();
    const int i0 = std::max(0, static_cast<int>(std::floor((rlo.x() - radius - lo.x()) / res)));
    const int i1 = std::min(s.nx - 1, static_cast<int>(std::floor((rhi.x() + radius - lo.x()) / res)));
    const int j0 = std::max(0, static_cast<int>(std::floor((rlo.y() - radius - lo.y()) / res)));
    const int j1 = std::min(s.ny - 1, static_cast<int>(std::floor((rhi.y() + radius - lo.y()) / res)));
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const size_t k = static_cast<size_t>(j) * s.nx + i;
        uint8_t& c = s.cells[k];
        const Eigen::Vector2d p = lo + res * Eigen::Vector2d(i + 0.5, j + 0.5);
        const double d = PlanDistanceToRegion(r, p);
        if (d <= 0.0) {
          c = 2;
          s.heights[k] = std::max(s.heights[k], static_cast<float>(r.HeightAt(p.x(), p.y())));
        } else if (d <= radius && c != 2) {  // a cell held by one region stays held
          c = 1;
        }
      }
    }
  }
  return s;
}


// The body positions' grid: over the regions, start and goal, padded by how far a body
// stands beyond its feet (reach + l_bnd), cells coarsened to at most options.max_cells.
struct BodyGrid {
  Eigen::Vector2d lo, hi;  // [m, world]
  double cell = 0.0;       // [m]
  int nx = 1, ny = 1;
};

BodyGrid MakeBodyGrid(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                      const Eigen::Vector2d& start_xy, const Eigen::Vector2d& goal_xy,
                      const StanceRouteOptions& options) {
  BodyGrid g;
  double reach = 0.0;
  for (const auto& leg : robot.legs) reach = std::max(reach, leg.nominal_offset_body_m.norm());
  Eigen::AlignedBox2d box(start_xy.cwiseMin(goal_xy), start_xy.cwiseMax(goal_xy));
  for (const ConvexRegion& r : regions) box.extend(PlanBounds(r));
  g.lo = box.min();
  g.hi = box.max();
  const double pad = reach + robot.l_bnd_m;
  g.lo -= Eigen::Vector2d::Constant(pad);
  g.hi += Eigen::Vector2d::Constant(pad);
  g.cell = options.cell_m;
  const double area = (g.hi - g.lo).prod();
  if (area / (g.cell * g.cell) > static_cast<double>(options.max_cells)) g.cell = std::sqrt(area / options.max_cells);
  g.nx = std::max(1, static_cast<int>(std::ceil((g.hi.x() - g.lo.x()) / g.cell)));
  g.ny = std::max(1, static_cast<int>(std::ceil((g.hi.y() - g.lo.y()) / g.cell)));
  return g;
}

// The body check of a pose (stance_route.h): obstacles near the pose judged against the
// body's plan box in its height band above the pose's ground, and against that box grown
// by the route's body margin in plan view. The obstacles near a grid cell do not depend on
// the heading, so they are looked up once per cell (cells: the body grid's cell count).
class BodyGate {
 public:
  enum class Room { kClear, kTight, kBlocked };

  BodyGate(const RobotModel& robot, const std::vector<BodyObstacle>& obstacles, const SupportRaster& support,
           double ground_z_m, double overlap_share, double margin_m, size_t cells)
      : robot_(robot), obstacles_(obstacles), support_(support), ground_z_m_(ground_z_m), share_(overlap_share) {
    const BodyExtent& body = robot.body;
    active_ = body.known() && !obstacles.empty();
    grown_ = body;
    grown_.min_m -= Eigen::Vector2d::Constant(std::max(0.0, margin_m));
    grown_.max_m += Eigen::Vector2d::Constant(std::max(0.0, margin_m));
    radius_m_ = BodyRadius(grown_);
    // A pose looks only at the buckets its radius reaches.
    if (active_) {
      index_ = BodyObstacleIndex(obstacles, std::max(radius_m_, kBodyBucketMinM));
      near_.resize(cells);
      near_known_.assign(cells, 0);
    }
  }
  bool active() const { return active_; }

  // kBlocked: the body at (c, yaw), c the centre of grid cell `cell`, overlaps an obstacle
  // in its band; kTight: only the grown body does.
  Room RoomAt(size_t cell, const Eigen::Vector2d& c, double yaw) {
    if (!active_) return Room::kClear;
    if (!near_known_[cell]) {
      near_[cell] = index_.Near(c, radius_m_);
      near_known_[cell] = 1;
    }
    const std::vector<int>& near = near_[cell];
    if (near.empty()) return Room::kClear;
    const double ground = Ground(c, yaw);
    if (BodyOverlapShare(grown_, obstacles_, near, c.x(), c.y(), yaw, ground) <= 0.0) return Room::kClear;
    return BodyOverlapShare(robot_.body, obstacles_, near, c.x(), c.y(), yaw, ground) > share_ ? Room::kBlocked
                                                                                              : Room::kTight;
  }

 private:
  // Mean height of the regions under the nominal feet; the fallback where none is.
  double Ground(const Eigen::Vector2d& c, double yaw) const {
    double sum = 0.0;
    int count = 0;
    for (int leg = 0; leg < robot_.num_legs(); ++leg) {
      const long k = support_.Index(NominalFootXY(robot_, leg, c.x(), c.y(), yaw));
      if (k < 0 || !std::isfinite(support_.heights[static_cast<size_t>(k)])) continue;
      sum += support_.heights[static_cast<size_t>(k)];
      ++count;
    }
    return count > 0 ? sum / count : ground_z_m_;
  }

  const RobotModel& robot_;
  const std::vector<BodyObstacle>& obstacles_;
  const SupportRaster& support_;
  BodyExtent grown_;  // the body box grown by the margin in plan view
  double ground_z_m_, share_, radius_m_ = 0.0;
  bool active_ = false;
  BodyObstacleIndex index_;
  std::vector<std::vector<int>> near_;  // per body grid cell: the obstacles near its centre
  std::vector<uint8_t> near_known_;     // per body grid cell: near_ holds its lookup
};


// What the searches of one PlanStanceRoute share (the same body grid and support): the
// support raster, the body gate with its per-cell obstacle lookups, and each pose's class
// at the finest heading count searched, so the search with fine headings does not judge
// again the poses the coarse search judged (their yaws are the same numbers).
struct StanceSpace {
  StanceSpace(const RobotModel& robot, const BodyGrid& body_grid, SupportRaster raster,
              const std::vector<BodyObstacle>& body_obstacles, double ground_z_m, const StanceRouteOptions& options)
      : grid(body_grid), support(std::move(raster)),
        gate(robot, body_obstacles, support, ground_z_m, options.body_overlap_share, options.body_margin_m,
             static_cast<size_t>(grid.nx) * grid.ny),
        headings(std::max({1, options.headings, options.fine_headings})),
        classes(static_cast<size_t>(grid.nx) * grid.ny * headings, 0) {}
  StanceSpace(const StanceSpace&) = delete;
  StanceSpace& operator=(const StanceSpace&) = delete;

  // The index into `classes` of heading h of H, or -1 when its yaw is not one of the
  // shared headings' yaws exactly.
  int SharedHeading(int h, int H) const {
    if (headings % H != 0) return -1;
    const int f = h * (headings / H);
    return HeadingYaw(h, H) == HeadingYaw(f, headings) ? f : -1;
  }
  static double HeadingYaw(int h, int H) { return h * 2 * M_PI / H; }

  // The class of the pose at cell `cell` (centre c) with heading h of H: 1 every nominal
  // foot on a region, 2 every reference box meets one or the body is tight, 3 a reference
  // box meets none, 4 refused by the body check alone. shared: SharedHeading(h, H).
  uint8_t Judge(const RobotModel& robot, size_t cell, const Eigen::Vector2d& c, int h, int H, int shared) {
    uint8_t* known = shared >= 0 ? &classes[cell * headings + shared] : nullptr;
    if (known != nullptr && *known != 0) return *known;
    const double yaw = HeadingYaw(h, H);
    int worst = 2;
    for (int leg = 0; leg < robot.num_legs() && worst > 0; ++leg) {
      worst = std::min(worst, support.At(NominalFootXY(robot, leg, c.x(), c.y(), yaw)));
    }
    uint8_t judged = static_cast<uint8_t>(3 - worst);
    if (judged < 3) {
      const BodyGate::Room room = gate.RoomAt(cell, c, yaw);
      if (room == BodyGate::Room::kBlocked) {
        judged = 4;
      } else if (room == BodyGate::Room::kTight) {
        judged = 2;
      }
    }
    if (known != nullptr) *known = judged;
    return judged;
  }

  BodyGrid grid;
  SupportRaster support;
  BodyGate gate;
  int headings;  // of `classes`
  // Per (cell, heading): 0 not judged yet, 1-3 the search's pose classes (SearchStances),
  // 4 class 3 by the body check alone.
  std::vector<uint8_t> classes;
};

// nullptr when the deadline passes while the support raster is built.
std::unique_ptr<StanceSpace> MakeStanceSpace(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                             const std::vector<BodyObstacle>& body_obstacles, double ground_z_m,
                                             const Eigen::Vector2d& start_xy, const Eigen::Vector2d& goal_xy,
                                             const StanceRouteOptions& options, const Deadline& deadline) {
  const BodyGrid grid = MakeBodyGrid(robot, regions, start_xy, goal_xy, options);
  // Support within l_bnd of a foot (for the footprint shape, within the polygon's inscribed
  // disk about the nominal foot, where its reference rows let a foot stand at any yaw); the
  // raster finer than the body grid.
  const double res = std::max(0.005, std::min(0.5 * robot.l_bnd_m, 0.5 * grid.cell));
  const double reference = robot.reach_shape == ReachShape::kFootprint ? FootprintInscribedReach(robot) : robot.l_bnd_m;
  std::optional<SupportRaster> raster =
      MakeSupportRaster(regions, grid.lo, grid.hi, res, options.support_radius_l_bnd * reference, deadline);
  if (!raster) return nullptr;
  return std::make_unique<StanceSpace>(robot, grid, std::move(*raster), body_obstacles, ground_z_m, options);
}

// The found route: the given start and goal poses with the searched cells' centres and
// yaws between them (cells and yaws from the start's cell to the goal's).
void SetRoute(const std::vector<Eigen::Vector2d>& cells, const std::vector<double>& yaws,
              const Eigen::Vector2d& start_xy, double start_yaw_rad, const Eigen::Vector2d& goal_xy,
              double goal_yaw_rad, StanceRoute* out) {
  out->route.push_back(start_xy);
  out->yaws_rad.push_back(cells.size() > 1 ? yaws.front() : start_yaw_rad);
  for (size_t k = 1; k + 1 < cells.size(); ++k) {
    out->route.push_back(cells[k]);
    out->yaws_rad.push_back(yaws[k]);
  }
  out->route.push_back(goal_xy);
  out->yaws_rad.push_back(goal_yaw_rad);
  for (size_t k = 1; k < out->route.size(); ++k) out->length_m += (out->route[k] - out->route[k - 1]).norm();
  out->found = true;
}


// A* over the poses of `space` with `headings` yaws (stance_route.h).
StanceRoute SearchStances(const RobotModel& robot, StanceSpace* space, const Eigen::Vector2d& start_xy,
                          double start_yaw_rad, const Eigen::Vector2d& goal_xy, double goal_yaw_rad, int headings,
                          const StanceRouteOptions& options, const Deadline& deadline) {
  StanceRoute out;
  const int H = std::max(1, headings);
  const BodyGrid& grid = space->grid;
  const Eigen::Vector2d lo = grid.lo;
  const double cell = grid.cell;
  const int nx = grid.nx, ny = grid.ny;
  std::vector<int> shared(static_cast<size_t>(H));
  for (int h = 0; h < H; ++h) shared[static_cast<size_t>(h)] = space->SharedHeading(h, H);
  auto heading_of = [&](double yaw) {
    const double u = std::remainder(yaw, 2 * M_PI);
    return ((static_cast<int>(std::lround(u / (2 * M_PI / H))) % H) + H) % H;
  };
  auto cell_of = [&](const Eigen::Vector2d& p, int* i, int* j) {
    *i = std::clamp(static_cast<int>(std::floor((p.x() - lo.x()) / cell)), 0, nx - 1);
    *j = std::clamp(static_cast<int>(std::floor((p.y() - lo.y()) / cell)), 0, ny - 1);
  };
  auto centre_of = [&](int i, int j) { return Eigen::Vector2d(lo + cell * Eigen::Vector2d(i + 0.5, j + 0.5)); };
  const size_t states = static_cast<size_t>(nx) * ny * H;
  auto id = [&](int i, int j, int h) { return (static_cast<size_t>(j) * nx + i) * H + h; };
  int si, sj, gi, gj;
  cell_of(start_xy, &si, &sj);
  cell_of(goal_xy, &gi, &gj);
  const int sh = heading_of(start_yaw_rad), gh = heading_of(goal_yaw_rad);
  const size_t start = id(si, sj, sh);
  // Per pose: 0 unknown, 1 every nominal foot on a region, 2 every reference box meets
  // one or the body clears obstacles by less than the margin (usable, at a higher cost:
  // such poses leave no room), 3 not usable.
  std::vector<uint8_t> usable(states, 0);
  auto pose_class = [&](int i, int j, int h) {
    uint8_t& u = usable[id(i, j, h)];
    if (u == 0) {
      ++out.classified_poses;
      const uint8_t judged = space->Judge(robot, static_cast<size_t>(j) * nx + i, centre_of(i, j), h, H,
                                          shared[static_cast<size_t>(h)]);
      if (judged == 4) {
        ++out.body_blocked_poses;
        const Eigen::Vector2d p = centre_of(i, j);
        const Eigen::Vector2d& nearest = out.body_blocked_nearest_goal_m;
        if (std::isnan(nearest.x()) || (p - goal_xy).norm() < (nearest - goal_xy).norm()) {
          out.body_blocked_nearest_goal_m = p;
        }
      }
      u = judged == 4 ? 3 : judged;
    }
    return u;
  };
  const double turn_cost = options.turn_cost_m;
  // float and 32-bit parents: at most 8 x 300,000 states, 8 bytes each.
  constexpr uint32_t kNone = UINT32_MAX;
  if (states >= kNone) return out;  // more headings than any caller asks for
  std::vector<float> dist(states, std::numeric_limits<float>::infinity());
  std::vector<uint32_t> parent(states, kNone);
  // Expanded poses: a pose is expanded once, and a closed pose is not queued again.
  std::vector<bool> closed(states, false);
  using Item = std::pair<double, size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  auto heuristic = [&](int i, int j) { return (centre_of(i, j) - centre_of(gi, gj)).norm(); };
  dist[start] = 0.0;
  open.push({heuristic(si, sj), start});
  size_t reached = SIZE_MAX;
  int until_check = kChecksEvery;
  while (!open.empty()) {
    if (--until_check == 0) {
      until_check = kChecksEvery;
      if (deadline.Expired()) {
        out.out_of_time = true;
        return out;
      }
    }
    const size_t s = open.top().second;
    open.pop();
    const int h = static_cast<int>(s % H);
    const size_t cellid = s / H;
    const int i = static_cast<int>(cellid % nx), j = static_cast<int>(cellid / nx);
    if (closed[s]) continue;
    closed[s] = true;
    ++out.expanded_poses;
    // Any heading at the goal cell: the windows turn to the goal yaw there.
    if (i == gi && j == gj) {
      reached = s;
      break;
    }
    auto relax = [&](int i2, int j2, int h2, double w) {
      const size_t t = id(i2, j2, h2);
      if (closed[t]) return;
      const bool endpoint = (i2 == gi && j2 == gj && h2 == gh);
      const uint8_t c = endpoint ? 1 : pose_class(i2, j2, h2);
      if (c == 3) return;
      if (c == 2) w *= options.tight_cost_factor;
      // Compared as stored: a sum rounded up to float would pass a double `<` again.
      const float via = static_cast<float>(dist[s] + w);
      if (via < dist[t]) {
        dist[t] = via;
        parent[t] = static_cast<uint32_t>(s);
        open.push({dist[t] + heuristic(i2, j2), t});
      }
    };
    for (int di = -1; di <= 1; ++di) {
      for (int dj = -1; dj <= 1; ++dj) {
        if (di == 0 && dj == 0) continue;
        const int i2 = i + di, j2 = j + dj;
        if (i2 < 0 || j2 < 0 || i2 >= nx || j2 >= ny) continue;
        relax(i2, j2, h, cell * std::sqrt(static_cast<double>(di * di + dj * dj)));
      }
    }
    relax(i, j, (h + 1) % H, turn_cost);
    relax(i, j, (h + H - 1) % H, turn_cost);
  }
  if (reached == SIZE_MAX) return out;
  // Positions and the yaw the body leaves each with (a turn in place keeps the later).
  std::vector<Eigen::Vector2d> cells;
  std::vector<double> yaws;
  // Route poses the body cannot hold at the goal's heading (a foot off support or the body
  // blocked; not counted in body_blocked_poses): windows aiming at that yaw leave the route.
  const long blocked_by_search = out.body_blocked_poses;
  const Eigen::Vector2d blocked_nearest_goal = out.body_blocked_nearest_goal_m;
  for (size_t s = reached; s != SIZE_MAX; s = parent[s] == kNone ? SIZE_MAX : parent[s]) {
    const size_t c = s / H;
    const int ci = static_cast<int>(c % nx), cj = static_cast<int>(c / nx);
    const Eigen::Vector2d p = centre_of(ci, cj);
    if (cells.empty() || (cells.back() - p).norm() > 1e-12) {
      cells.push_back(p);
      yaws.push_back(static_cast<double>(s % H) * 2 * M_PI / H);
      const bool inner = !(ci == si && cj == sj) && !(ci == gi && cj == gj);
      out.goal_yaw_unusable_poses += inner && pose_class(ci, cj, gh) == 3;
    }
  }
  out.body_blocked_poses = blocked_by_search;
  out.body_blocked_nearest_goal_m = blocked_nearest_goal;
  std::reverse(cells.begin(), cells.end());
  std::reverse(yaws.begin(), yaws.end());
  SetRoute(cells, yaws, start_xy, start_yaw_rad, goal_xy, goal_yaw_rad, &out);
  return out;
}


}  // namespace

StanceRoute PlanStanceRoute(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                            const Eigen::Vector2d& start_xy, double start_yaw_rad, const Eigen::Vector2d& goal_xy,
                          double goal_yaw_rad, const StanceRouteOptions& options, const Deadline& deadline) {
  return PlanStanceRoute(robot, regions, {}, 0.0, start_xy, start_yaw_rad, goal_xy, goal_yaw_rad, options, deadline);
}

StanceRoute PlanStanceRoute(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                            const std::vector<BodyObstacle>& body_obstacles, double ground_z_m,
                            const Eigen::Vector2d& start_xy, double start_yaw_rad, const Eigen::Vector2d& goal_xy,
                          double goal_yaw_rad, const StanceRouteOptions& options, const Deadline& deadline) {
  const std::unique_ptr<StanceSpace> space =
      MakeStanceSpace(robot, regions, body_obstacles, ground_z_m, start_xy, goal_xy, options, deadline);
  if (space == nullptr) {
    StanceRoute out_of_time;
    out_of_time.out_of_time = true;
    return out_of_time;
  }
  StanceRoute route = SearchStances(robot, space.get(), start_xy, start_yaw_rad, goal_xy, goal_yaw_rad,
                                    options.headings, options, deadline);
  // Where the body check refused poses, finer headings let the body turn to fit.
  if (route.body_blocked_poses > 0 && options.headings < options.fine_headings && !route.out_of_time) {
    StanceRoute finer = SearchStances(robot, space.get(), start_xy, start_yaw_rad, goal_xy, goal_yaw_rad,
                                      options.fine_headings, options, deadline);
    if (finer.found || !route.found) route = std::move(finer);
  }
  return route;
}

StanceRoute PlanStanceRouteWithFallbacks(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                         const std::vector<BodyObstacle>& body_obstacles, double ground_z_m,
                                         const Eigen::Vector2d& start_xy, double start_yaw_rad,
                                         const Eigen::Vector2d& goal_xy, double goal_yaw_rad,
                                         const StanceRouteOptions& options, const Deadline& deadline) {
  StanceRoute stances = PlanStanceRoute(robot, regions, body_obstacles, ground_z_m, start_xy, start_yaw_rad, goal_xy,
                                        goal_yaw_rad, options, deadline);
  if (!stances.found && !stances.out_of_time) {
    // Where no pose has every reference box surely on support, poses whose boxes may
    // meet it (an octopod on stones laid for its feet: the region graph's route through
    // region centres zig-zagged across the tracks, 2.45 m short).
    StanceRouteOptions loose = options;
    loose.support_radius_l_bnd = std::max(options.support_radius_l_bnd, std::sqrt(2.0));
    stances = PlanStanceRoute(robot, regions, body_obstacles, ground_z_m, start_xy, start_yaw_rad, goal_xy,
                              goal_yaw_rad, loose, deadline);
  }
  if (!stances.found && !stances.out_of_time && stances.body_blocked_poses > 0 &&
      options.body_blocked_cell_m < options.cell_m) {
    // A passage only a little wider than the body: a finer grid of body positions.
    StanceRouteOptions fine = options;
    fine.cell_m = options.body_blocked_cell_m;
    StanceRoute finer = PlanStanceRoute(robot, regions, body_obstacles, ground_z_m, start_xy, start_yaw_rad, goal_xy,
                                        goal_yaw_rad, fine, deadline);
    if (finer.found || finer.out_of_time) stances = std::move(finer);
  }
  return stances;
}

}  // namespace mfp

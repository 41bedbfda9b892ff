// Issue 25 in the daemon: its map stage keeps the surface the map saw from above beside the
// regions, and its requests accept a start foot on that surface where no region holds it
// (the robot stands there), as mfp-plan does; a foot in the air is still invalid_start,
// naming the nearest seen surface; a goal beyond reach of every region is answered from the
// planning thread naming the nearest stance on regions, as mfp-plan answers it. Driven over
// memq:// with the real map reader and planner.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "daemon/daemon_config.h"
#include "daemon/daemon_core.h"
#include "daemon/daemon_runner.h"
#include "daemon/daemon_setup.h"
#include "daemon/map_regions.h"
#include "daemon/message_conversion.h"
#include "daemon/solver_plan_function.h"
#include "geometry/convex_region.h"
#include "lcmtypes/lcm_transport.h"
#include "lcmtypes/message_guard.h"
#include "mfp/plan_request_t.hpp"
#include "mfp/plan_t.hpp"
#include "mfp/region_set_t.hpp"
#include "mfp/terrain_map_t.hpp"
#include "planner/qp/relaxation_solver_factory.h"
#include "terrain/extraction/map_simulation.h"
#include "terrain/octomap/octomap_io.h"

namespace mfp {
namespace {

// A 3 m x 2 m floor slab, top at z = 0, voxelised at 2 cm.
std::string FloorMapBytes() {
  TerrainDescription t;
  TerrainBox floor;
  floor.name = "floor";
  floor.center_world_m = {0.5, 0.0, -0.1};
  floor.size_m = {3.0, 2.0, 0.2};
  t.boxes.push_back(floor);
  const std::vector<uint8_t> bytes = OccupancyMapBytes(MakeTerrainMap(t), true);
  return std::string(bytes.begin(), bytes.end());
}
constexpr double kFloorEdgeY = 1.0;  // the slab's +y side [m]

// goal_pinned: goal tolerances 0, so a goal spot off the regions is not moved onto them.
std::shared_ptr<const DaemonSetup> HexapodSetup(bool goal_pinned = false) {
  DaemonConfig config;
  if (goal_pinned) {
    config.planner.goal_position_tolerance_m = 0.0;
    config.planner.goal_heading_tolerance_rad = 0.0;
  }
  config.file = "test";
  config.robot_files = {std::string(MFP_SOURCE_DIR) + "/config/robots/hexapod.yaml"};
  config.default_robot = "hexapod";
  config.limits.max_map_bytes = 1 << 22;
  return std::make_shared<const DaemonSetup>(LoadDaemonSetup(config));
}

template <class Message>
std::vector<uint8_t> Encode(const Message& m) {
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// The robot's nominal stance with its body centre at (0, centre_y), yaw 0: request `id`
// to walk 0.3 m along x.
plan_request_t StanceRequest(const RobotModel& robot, double centre_y, int64_t id) {
  plan_request_t m{};
  m.utime = 1;
  m.request_id = id;
  m.num_legs = robot.num_legs();
  for (const LegModel& leg : robot.legs) {
    m.start_feet.push_back({leg.nominal_offset_body_m.x(), centre_y + leg.nominal_offset_body_m.y(), 0.0});
  }
  m.goal_x = 0.3;
  m.goal_y = centre_y;
  m.time_limit_s = 20.0;
  return m;
}

double LargestFootY(const RobotModel& robot) {
  double y = -1e9;
  for (const LegModel& leg : robot.legs) y = std::max(y, leg.nominal_offset_body_m.y());
  return y;
}

bool OnSomeRegion(const std::vector<ConvexRegion>& regions, const Eigen::Vector3d& p, double tolerance_m) {
  for (const ConvexRegion& r : regions) {
    if (RegionContains(r, p, tolerance_m)) return true;
  }
  return false;
}

class DaemonSeenSurfaceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    setup_ = HexapodSetup();
    map_bytes_ = FloorMapBytes();
    transport_.Subscribe(kRegionsChannel, [this](const RawMessage& raw) {
      region_set_t m;
      ASSERT_EQ(DecodeGuarded(raw.data, raw.size, 1 << 22, &m), "");
      std::lock_guard<std::mutex> lock(mutex_);
      region_sets_.push_back(m);
    });
    transport_.Subscribe(kPlanChannel, [this](const RawMessage& raw) {
      plan_t m;
      ASSERT_EQ(DecodeGuarded(raw.data, raw.size, 1 << 22, &m), "");
      std::lock_guard<std::mutex> lock(mutex_);
      replies_[m.request_id] = m;
    });
  }

  // Sends the floor map and a request, and returns its reply (status -1: none in 60 s).
  plan_t PlanOnFloor(const plan_request_t& request) {
    DaemonCore core(setup_, map_function_ ? map_function_ : MakeOctomapMapFunction(*setup_), MakeSolverPlanFunction(), transport_,
                    [] { return std::chrono::duration_cast<std::chrono::microseconds>(
                                    std::chrono::steady_clock::now().time_since_epoch()).count(); });
    core.SubscribeTo(transport_);
    DaemonRunner runner(core, transport_, 0.2);
    terrain_map_t map{};
    map.utime = 5;
    map.frame = "world";
    map.format = "bt";
    map.data.assign(map_bytes_.begin(), map_bytes_.end());
    map.num_bytes = static_cast<int32_t>(map.data.size());
    const std::vector<uint8_t> map_message = Encode(map);
    EXPECT_TRUE(transport_.Publish(kTerrainMapChannel, map_message.data(), map_message.size()));
    for (int i = 0; i < 1000 && core.counters().maps == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_EQ(core.counters().maps, 1);
    const std::vector<uint8_t> bytes = Encode(request);
    EXPECT_TRUE(transport_.Publish(kPlanRequestChannel, bytes.data(), bytes.size()));
    for (int i = 0; i < 6000; ++i) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        const auto it = replies_.find(request.request_id);
        if (it != replies_.end()) return it->second;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    plan_t none{};
    none.status = -1;
    return none;
  }

  const RobotModel& robot() const { return setup_->robots.at("hexapod"); }

  LcmTransport transport_{"memq://", 1 << 22};
  std::shared_ptr<const DaemonSetup> setup_;
  std::string map_bytes_;
  std::mutex mutex_;
  std::map<int64_t, plan_t> replies_;
  std::vector<region_set_t> region_sets_;  // MFP_REGIONS, in order of arrival
  MapFunction map_function_;               // empty: the real OctoMap map stage
};

TEST_F(DaemonSeenSurfaceTest, TheMapStageKeepsTheSeenSurfaceBesideTheRegions) {
  const MapTerrain terrain = MakeOctomapMapFunction(*setup_)(map_bytes_, "bt", "floor");
  ASSERT_FALSE(terrain.regions.empty());
  ASSERT_NE(terrain.seen_surface, nullptr);
  // 1 cm inside the slab's edge: seen from above, but inside the regions' inset.
  const Eigen::Vector3d near_edge(0.0, kFloorEdgeY - 0.01, 0.0);
  EXPECT_TRUE(OnSeenSurface(*terrain.seen_surface, near_edge, 0.02));
  EXPECT_FALSE(OnSomeRegion(terrain.regions, near_edge, setup_->config.planner.start_tolerance_m));
  EXPECT_FALSE(OnSeenSurface(*terrain.seen_surface, Eigen::Vector3d(0.0, kFloorEdgeY + 0.2, 0.0), 0.02));
}

TEST_F(DaemonSeenSurfaceTest, AStartFootOnTheSeenFloorOffTheRegionsIsPlannedFrom) {
  // The outermost feet 1 cm inside the slab's edge.
  const plan_request_t request = StanceRequest(robot(), kFloorEdgeY - 0.01 - LargestFootY(robot()), 7);
  const MapTerrain terrain = MakeOctomapMapFunction(*setup_)(map_bytes_, "bt", "floor");
  bool some_foot_off_regions = false;
  for (const auto& f : request.start_feet) {
    const Eigen::Vector3d p(f[0], f[1], f[2]);
    some_foot_off_regions = some_foot_off_regions || !OnSomeRegion(terrain.regions, p, setup_->config.planner.start_tolerance_m);
  }
  ASSERT_TRUE(some_foot_off_regions);  // else the case is not the one under test
  const plan_t reply = PlanOnFloor(request);
  ASSERT_NE(reply.status, -1) << "no reply";
  EXPECT_NE(reply.status, int{plan_t::STATUS_INVALID_START}) << reply.message;
  EXPECT_TRUE(reply.status == plan_t::STATUS_OPTIMAL || reply.status == plan_t::STATUS_FEASIBLE) << reply.message;
  // Every footstep after the start stance lands in a region.
  ASSERT_GT(reply.steps.size(), request.start_feet.size());
  for (size_t i = request.start_feet.size(); i < reply.steps.size(); ++i) {
    const Eigen::Vector3d p(reply.steps[i].position[0], reply.steps[i].position[1], reply.steps[i].position[2]);
    EXPECT_TRUE(OnSomeRegion(terrain.regions, p, 1e-6)) << "footstep " << i;
  }
}

TEST_F(DaemonSeenSurfaceTest, AStartFootInTheAirIsInvalidStartNamingTheNearestSeenSurface) {
  // The outermost feet 0.15 m beyond the slab's edge: nothing seen under them.
  const plan_t reply = PlanOnFloor(StanceRequest(robot(), kFloorEdgeY + 0.15 - LargestFootY(robot()), 8));
  ASSERT_NE(reply.status, -1) << "no reply";
  EXPECT_EQ(reply.status, int{plan_t::STATUS_INVALID_START}) << reply.message;
  EXPECT_NE(reply.message.find("nearest seen surface"), std::string::npos) << reply.message;
}

TEST_F(DaemonSeenSurfaceTest, AFarGoalIsInvalidGoalNamingTheNearestStanceAsThePlannerDoes) {
  // The goal 1.5 m beyond the slab's +x end (x = 2): farther than any foot reaches from
  // every region, and the slab within goal_search.report_radius (2 m).
  plan_request_t request = StanceRequest(robot(), 0.0, 9);
  request.goal_x = 3.5;
  const plan_t reply = PlanOnFloor(request);
  ASSERT_NE(reply.status, -1) << "no reply";
  EXPECT_EQ(reply.status, int{plan_t::STATUS_INVALID_GOAL}) << reply.message;
  EXPECT_NE(reply.message.find("from the nearest region"), std::string::npos) << reply.message;
  const std::string kNamed = "the nearest stance on regions is (";
  const size_t named = reply.message.find(kNamed);
  ASSERT_NE(named, std::string::npos) << reply.message;

  // The planner itself, as mfp-plan calls it, names the same stance.
  const MapTerrain terrain = MakeOctomapMapFunction(*setup_)(map_bytes_, "bt", "floor");
  PlanRequest direct;
  for (const auto& f : request.start_feet) direct.start_feet_world_m.emplace_back(f[0], f[1], f[2]);
  direct.goal_x_m = request.goal_x;
  direct.goal_y_m = request.goal_y;
  direct.time_limit_s = request.time_limit_s;
  direct.seen_surface = terrain.seen_surface;
  const PlannerOptions& options = setup_->config.planner;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers);
  const Plan plan = PlanFootsteps(robot(), terrain.regions, direct, options, solvers.workers());
  EXPECT_EQ(plan.status, SolveStatus::kInvalidGoal) << plan.message;
  const size_t direct_named = plan.message.find(kNamed);
  ASSERT_NE(direct_named, std::string::npos) << plan.message;
  EXPECT_EQ(reply.message.substr(named), plan.message.substr(direct_named));
}

// Goal footholds in the daemon: the map stage's regions leave a hole about a goal foot spot
// over floor the map saw flat, and the goal is pinned (tolerances 0). The plan stands on a
// foothold, and the daemon publishes the map's region set with it added before the reply,
// so every footstep's region id names a published region.
TEST_F(DaemonSeenSurfaceTest, AGoalOnSeenFloorOffTheRegionsStandsOnAFootholdTheDaemonPublishes) {
  setup_ = HexapodSetup(/*goal_pinned=*/true);
  const plan_request_t request = StanceRequest(robot(), 0.0, 10);
  const LegModel& leg = robot().legs[static_cast<size_t>(robot().gait[0])];
  const Eigen::Vector2d spot(request.goal_x + leg.nominal_offset_body_m.x(), request.goal_y + leg.nominal_offset_body_m.y());
  const MapFunction real = MakeOctomapMapFunction(*setup_);
  map_function_ = [real, spot](const std::string& bytes, const std::string& format, const std::string& what) {
    MapTerrain terrain = real(bytes, format, what);
    // The slab's top inset by 5 cm, less a square of half side 8 cm about the spot.
    const double x0 = spot.x() - 0.08, x1 = spot.x() + 0.08, y0 = spot.y() - 0.08, y1 = spot.y() + 0.08;
    const auto rect = [](int id, double ax, double ay, double bx, double by) {
      return MakeRegionFromPolygon(id, {{ax, ay, 0.0}, {bx, ay, 0.0}, {bx, by, 0.0}, {ax, by, 0.0}}, 0.005);
    };
    terrain.regions = {rect(0, -0.95, -0.95, x0, 0.95), rect(1, x1, -0.95, 1.95, 0.95), rect(2, x0, -0.95, x1, y0),
                       rect(3, x0, y1, x1, 0.95)};
    return terrain;
  };
  const plan_t reply = PlanOnFloor(request);
  ASSERT_NE(reply.status, -1) << "no reply";
  ASSERT_TRUE(reply.status == plan_t::STATUS_OPTIMAL || reply.status == plan_t::STATUS_FEASIBLE) << reply.message;
  EXPECT_TRUE(reply.reaches_goal) << reply.message;
  std::lock_guard<std::mutex> lock(mutex_);
  ASSERT_EQ(region_sets_.size(), 2u);  // the map's, then the plan's with its foothold
  EXPECT_EQ(region_sets_[0].num_regions, 4);
  EXPECT_GT(region_sets_[1].num_regions, 4);
  EXPECT_EQ(region_sets_[1].map_utime, region_sets_[0].map_utime);
  EXPECT_EQ(region_sets_[1].frame, "world");
  const std::vector<ConvexRegion> published = FromRegionSetMessage(region_sets_[1]);
  bool on_foothold = false;
  for (size_t i = request.start_feet.size(); i < reply.steps.size(); ++i) {
    const footstep_t& f = reply.steps[i];
    const auto region = std::find_if(published.begin(), published.end(), [&](const ConvexRegion& r) { return r.id == f.region_id; });
    ASSERT_NE(region, published.end()) << "footstep " << i << ": region " << f.region_id << " not published";
    EXPECT_TRUE(RegionContains(*region, Eigen::Vector3d(f.position[0], f.position[1], f.position[2]), 1e-6)) << "footstep " << i;
    on_foothold = on_foothold || f.region_id >= 4;
  }
  EXPECT_TRUE(on_foothold);
}

}  // namespace
}  // namespace mfp

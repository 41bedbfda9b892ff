#pragma once
// Seeded procedural courses for the planner benchmark (mfp-bench --courses) and its
// regression test. A course is a box terrain built along a route of body poses that the
// robot's reach can follow (every nominal foot of every route pose has a spot on a true
// top face, at least `edge_margin_m` inside its edges, within 0.9 l_bnd; neighbouring
// surfaces differ in height by at most 0.6 dz_max), or one whose every route is cut (a gap
// wider than any step can cross). The generator therefore knows the truth: route_exists.
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/terrain_description.h"
#include "io/scenario_yaml.h"
#include "planner/robot/robot_model.h"

namespace mfp {

enum class CourseKind {
  kStones,      // stepping stones of random size, spacing and height along the foot tracks
  kStonesTurn,  // stones, a corner platform, stones after a 90 degree turn
  kGaps,        // ground slabs with gaps to step across
  kStairs,      // steps up, then down
  kTilted,      // tilted blocks
  kRough,       // an uneven field of abutting blocks of random height, with a 90 degree turn
  kBeams,       // one narrow beam under each foot track
  kDetour,      // a wall across the straight route, a corridor around it, a dead-end pocket
  kCutStones,   // stones cut by a gap no step can cross (no route)
  kCutGaps,     // ground cut by such a gap (no route)
  kWalledGoal,  // the goal platform out of reach of everything (no route)
  // Body clearance (the route's body poses clear of every box in the body's band):
  kPocket,      // a U-shaped dead-end pocket open toward the start, the goal behind it
  kBaffles,     // a walled corridor with three baffles from alternating sides (slalom)
  kDoorway,     // a wall with a door wider than the body's short side, narrower than its
                // long side, met with the long side across it (must turn)
  kCorridor,    // a floor corridor with walls beside it and a 90 degree turn
  kClosedDoor,  // the doorway with a door narrower than the body's short side (no route
                // for the body; the feet could step through)
};

const std::vector<CourseKind>& AllCourseKinds();
std::string ToString(CourseKind kind);

struct Course {
  std::string name;
  CourseKind kind = CourseKind::kStones;
  std::string robot_path;
  TerrainDescription terrain;
  Pose2D start, goal;
  bool route_exists = true;
  // Surface a foot's centre needs around it on a true top face [m] (foot radius + edge margin).
  double edge_margin_m = 0.0;
  std::vector<Pose2D> route;  // body poses the course was built along (empty for cut parts)
};

// Longest horizontal foot travel of one step that the planner's model allows: a foot
// stays within the d_lim square about its nominal spot, and the centre of contacts moves
// with the foot by 1/n of its travel [m]. Route checks and cut widths use it.
double MaxFootTravel(const RobotModel& robot);

// Edge margin beyond the foot radius that generated courses leave and the checker demands [m].
constexpr double kCourseEdgeMargin = 0.01;
// Voxel size of a course's map (extracted regions): the finest feature (narrowest gap
// between footholds, least width a foothold keeps beyond its margins, twice a stair's
// rise) over
// kCourseVoxelsPerFeature, within [kCourseMinResolution, kCourseMaxResolution] [m]. A map
// coarser than a course's gaps shows no gap there: its regions run over it.
constexpr double kCourseMaxResolution = 0.02;
constexpr double kCourseMinResolution = 0.005;
constexpr double kCourseVoxelsPerFeature = 6.0;

// Whether every body pose along the route (interpolated as RouteHolds does) keeps the
// body's plan box clear of every box in its band above ground_z_m; true when the body is unknown.
bool BodyRouteClear(const RobotModel& robot, const TerrainDescription& terrain, const std::vector<Pose2D>& route,
                    double ground_z_m);

Course GenerateCourse(const RobotModel& robot, const std::string& robot_path, CourseKind kind, uint64_t seed);

// The course as a scenario (its name, robot, boxes, start and goal; default planner
// options), and as a scenario YAML (config/scenarios format; robot path written as given).
Scenario CourseScenario(const Course& course, double time_limit_s);
std::string CourseToScenarioYaml(const Course& course, double time_limit_s);

}  // namespace mfp

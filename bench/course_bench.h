#pragma once
// mfp-bench --courses N: generated courses planned end to end and judged by the
// independent checker; prints one row per course and a summary table.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bench/course_generator.h"
#include "io/scenario_yaml.h"
#include "planner/robot/robot_model.h"

namespace mfp {

struct CourseBenchOptions {
  int courses = 200;
  int first = 0;                   // skip the courses before this index (their seeds stay seed + i)
  uint64_t seed = 1;
  double time_limit_s = 15.0;      // per plan
  std::string robots_dir;          // config/robots
  // Robot files (YAML or URDF) the courses cycle through; empty: robots_dir's littledog,
  // hexapod and octopod.
  std::vector<std::string> robot_paths;
  // Robot files added to the rotation after robot_paths (or the default three).
  std::vector<std::string> extra_robot_paths;
  // Regions the planner gets: the map pipeline (voxelised boxes, as on the robot), or the
  // boxes' exact top faces inset by the checker's edge margin (perfect perception: separates
  // planning failures from perception ones).
  bool top_face_regions = false;
  bool print_windows = false;      // one line per window solved under each course's row
  std::string write_dir;           // write each course's scenario YAML here ("" = no)
  std::string plan_dir;            // write each course's plan JSON (NAME.json, io/plan_json.h) here ("" = no)
  // Plan only courses whose name contains this ("" = all); a kind's exact name
  // (ToString(CourseKind), e.g. "doorway") makes every course of that kind.
  std::string only;
  bool body_check = true;          // pass the boxes to the planner as body obstacles
  bool verbose = false;            // print each accepted window (steps, distance, nodes)
  std::function<void(Scenario*)> adjust;  // --set overrides
};

// The robots and course kinds the bench cycles through: course i is robot i % robots, kind
// (i / robots) % kinds, seed options.seed + i.
struct CourseRotation {
  std::vector<std::string> robot_paths;  // options.robot_paths (or the default three), then the extra ones
  std::vector<RobotModel> robots;        // loaded from robot_paths
  std::vector<CourseKind> kinds;         // every kind, or the one options.only names exactly
  size_t RobotIndex(int i) const { return static_cast<size_t>(i) % robots.size(); }
  CourseKind Kind(int i) const { return kinds[(static_cast<size_t>(i) / robots.size()) % kinds.size()]; }
  // Course i; throws std::runtime_error when the generator gives up on it.
  Course Generate(int i, uint64_t seed) const {
    return GenerateCourse(robots[RobotIndex(i)], robot_paths[RobotIndex(i)], Kind(i), seed + i);
  }
};
CourseRotation MakeCourseRotation(const CourseBenchOptions& options);

// Returns the number of courses where a route exists that did not plan validly to the goal.
int RunCourseBench(const CourseBenchOptions& options);

}  // namespace mfp

#pragma once
// Plans a generated course as mfp-plan plans a scenario and judges the plan with the
// independent checker against the course's true boxes: shared by the course tests.
#include <vector>

#include "bench/course_checker.h"
#include "bench/course_generator.h"
#include "planner/planning/footstep_planner.h"
#include "planner/qp/relaxation_solver_factory.h"

namespace mfp {

struct CourseOutcome {
  Plan plan;
  CourseVerdict verdict;
  std::vector<BodyObstacle> body_obstacles;  // what the plan kept the body clear of
};

// Plans on the boxes' true top faces inset by the edge margin, or (from_map) on the
// regions extracted from the course's voxel map with the map's body obstacles (not the true
// boxes, which only the checker sees), within time_limit_s [s].
inline CourseOutcome PlanCourse(const Course& course, const RobotModel& robot, double time_limit_s,
                                bool from_map = false) {
  const Scenario scenario = CourseScenario(course, time_limit_s);
  ScenarioTerrain terrain;
  if (from_map) terrain = LoadScenarioTerrain(scenario, robot);
  const std::vector<ConvexRegion> regions =
      from_map ? terrain.regions : TopFaceRegions(course.terrain, course.edge_margin_m, robot.max_slope_rad);
  PlanRequest request = ScenarioRequest(scenario, robot, regions);
  if (terrain.map_body_obstacles) request.body_obstacles = *terrain.map_body_obstacles;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(scenario.options.solvers.backend, 1);
  CourseOutcome out;
  out.plan = PlanFootsteps(robot, regions, request, scenario.options, solvers.workers());
  out.body_obstacles = request.body_obstacles;
  out.verdict = CheckPlanOnCourse(course.terrain, robot, out.plan.footsteps, course.goal, course.edge_margin_m);
  return out;
}

}  // namespace mfp

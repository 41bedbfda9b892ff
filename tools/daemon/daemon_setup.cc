#include "tools/daemon/daemon_setup.h"

#include "planner/check.h"
#include "planner/robot_yaml.h"

namespace mfp {

DaemonSetup LoadDaemonSetup(const DaemonConfig& config) {
  DaemonSetup setup;
  setup.config = config;
  for (const std::string& file : config.robot_files) {
    RobotModel robot = LoadRobotYaml(file);
    if (setup.robots.count(robot.name) != 0)
      throw InputError(config.file + ": robots: two robots are named '" + robot.name + "'");
    setup.robots.emplace(robot.name, std::move(robot));
  }
  if (setup.config.default_robot.empty()) {
    MFP_CHECK(!setup.robots.empty());
    // The first robot listed is the default.
    setup.config.default_robot = LoadRobotYaml(config.robot_files.front()).name;
  }
  if (setup.robots.count(setup.config.default_robot) == 0)
    throw InputError(config.file + ": default_robot: '" + setup.config.default_robot +
                     "' is not one of the robots listed");
  return setup;
}

}  // namespace mfp

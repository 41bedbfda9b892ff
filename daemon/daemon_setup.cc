#include "daemon/daemon_setup.h"

#include "base/check.h"
#include "io/robot_loader.h"

namespace mfp {

DaemonSetup LoadDaemonSetup(const DaemonConfig& config) {
  DaemonSetup setup;
  setup.config = config;
  std::string first_robot;
  for (const std::string& file : config.robot_files) {
    RobotModel robot = LoadRobot(file);
    if (first_robot.empty()) first_robot = robot.name;
    if (setup.robots.count(robot.name) != 0)
      throw InputError(config.file + ": robots: two robots are named '" + robot.name + "'");
    setup.robots.emplace(robot.name, std::move(robot));
  }
  // The first robot listed is the default unless the config names one.
  if (setup.config.default_robot.empty()) setup.config.default_robot = first_robot;
  if (setup.robots.count(setup.config.default_robot) == 0)
    throw InputError(config.file + ": default_robot: '" + setup.config.default_robot +
                     "' is not one of the robots listed");
  return setup;
}

}  // namespace mfp

#pragma once
// Builds a DaemonSetup from a config: loads every robot and checks the default robot.
#include "daemon/daemon_core.h"

namespace mfp {

// Throws InputError naming the robot file or the config key at fault.
DaemonSetup LoadDaemonSetup(const DaemonConfig& config);

}  // namespace mfp

#pragma once
// The map -> regions step of the daemon: one function, so the terrain pipeline can be
// swapped or tuned in one place.
#include "daemon/daemon_core.h"

namespace mfp {

// Regions from the bytes of an OctoMap file (.bt or .ot), or of a height_map_t message
// (format kHeightMapFormat), extracted for the robots of
// the setup (inset by the largest foot radius, slopes up to the smallest max_slope), with
// the surface layers they were cut from as the map's seen surface.
MapFunction MakeOctomapMapFunction(const DaemonSetup& setup);

}  // namespace mfp

#pragma once
// Synthetic terrains with known answers, shared by the tests and mfp-terrain-bench:
// flat ground, a step, stepping stones, 3 and 15 degree tilts, a 40 degree slope, a gap,
// a wall, and a 4 m x 4 m course mixing them. Box edges lie on the 2 cm voxel grid where
// the shape allows, so the exact answers are known to the voxel.
#include <string>
#include <vector>

#include "terrain/terrain_description.h"

namespace mfp {

struct NamedTerrain {
  std::string name;
  TerrainDescription terrain;
};

TerrainDescription FlatTerrain();           // 2 m x 2 m ground, top at z = 0
TerrainDescription StepTerrain();           // ground; x in [0, 1] is 0.1 m higher
TerrainDescription SteppingStonesTerrain(); // 3 x 4 stones of 0.2 m at three heights, no ground
TerrainDescription TiltTerrain(double pitch_rad, double yaw_rad);  // a 1.2 m tilted slab
TerrainDescription GapTerrain();            // two 1 m platforms 0.2 m apart
TerrainDescription WallTerrain();           // ground with a 0.5 m high, 4 cm thick wall at x = 0
TerrainDescription CourseTerrain4m();       // 4 m x 4 m, all of the above together

std::vector<NamedTerrain> TerrainCatalogue();

}  // namespace mfp

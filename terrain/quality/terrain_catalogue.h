#pragma once
// Synthetic terrains with known answers, shared by the tests and mfp-terrain-bench:
// flat ground, a step, stepping stones, 3 and 15 degree tilts, a 40 degree slope, a gap,
// a wall, and a 4 m x 4 m course mixing them; bridges, tables, overhangs and a scanned
// corridor with a ceiling. Box edges lie on the 2 cm voxel grid where
// the shape allows, so the exact answers are known to the voxel.
#include <string>
#include <vector>

#include "geometry/terrain_description.h"

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
// Levels above one another (for multi-level surfaces and clearance):
TerrainDescription BridgeTerrain();         // ground with a 0.6 m high bridge deck over it
TerrainDescription TableTerrain();          // floor with a 0.7 m high table on four legs
TerrainDescription OverhangTerrain();       // two 0.1 m stair treads under a 0.5 m overhang
// An indoor corridor (floor, side walls with door openings, ceiling at 2.8 m), length
// along x from 0, 1.6 m wide, at resolution_m, scanned by sensors every 1.5 m along its
// centre line 1 m above the floor (free space from rays), with the given noise.
TerrainDescription CorridorTerrain(double length_m, double resolution_m, const MapNoise& noise);
// A 40 m x 15 m floor of rooms and corridors (walls with doors, tables, no ceiling),
// voxelised at 8 cm: the large map of mfp-terrain-bench.
TerrainDescription BuildingFloorTerrain();

std::vector<NamedTerrain> TerrainCatalogue();

}  // namespace mfp

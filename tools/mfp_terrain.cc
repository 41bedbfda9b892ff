// mfp-terrain SCENARIO.yaml --out FILE.bt|FILE.ot: builds an OctoMap map from the
// `terrain:` block of a scenario (boxes with centre, size and roll/pitch/yaw), so tests
// and demos make their maps: voxelised, or scanned by rays from sensor positions (free
// space stored, as in a real map) with optional noise (terrain_yaml.h). Exit 0 on
// success, 2 on bad input (problem on stderr).
#include <CLI/CLI.hpp>

#include <cstdio>

#include "planner/check.h"
#include "terrain/map_simulation.h"
#include "terrain/octomap_io.h"
#include "terrain/terrain_yaml.h"

int main(int argc, char** argv) {
  CLI::App app{"Build an OctoMap terrain map from a scenario's terrain description"};
  std::string scenario_path, out_path;
  app.add_option("scenario", scenario_path, "scenario YAML with a terrain: block")->required();
  app.add_option("--out", out_path, "map file to write (.bt binary, or .ot)")->required();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    const mfp::TerrainDescription terrain = mfp::LoadTerrainDescription(scenario_path);
    const mfp::OccupancyMap map = mfp::MakeTerrainMap(terrain);
    mfp::WriteOccupancyMap(map, out_path);
    std::printf("%s: %zu boxes at %.3f m resolution, %s%s: %zu occupied and %zu free voxels written to %s\n",
                scenario_path.c_str(), terrain.boxes.size(), terrain.resolution_m,
                terrain.scan.sensors_world_m.empty() ? "voxelised" : "scanned from sensors",
                terrain.noise.Any() ? " with noise" : "", map.leaves.size(), map.free_leaves.size(),
                out_path.c_str());
  } catch (const mfp::InputError& e) {
    std::fprintf(stderr, "mfp-terrain: %s\n", e.what());
    return 2;
  }
  return 0;
}

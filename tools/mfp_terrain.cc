// mfp-terrain SCENARIO.yaml --out FILE.bt|FILE.ot: builds an OctoMap map from the
// `terrain:` block of a scenario (boxes with centre, size and roll/pitch/yaw), so tests
// and demos make their maps: voxelised, or scanned by rays from sensor positions (free
// space stored, as in a real map) with optional noise (terrain_yaml.h). Exit 0 on
// success, 2 on bad input (problem on stderr).
// mfp-terrain SCENARIO.yaml --check-plan PLAN.json --radius R: judges a plan's footsteps
// against the boxes themselves (OnTrueTopSurface: a disk of radius R about each foot on
// a true top surface, within a voxel in height); prints each failing footstep, exit 3
// when any fails.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "base/check.h"
#include "io/cli_parse.h"
#include "io/terrain_yaml.h"
#include "terrain/extraction/map_simulation.h"
#include "terrain/octomap/octomap_io.h"
#include "terrain/quality/terrain_quality.h"

int main(int argc, char** argv) {
  CLI::App app{"Build an OctoMap terrain map from a scenario's terrain description"};
  std::string scenario_path, out_path;
  app.add_option("scenario", scenario_path, "scenario YAML with a terrain: block")->required();
  std::string plan_path;
  double radius_m = 0.0;
  auto* out = app.add_option("--out", out_path, "map file to write (.bt binary, or .ot)");
  auto* check = app.add_option("--check-plan", plan_path, "plan JSON (mfp-plan --json) to judge against the boxes");
  app.add_option("--radius", radius_m, "with --check-plan: real surface needed around each foot centre [m]")
      ->check(CLI::Range(0.0, 1.0));
  out->excludes(check);
  check->excludes(out);
  MFP_CLI_PARSE(app, argc, argv);
  try {
    const mfp::TerrainDescription terrain = mfp::LoadTerrainDescription(scenario_path);
    if (!plan_path.empty()) {
      std::ifstream in(plan_path);
      if (!in) throw mfp::InputError(plan_path + ": cannot open the plan");
      nlohmann::json plan;
      try {
        in >> plan;
      } catch (const std::exception& e) {
        throw mfp::InputError(plan_path + ": not JSON (" + e.what() + ")");
      }
      if (!plan.contains("footsteps") || !plan["footsteps"].is_array()) {
        throw mfp::InputError(plan_path + ": no footsteps list");
      }
      int bad = 0, n = 0;
      double z_lo = INFINITY, z_hi = -INFINITY;
      for (const auto& f : plan["footsteps"]) {
        const Eigen::Vector3d p(f.at("x").get<double>(), f.at("y").get<double>(), f.at("z").get<double>());
        ++n;
        z_lo = std::min(z_lo, p.z());
        z_hi = std::max(z_hi, p.z());
        if (!mfp::OnTrueTopSurface(terrain, p, radius_m, terrain.resolution_m)) {
          ++bad;
          std::printf("footstep %d at (%.3f, %.3f, %.3f) m: not on a true top surface with %.3f m around it\n",
                      n - 1, p.x(), p.y(), p.z(), radius_m);
        }
      }
      std::printf("%s: %d of %d footsteps on a true top surface with %.3f m around them (z %.3f .. %.3f m)\n",
                  plan_path.c_str(), n - bad, n, radius_m, z_lo, z_hi);
      return bad > 0 ? 3 : 0;
    }
    if (out_path.empty()) throw mfp::InputError("give --out FILE.bt|FILE.ot or --check-plan PLAN.json");
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

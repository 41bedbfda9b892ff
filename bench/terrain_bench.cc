// mfp-terrain-bench: region extraction on the synthetic terrains with known answers.
// Prints, per map: extraction time (median of several runs), regions, soundness (largest
// distance of sampled region points from the true top surface, in voxels) and the
// coverage of each flat top face larger than a foot (after the foot-radius inset).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "planner/base/check.h"
#include "terrain/octomap_io.h"
#include "terrain/region_extractor.h"
#include "terrain/terrain_catalogue.h"
#include "terrain/terrain_quality.h"
#include "terrain/voxelize.h"

int main(int argc, char** argv) {
  CLI::App app{"Region extraction benchmark on synthetic terrains"};
  int runs = 9;
  double foot_radius_m = 0.01;
  double max_slope_rad = 0.45;
  app.add_option("--runs", runs, "timed runs per map (median reported)")->check(CLI::Range(1, 1000));
  app.add_option("--foot-radius", foot_radius_m, "foot radius [m]")->check(CLI::Range(0.0, 0.2));
  app.add_option("--max-slope", max_slope_rad, "steepest walkable slope [rad]")
      ->check(CLI::Range(0.01, 1.5));
  CLI11_PARSE(app, argc, argv);

  mfp::RegionExtractorOptions options;
  options.foot_radius_m = foot_radius_m;
  options.max_slope_rad = max_slope_rad;
  std::printf("foot radius %.3f m, max slope %.3f rad, %d runs per map\n\n", foot_radius_m,
              max_slope_rad, runs);
  std::printf("%-18s %9s %8s %9s %8s %7s %11s  %s\n", "map", "cells", "leaves", "median_ms",
              "regions", "steep", "sound_vox", "coverage of flat top faces (after inset)");
  bool all_ok = true;
  for (const mfp::NamedTerrain& named : mfp::TerrainCatalogue()) {
    // Through a .bt file and back, as a robot would receive it (pruned leaves).
    const mfp::OccupancyMap map = mfp::LoadMapBytes(
        mfp::OccupancyMapBytes(mfp::VoxelizeTerrain(named.terrain), true), named.name);
    std::vector<double> times_ms;
    mfp::RegionExtractionResult result;
    for (int i = 0; i < runs; ++i) {
      const auto start = std::chrono::steady_clock::now();
      result = mfp::ExtractRegions(map, options);
      times_ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::nth_element(times_ms.begin(), times_ms.begin() + runs / 2, times_ms.end());
    const double res = named.terrain.resolution_m;
    const double sound_vox =
        mfp::MaxDistanceToTopSurfaceM(result.regions, named.terrain, res) / res;
    const std::vector<mfp::FaceCoverage> coverage = mfp::TopFaceCoverage(
        result.regions, named.terrain, foot_radius_m, max_slope_rad, res);
    std::string cov_text;
    for (const mfp::FaceCoverage& c : coverage) {
      char buf[64];
      std::snprintf(buf, sizeof(buf), "%s%s %.0f%%", cov_text.empty() ? "" : ", ", c.name.c_str(),
                    100.0 * c.coverage);
      cov_text += buf;
      all_ok = all_ok && c.coverage >= 0.85;
    }
    all_ok = all_ok && sound_vox <= 1.0;
    std::printf("%-18s %9zu %8zu %9.2f %8zu %7d %11.3f  %s\n", named.name.c_str(),
                result.height_map.height_m.size(), map.leaves.size(), times_ms[runs / 2],
                result.regions.size(), result.stats.patches_too_steep, sound_vox, cov_text.c_str());
    if (named.name == "course_4m") {
      const mfp::RegionExtractionStats& s = result.stats;
      std::printf("  course_4m stages (last run): height map %.2f ms, surface fits %.2f ms, "
                  "segmentation %.2f ms, decomposition %.2f ms\n",
                  1e3 * s.height_map_s, 1e3 * s.analysis_s, 1e3 * s.segmentation_s,
                  1e3 * s.decomposition_s);
    }
  }
  std::printf("\nsoundness <= 1 voxel and coverage >= 85%% on every face: %s\n",
              all_ok ? "yes" : "NO");
  return all_ok ? 0 : 1;
}

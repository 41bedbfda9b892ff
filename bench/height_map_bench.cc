#include "bench/height_map_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "terrain/extraction/height_grid.h"
#include "terrain/quality/height_grid_sampling.h"
#include "terrain/quality/terrain_catalogue.h"
#include "terrain/quality/terrain_quality.h"

namespace mfp {

bool PrintHeightMapRows(const RegionExtractorOptions& options, int runs) {
  struct Row {
    std::string name, terrain;
    double resolution_m;
  };
  // course_4m: 4 m x 4 m at 2 cm (the target: extraction in at most 50 ms).
  const std::vector<Row> rows = {{"hm_course_4m_2cm", "course_4m", 0.02},
                                 {"hm_stepping_stones_1cm", "stepping_stones", 0.01},
                                 {"hm_gap_2cm", "gap", 0.02}};
  bool ok = true;
  for (const Row& row : rows) {
    for (const NamedTerrain& named : TerrainCatalogue()) {
      if (named.name != row.terrain) continue;
      const HeightGrid grid = SampleHeightGrid(named.terrain, row.resolution_m);
      std::vector<double> times_ms;
      RegionExtractionResult result;
      for (int i = 0; i < runs; ++i) {
        const auto start = std::chrono::steady_clock::now();
        result = ExtractRegionsFromHeightGrid(grid, options);
        times_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      }
      std::nth_element(times_ms.begin(), times_ms.begin() + runs / 2, times_ms.end());
      const double margin = options.foot_radius_m + options.edge_margin_m;
      const RegionSoundness sound = MeasureSoundness(result.regions, named.terrain, margin, row.resolution_m);
      CoverageOptions cov;
      cov.inset_m = margin;
      cov.disk_radius_m = margin;
      cov.clearance_m = options.clearance_m;
      cov.max_slope_rad = options.max_slope_rad;
      cov.height_tolerance_m = row.resolution_m;
      double worst = 1.0;
      for (const FaceCoverage& c : TopFaceCoverage(result.regions, named.terrain, cov)) worst = std::min(worst, c.coverage);
      ok = ok && sound.fraction >= 0.99;
      std::printf("%-22s %6.3f %7s %9zu %8s %9.1f %8zu %6d %9.4f  least-covered walkable face %.0f%%\n",
                  row.name.c_str(), row.resolution_m, "1.0/0.5", grid.heights_m.size(), "-", times_ms[runs / 2],
                  result.regions.size(), result.stats.layers, sound.fraction, 100.0 * worst);
      std::printf("  stages [ms]: layers %.1f, surface fit %.1f, segmentation %.1f, decomposition %.1f\n",
                  1e3 * result.stats.height_map_s, 1e3 * result.stats.analysis_s, 1e3 * result.stats.segmentation_s,
                  1e3 * result.stats.decomposition_s);
      if (sound.fraction < 1.0) {
        std::printf("  unsound sample e.g. at (%.3f, %.3f, %.3f)\n", sound.worst_point.x(), sound.worst_point.y(),
                    sound.worst_point.z());
      }
    }
  }
  return ok;
}

}  // namespace mfp

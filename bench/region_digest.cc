#include "bench/region_digest.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>

#include "terrain/extraction/map_simulation.h"
#include "terrain/octomap/octomap_io.h"
#include "terrain/quality/terrain_catalogue.h"

namespace mfp {
namespace {

// FNV-1a over the bytes of every region's id, layer and vertices (exact bits).
uint64_t RegionHash(const RegionExtractionResult& result) {
  uint64_t h = 1469598103934665603ull;
  auto add = [&h](const void* data, size_t size) {
    const unsigned char* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
  };
  for (size_t r = 0; r < result.regions.size(); ++r) {
    const int layer = r < result.region_layer.size() ? result.region_layer[r] : -1;
    add(&layer, sizeof(layer));
    for (const Eigen::Vector3d& v : result.regions[r].vertices_world_m) add(v.data(), 3 * sizeof(double));
  }
  return h;
}

// The options the bench's map rows use: a plain voxelisation's edges within half a voxel,
// a ray-cast scan's risers exact.
RegionExtractorOptions MapOptions(const TerrainDescription& terrain, RegionExtractorOptions options) {
  if (terrain.scan.sensors_world_m.empty() && !terrain.noise.Any()) {
    options.edge_uncertainty_voxels = 0.5;
    options.riser_uncertainty_voxels = 0.5;
  } else if (!terrain.scan.sensors_world_m.empty()) {
    options.riser_uncertainty_voxels = 0.0;
  }
  return options;
}

void DigestOne(const std::string& name, const OccupancyMap& map, const RegionExtractorOptions& options, int runs) {
  std::vector<double> cpu_ms, wall_ms;
  std::vector<RegionExtractionStats> stats;
  RegionExtractionResult result;
  for (int i = 0; i < runs; ++i) {
    const std::clock_t cpu_start = std::clock();
    const auto wall_start = std::chrono::steady_clock::now();
    result = ExtractRegions(map, options);
    wall_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall_start).count());
    cpu_ms.push_back(1e3 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    stats.push_back(result.stats);
  }
  std::vector<size_t> order(cpu_ms.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cpu_ms[a] < cpu_ms[b]; });
  const size_t mid = order[order.size() / 2];
  const RegionExtractionStats& s = stats[mid];
  std::vector<double> walls = wall_ms;
  std::nth_element(walls.begin(), walls.begin() + static_cast<std::ptrdiff_t>(walls.size() / 2), walls.end());
  std::printf("%-26s %7zu %016llx %8.1f %8.1f %8.1f %8.1f %8.1f %8.1f %8.1f\n", name.c_str(), result.regions.size(),
              static_cast<unsigned long long>(RegionHash(result)), cpu_ms[mid], walls[walls.size() / 2],
              1e3 * s.height_map_s,
              1e3 * s.analysis_s, 1e3 * s.segmentation_s, 1e3 * s.decomposition_s, 1e3 * s.total_s);
}

}  // namespace

void PrintRegionDigests(const std::vector<std::string>& scans, const RegionExtractorOptions& options, int runs,
                        bool scans_only) {
  std::printf("%-26s %7s %16s %8s %8s %8s %8s %8s %8s %8s\n", "map", "regions", "vertex_hash", "cpu_ms", "wall_ms",
              "layers_ms", "fit_ms", "segm_ms", "decomp_ms", "total_ms");
  for (const std::string& path : scans) {
    RegionExtractorOptions scan_options = options;
    scan_options.riser_uncertainty_voxels = 0.0;  // as the scan rows: a scan occupies every voxel a ray hits
    DigestOne(path.substr(path.find_last_of('/') + 1), LoadMapFile(path), scan_options, runs);
  }
  if (scans_only) return;
  for (const NamedTerrain& named : TerrainCatalogue()) {
    const OccupancyMap map = LoadMapBytes(OccupancyMapBytes(MakeTerrainMap(named.terrain), true), named.name);
    DigestOne(named.name, map, MapOptions(named.terrain, options), runs);
  }
  MapNoise noise;
  noise.seed = 7;
  noise.jitter_fraction = 0.03;
  noise.hole_fraction = 0.01;
  noise.outliers = 20;
  const NamedTerrain large[] = {{"corridor_8cm_scan", CorridorTerrain(7.0, 0.08, noise)},
                                {"building_40x15_8cm", BuildingFloorTerrain()}};
  for (const NamedTerrain& named : large) {
    DigestOne(named.name, LoadMapBytes(OccupancyMapBytes(MakeTerrainMap(named.terrain), true), named.name),
              MapOptions(named.terrain, options), runs);
  }
}

}  // namespace mfp

// mfp-terrain-bench: region extraction on synthetic terrains with known answers.
// Prints, per map: extraction time (median of several runs), regions and layers,
// soundness (share of sampled region points whose foot disk plus edge margin lies on a
// true top surface, within a voxel in height) and the coverage of each walkable top face
// (the face inset by foot radius + edge margin, where it has the clearance above it).
// Coverage is printed against that walkable face, and (in brackets) against the part a
// map can certify whatever made it: the walkable face inset by a further voxel (the most
// any map's edges are uncertain), with that much room from any box above (walls) too. Each map is extracted with the edge
// uncertainty of how it was made (column unc: at drops / at walls, in voxels): mfp's
// voxelisation marks a voxel whose centre is inside a box (half a voxel either way), a
// scan marks every voxel a ray hits (a voxel at drops, none at walls). The maps marked *
// are the criterion: whole-face coverage >= 85 % with soundness >= 0.99.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <utility>
#include <vector>

#include "base/check.h"
#include "bench/coverage_breakdown.h"
#include "bench/height_map_bench.h"
#include "bench/region_digest.h"
#include "bench/scan_walks.h"
#include "io/cli_parse.h"
#include "terrain/extraction/map_simulation.h"
#include "terrain/extraction/region_extractor.h"
#include "terrain/octomap/octomap_io.h"
#include "terrain/quality/terrain_catalogue.h"
#include "terrain/quality/terrain_quality.h"
#include "terrain/quality/voxel_quality.h"

namespace {

// A real scan (a .bt/.ot path): regions, extraction time, the floor seen from above, the
// share of its certifiable part (eroded by foot radius + 1 cm + one voxel) the regions
// cover, and soundness of region points against the raw voxels (voxel_quality.h).
// Returns whether soundness is at least 0.99; appends where the certifiable floor the
// regions miss goes to `breakdowns` (one more extraction, recording cell fates).
bool BenchRealScan(const std::string& path, const mfp::RegionExtractorOptions& options, int runs,
                   std::vector<std::pair<std::string, mfp::CoverageBreakdown>>* breakdowns) {
  const mfp::OccupancyMap map = mfp::LoadMapFile(path);
  mfp::RegionExtractorOptions scan_options = options;
  scan_options.riser_uncertainty_voxels = 0.0;  // a scan occupies every voxel a ray hits
  std::vector<double> times_ms, cpu_ms;
  mfp::RegionExtractionResult result;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    result = mfp::ExtractRegions(map, scan_options);
    cpu_ms.push_back(1e3 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    times_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(times_ms.begin(), times_ms.begin() + runs / 2, times_ms.end());
  std::nth_element(cpu_ms.begin(), cpu_ms.begin() + runs / 2, cpu_ms.end());
  mfp::VoxelQualityOptions judge;
  judge.clearance_m = options.clearance_m;
  judge.erosion_m = options.foot_radius_m + 0.01 + map.resolution_m;
  judge.list_missed = true;
  const mfp::VoxelQuality q = mfp::JudgeRegionsAgainstVoxels(result.regions, map, judge);
  const std::string name = path.substr(path.find_last_of('/') + 1);
  scan_options.record_cell_fates = true;
  breakdowns->emplace_back(name, mfp::BreakDownMissedFloor(q, mfp::ExtractRegions(map, scan_options)));
  std::printf("%-22s %6.3f %8zu %9.1f %7.1f %8zu %8.2f %8.1f %9d %8.1f%% %8.1f%% %8.1f%% %9.4f\n", name.c_str(),
              map.resolution_m, map.leaves.size(), times_ms[runs / 2], cpu_ms[runs / 2], result.regions.size(),
              q.floor_height_m, q.seen_floor_m2, q.certifiable_floor_cells, 100.0 * q.seen_floor_coverage,
              100.0 * q.certifiable_coverage, 100.0 * q.certifiable_centre_coverage, q.soundness);
  if (q.soundness < 1.0) {
    std::printf("  %d of %d region points off seen surface, e.g. at (%.3f, %.3f, %.3f)\n",
                q.region_samples - q.sound_samples, q.region_samples, q.worst_point.x(), q.worst_point.y(),
                q.worst_point.z());
  }
  return q.soundness >= 0.99;
}

// The bench's flags: the extractor's options, the maps to run, and the walks' options.
struct BenchFlags {
  int runs = 5;
  mfp::RegionExtractorOptions options;
  bool large = true;
  bool scans_only = false;
  std::vector<std::string> scans;
  std::vector<std::string> walk_robots;
  mfp::ScanWalkOptions walks;
  std::string walk_reach;  // --walk-reach: "", box, octagon, hexadecagon or footprint
  bool digest = false;
};

void AddExtractorFlags(CLI::App& app, BenchFlags& f) {
  mfp::RegionExtractorOptions& options = f.options;
  app.add_option("--runs", f.runs, "timed runs per map (median reported)")->check(CLI::Range(1, 1000));
  app.add_option("--foot-radius", options.foot_radius_m, "foot radius [m]")->check(CLI::Range(0.0, 0.2));
  app.add_option("--edge-margin", options.edge_margin_m, "real surface kept around a foot [m]")
      ->check(CLI::Range(0.0, 0.2));
  app.add_option("--clearance", options.clearance_m, "free space a surface needs above it [m]")
      ->check(CLI::Range(0.01, 100.0));
  app.add_option("--max-slope", options.max_slope_rad, "steepest walkable slope [rad]")
      ->check(CLI::Range(0.01, 1.5));
  app.add_option("--max-regions-per-patch", options.max_regions_per_patch, "regions per planar patch at most")
      ->check(CLI::Range(1, 10000));
  app.add_option("--regions-per-m2", options.regions_per_m2, "a patch's regions per square metre at most")
      ->check(CLI::Range(0.0, 1e4));
  app.add_option("--target-coverage", options.target_coverage, "a patch's cover stops at this share")
      ->check(CLI::Range(0.01, 1.0));
  app.add_option("--threads", options.threads, "threads of the fit, segmentation and decomposition (1: one)")
      ->check(CLI::Range(1, 64));
  app.add_option("--convex-cover", options.convex_cover,
                 "cover patches by convex pieces along their outline (1) or by rectangles (0)");
  app.add_option("--max-region-vertices", options.max_region_vertices, "vertices of a convex piece at most")
      ->check(CLI::Range(3, 64));
  app.add_option("--convex-alone-cells", options.convex_alone_cells,
                 "a patch with this many kept cells is covered by convex pieces without rectangles to compare")
      ->check(CLI::Range(0, 1000000000));
  app.add_option("--convex-alone-outline", options.convex_alone_outline,
                 "... and an outline of at least this many times a square's of as many cells")
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--convex-alone-outline-share", options.convex_alone_outline_share,
                 "... and of at least this share of its kept cells")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--convex-shrunk-seeds", options.convex_shrunk_seeds,
                 "grow each convex piece also about its seed's middle half and quarter (1) or about the seed alone (0)");
  app.add_option("--convex-shrunk-seed-min-cells", options.convex_shrunk_seed_min_cells,
                 "only a seed at least this many cells on its shorter side is also grown from its middle [cells]")
      ->check(CLI::Range(1, 1000000000));
  app.add_option("--noise-max-cells", options.noise_max_cells, "largest group of off-plane cells kept in a patch")
      ->check(CLI::Range(0, 1000));
  app.add_option("--enclosed-unseen-radius", options.enclosed_unseen_radius_cells,
                 "unseen floor enclosed by seen floor within this many cells is floor (0: off) [cells]")
      ->check(CLI::Range(0, 64));
  app.add_option("--edge-uncertainty", options.edge_uncertainty_voxels,
                 "how far inside its outermost voxel a surface may end at a drop [voxels]")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--max-residual", options.max_residual_voxels, "patch cells further from the plane are dropped [voxels]")
      ->check(CLI::Range(0.01, 10.0));
  app.add_option("--grow-tolerance", options.grow_tolerance_voxels, "a cell joins a patch within this of its plane [voxels]")
      ->check(CLI::Range(0.01, 10.0));
  app.add_flag("--overlapping-regions", options.overlapping_regions, "a patch's regions may overlap");
}

void AddMapFlags(CLI::App& app, BenchFlags& f) {
  app.add_flag("!--no-large", f.large, "skip the scanned corridor and the 40 m x 15 m floor");
  app.add_option("--scan", f.scans, "a real scan (.bt/.ot) judged against its own voxels (repeatable)")
      ->check(CLI::ExistingFile);
  app.add_flag("--scans-only", f.scans_only, "only the real scans given with --scan");
}

void AddWalkFlags(CLI::App& app, BenchFlags& f) {
  mfp::ScanWalkOptions& walks = f.walks;
  app.add_option("--walk-robot", f.walk_robots,
                 "with --scan: walks on each scan with this robot (URDF or robot YAML; repeatable), judged against "
                 "the raw voxels; only the walks are run")
      ->check(CLI::ExistingFile);
  app.add_option("--walks", walks.walks, "walks per scan and robot")->check(CLI::Range(1, 1000));
  app.add_option("--walk-time-limit", walks.time_limit_s, "time limit of each walk's plan [s]")
      ->check(CLI::Range(0.1, 3600.0));
  app.add_option("--walk-enclosed-unseen-radius", walks.enclosed_unseen_radius_cells,
                 "the walks' extractor: --enclosed-unseen-radius (-1: its default) [cells]")
      ->check(CLI::Range(-1, 64));
  app.add_option("--walk-convex-cover", walks.convex_cover,
                 "the walks' extractor: --convex-cover (-1: its default, 0 rectangles, 1 convex pieces)")
      ->check(CLI::Range(-1, 1));
  app.add_option("--walk-target-coverage", walks.target_coverage,
                 "the walks' extractor: --target-coverage (negative: its default)");
  app.add_option("--walk-regions-per-m2", walks.regions_per_m2,
                 "the walks' extractor: --regions-per-m2 (negative: its default)");
  app.add_option("--walk-max-regions", walks.max_regions, "the walks' extractor: --max-regions (-1: its default)")
      ->check(CLI::Range(-1, 100000));
  app.add_flag("--walk-details", walks.verbose, "a line per walk (and, for a failed walk, its cause)");
  app.add_option("--walk-cell-map", walks.cell_map_cells,
                 "with --walk-details: a map of the extractor's cell fates and the voxels' column kinds this many "
                 "cells each way around a failed walk's feet on no region [cells]")
      ->check(CLI::Range(0, 30));
  app.add_flag("--walk-certifiable", walks.certifiable_ends,
               "draw walk ends whose every foot stands on certifiable floor (seen for foot radius + 1 cm + a voxel "
               "around it)");
  app.add_flag("--walk-joined", walks.joined_ends,
               "keep walks whose ends certifiable floor joins by steps (judged on the raw voxels); the unjoined walks "
               "drawn on the way are run and reported as a second population");
  app.add_flag("--walk-legs-joined", walks.legs_joined_ends,
               "with --walk-joined: also every leg's own way joined from its start height (steps within dz_max), so "
               "no foot must change level by more than dz_max");
  app.add_option("--walk-only", walks.only_walk,
                 "plan only the walk of this index (0-based) of each scan and robot's draw (the same draw)")
      ->check(CLI::Range(0, 999));
  app.add_option("--walk-reach", f.walk_reach,
                 "the planner's reach polygon for the walks, replacing the robot file's (the draw and the judge keep "
                 "the box)")
      ->check(CLI::IsMember({"box", "octagon", "hexadecagon", "footprint"}));
  app.add_option("--walk-seed", walks.seed,
                 "the walks' draw: endpoints from this seed, mixed per scan file name and robot name (25: the draw "
                 "of the recorded walks)");
  app.add_flag("--walk-body-room", walks.body_room_ends,
               "draw walk ends with room for the body: no occupied voxel in the body's band over its plan box");
}

// The real scans' table and where the certifiable floor the regions miss goes. Returns
// whether soundness is at least 0.99 on every scan.
bool BenchRealScans(const BenchFlags& f) {
  bool scans_ok = true;
  std::printf("real scans: floor = seen surface voxels (known free above, no occupied voxel within the "
              "clearance) of the dominant level +-0.1 m; certifiable = floor (as a set of "
              "cell squares) eroded by foot radius + 1 cm + one voxel; cert_ctr = the same eroded centre to centre "
              "(half a voxel more lenient); sound = region point on a seen surface voxel\n");
  std::printf("%-22s %6s %8s %9s %7s %8s %8s %8s %9s %9s %9s %9s %9s\n", "scan", "res_m", "leaves", "median_ms",
              "cpu_ms", "regions", "floor_z", "floor_m2", "cert_cells", "floor_cov", "cert_cov", "cert_ctr", "sound");
  std::vector<std::pair<std::string, mfp::CoverageBreakdown>> breakdowns;
  for (const std::string& path : f.scans) scans_ok = BenchRealScan(path, f.options, f.runs, &breakdowns) && scans_ok;
  std::printf("real scans: soundness >= 0.99 on every scan: %s\n\n", scans_ok ? "yes" : "NO");
  std::printf("certifiable floor missed, by cause (%% of the certifiable floor; bench/coverage_breakdown.h, "
              "terrain/extraction/cell_fate.h)\n");
  mfp::PrintBreakdownHeader();
  for (const auto& [name, breakdown] : breakdowns) mfp::PrintBreakdownRow(name, breakdown);
  std::printf("\n");
  return scans_ok;
}

// The catalogue's maps, the finer copies of some, and (large) the scanned corridor and
// the building floor; appends the maps of the criterion to `criterion`.
std::vector<mfp::NamedTerrain> BenchMaps(bool large, std::vector<std::string>* criterion) {
  std::vector<mfp::NamedTerrain> maps = mfp::TerrainCatalogue();
  // The stepping-stone, tilted and bridge courses at 1 cm: fine enough that the half-voxel
  // edge uncertainty leaves 85 % of each walkable face.
  for (const std::string name : {"stepping_stones", "tilt_3deg", "tilt_15deg_yaw30", "bridge"}) {
    for (const mfp::NamedTerrain& t : mfp::TerrainCatalogue()) {
      if (t.name != name) continue;
      mfp::NamedTerrain fine = t;
      fine.name += "_1cm";
      fine.terrain.resolution_m = 0.01;
      maps.push_back(fine);
      criterion->push_back(fine.name);
    }
  }
  if (large) {
    mfp::MapNoise noise;
    noise.seed = 7;
    noise.jitter_fraction = 0.03;
    noise.hole_fraction = 0.01;
    noise.outliers = 20;
    maps.push_back({"corridor_8cm_scan", mfp::CorridorTerrain(7.0, 0.08, noise)});
    maps.push_back({"building_40x15_8cm", mfp::BuildingFloorTerrain()});
  }
  return maps;
}

// Whether every map so far met the bench's bar (all_ok) and the criterion maps the issue's.
struct MapVerdicts {
  bool all_ok = true;
  bool criterion_ok = true;
};

// The extractor's options for a map, with the edge uncertainty of how it was made.
mfp::RegionExtractorOptions MapExtractorOptions(const mfp::NamedTerrain& named, mfp::RegionExtractorOptions options) {
  const bool scanned = !named.terrain.scan.sensors_world_m.empty();
  const bool plain = !scanned && !named.terrain.noise.Any();
  if (plain) {
    options.edge_uncertainty_voxels = 0.5;
    options.riser_uncertainty_voxels = 0.5;
  } else if (scanned) {
    options.riser_uncertainty_voxels = 0.0;
  }
  return options;
}

// The map row's coverage text (the first faces' whole and certifiable coverage); judges
// every face's coverage into `verdicts` and prints a line per face under 85 %.
std::string CoverageText(const mfp::NamedTerrain& named, const std::vector<mfp::ConvexRegion>& regions,
                         const mfp::RegionExtractorOptions& options, bool in_criterion, MapVerdicts* verdicts) {
  const double res = named.terrain.resolution_m;
  const double margin = options.foot_radius_m + options.edge_margin_m;
  mfp::CoverageOptions cov;
  cov.inset_m = margin;
  cov.disk_radius_m = margin;
  cov.clearance_m = options.clearance_m;
  cov.max_slope_rad = options.max_slope_rad;
  cov.height_tolerance_m = res;
  const std::vector<mfp::FaceCoverage> walkable = mfp::TopFaceCoverage(regions, named.terrain, cov);
  cov.inset_m = margin + res;  // a further voxel: the most any map's edges are uncertain
  cov.disk_radius_m = cov.inset_m;
  const std::vector<mfp::FaceCoverage> certifiable = mfp::TopFaceCoverage(regions, named.terrain, cov);
  std::string cov_text;
  int shown = 0;
  // Faces a scan never saw from above (higher than every sensor: a ceiling's top) are
  // not walkable in that map, and faces with no certifiable part (a wall's top narrower
  // than two insets) cannot be covered.
  double highest_sensor = -INFINITY;
  for (const Eigen::Vector3d& p : named.terrain.scan.sensors_world_m) highest_sensor = std::max(highest_sensor, p.z());
  for (const mfp::FaceCoverage& c : walkable) {
    double cert = -1.0;
    for (const mfp::FaceCoverage& d : certifiable) cert = d.box == c.box ? d.coverage : cert;
    const mfp::TerrainBox& box = named.terrain.boxes[static_cast<size_t>(c.box)];
    if (cert < 0.0) continue;
    if (!named.terrain.scan.sensors_world_m.empty() && box.center_world_m.z() + 0.5 * box.size_m.z() > highest_sensor) {
      continue;
    }
    verdicts->all_ok = verdicts->all_ok && cert >= 0.85;
    if (in_criterion) verdicts->criterion_ok = verdicts->criterion_ok && c.coverage >= 0.85;
    if (cert < 0.85) std::printf("  %s: face %s covers %.0f%% of its certifiable part\n", named.name.c_str(),
                                 c.name.c_str(), 100.0 * cert);
    if (++shown > 6) continue;
    char buf[96];
    std::snprintf(buf, sizeof(buf), "%s%s %.0f%% [%.0f%%]", cov_text.empty() ? "" : ", ", c.name.c_str(),
                  100.0 * c.coverage, 100.0 * cert);
    cov_text += buf;
  }
  if (shown > 6) cov_text += ", ... (" + std::to_string(shown) + " faces)";
  return cov_text;
}

// One map's row: extraction time (median of `runs`), regions, layers, soundness and
// coverage, judged into `verdicts`.
void BenchMap(const mfp::NamedTerrain& named, const mfp::RegionExtractorOptions& options, int runs, bool in_criterion,
              MapVerdicts* verdicts) {
  const mfp::RegionExtractorOptions map_options = MapExtractorOptions(named, options);
  // Through a .bt file and back, as a robot would receive it (pruned leaves).
  const mfp::OccupancyMap map =
      mfp::LoadMapBytes(mfp::OccupancyMapBytes(mfp::MakeTerrainMap(named.terrain), true), named.name);
  std::vector<double> times_ms;
  mfp::RegionExtractionResult result;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    result = mfp::ExtractRegions(map, map_options);
    times_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(times_ms.begin(), times_ms.begin() + runs / 2, times_ms.end());
  const double res = named.terrain.resolution_m;
  const double margin = options.foot_radius_m + options.edge_margin_m;
  const mfp::RegionSoundness sound = mfp::MeasureSoundness(result.regions, named.terrain, margin, res);
  const std::string cov_text = CoverageText(named, result.regions, options, in_criterion, verdicts);
  verdicts->all_ok = verdicts->all_ok && sound.fraction >= 0.99;
  verdicts->criterion_ok = verdicts->criterion_ok && sound.fraction >= 0.99;
  char unc[16];
  std::snprintf(unc, sizeof(unc), "%.1f/%.1f", map_options.edge_uncertainty_voxels,
                map_options.riser_uncertainty_voxels);
  std::printf("%-22s %6.3f %7s %9zu %8zu %9.1f %8zu %6d %9.4f  %s\n", (named.name + (in_criterion ? " *" : "")).c_str(),
              res, unc, result.height_map.height_m.size(), map.leaves.size(), times_ms[runs / 2],
              result.regions.size(), result.stats.layers, sound.fraction, cov_text.c_str());
  if (sound.fraction < 1.0) {
    std::printf("  unsound sample e.g. at (%.3f, %.3f, %.3f)\n", sound.worst_point.x(), sound.worst_point.y(),
                sound.worst_point.z());
  }
}

// The synthetic maps' table, then the height maps' rows; returns the verdicts.
MapVerdicts BenchSyntheticMaps(const BenchFlags& f) {
  std::printf("%-22s %6s %7s %9s %8s %9s %8s %6s %9s  %s\n", "map", "res_m", "unc", "cells", "leaves", "median_ms",
              "regions", "layers", "sound", "coverage of walkable top faces [certifiable part]");
  std::vector<std::string> criterion = {"corridor_8cm_scan"};
  const std::vector<mfp::NamedTerrain> maps = BenchMaps(f.large, &criterion);
  MapVerdicts verdicts;
  for (const mfp::NamedTerrain& named : maps) {
    const bool in_criterion = std::find(criterion.begin(), criterion.end(), named.name) != criterion.end();
    BenchMap(named, f.options, f.runs, in_criterion, &verdicts);
  }
  // Height maps (.npy / height_map_t input): the same terrains sampled at cell centres.
  verdicts.all_ok = mfp::PrintHeightMapRows(f.options, f.runs) && verdicts.all_ok;
  return verdicts;
}

// Runs what the flags ask for; bad input (a map, a robot) throws mfp::InputError.
int Run(BenchFlags f) {
  if (f.digest) {
    mfp::PrintRegionDigests(f.scans, f.options, f.runs, f.scans_only);
    return 0;
  }
  if (!f.walk_reach.empty()) {
    for (mfp::ReachShape shape : {mfp::ReachShape::kBox, mfp::ReachShape::kOctagon, mfp::ReachShape::kHexadecagon,
                                  mfp::ReachShape::kFootprint}) {
      if (f.walk_reach == mfp::ReachShapeName(shape)) f.walks.reach_shape = shape;
    }
  }
  if (!f.walk_robots.empty()) {
    mfp::BenchScanWalks(f.scans, f.walk_robots, f.walks);
    return 0;
  }

  std::printf("foot radius %.3f m, edge margin %.3f m, edge uncertainty per map (unc), clearance %.2f m, "
              "max slope %.3f rad, %d runs per map\n\n",
              f.options.foot_radius_m, f.options.edge_margin_m, f.options.clearance_m, f.options.max_slope_rad, f.runs);
  bool scans_ok = true;
  if (!f.scans.empty()) {
    scans_ok = BenchRealScans(f);
    if (f.scans_only) return scans_ok ? 0 : 1;
  }
  const MapVerdicts verdicts = BenchSyntheticMaps(f);
  std::printf("\nsoundness >= 0.99 and coverage of the certifiable part >= 85%% on every face: %s\n",
              verdicts.all_ok ? "yes" : "NO");
  std::printf("maps marked *: soundness >= 0.99 and coverage of the whole walkable face >= 85%% on every face: %s\n",
              verdicts.criterion_ok ? "yes" : "NO");
  return verdicts.all_ok && verdicts.criterion_ok && scans_ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Region extraction benchmark on synthetic terrains"};
  BenchFlags f;
  f.options.clearance_m = 0.4;
  AddExtractorFlags(app, f);
  AddMapFlags(app, f);
  AddWalkFlags(app, f);
  app.add_flag("--digest", f.digest,
               "only the regions' digests (count, vertex hash) and stage times of the --scan scans and the catalogue's "
               "maps (with --scans-only: the scans alone): equal digests, equal regions");
  MFP_CLI_PARSE(app, argc, argv);
  try {
    return Run(std::move(f));
  } catch (const mfp::InputError& e) {
    // A map or robot file that cannot be read: its message names the file and the problem.
    std::fprintf(stderr, "mfp-terrain-bench: %s\n", e.what());
    return 2;
  }
}

#include "terrain/extraction/region_extractor.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>

#include "base/check.h"
#include "terrain/extraction/internal/noise_levels.h"
#include "terrain/extraction/internal/parallel_work.h"
#include "terrain/extraction/internal/patch_decomposition.h"
#include "terrain/extraction/internal/plane_segmentation.h"
#include "terrain/extraction/internal/surface_layers.h"
#include "terrain/extraction/map_simulation.h"

namespace mfp {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void RequireRange(const char* field, double value, double lo, double hi, bool open_lo) {
  if (!std::isfinite(value) || value < lo || value > hi || (open_lo && value == lo)) {
    std::ostringstream msg;
    msg << "region extractor option " << field << " = " << value << " is outside the allowed range "
        << (open_lo ? "(" : "[") << lo << ", " << hi << "]";
    throw InputError(msg.str());
  }
}

void ValidateOptions(const RegionExtractorOptions& o) {
  RequireRange("foot_radius_m", o.foot_radius_m, 0.0, 1.0, false);
  RequireRange("edge_margin_m", o.edge_margin_m, 0.0, 1.0, false);
  RequireRange("edge_uncertainty_voxels", o.edge_uncertainty_voxels, 0.0, 10.0, false);
  RequireRange("riser_uncertainty_voxels", o.riser_uncertainty_voxels, 0.0, 10.0, false);
  if (!(o.clearance_m > 0.0)) {
    throw InputError("region extractor option clearance_m must be > 0 m (infinity: highest surfaces only)");
  }
  RequireRange("max_slope_rad", o.max_slope_rad, 0.0, M_PI / 2, true);
  RequireRange("min_region_area_m2", o.min_region_area_m2, 0.0, 100.0, false);
  RequireRange("min_region_area_voxels", o.min_region_area_voxels, 0.0, 1e6, false);
  RequireRange("grow_tolerance_voxels", o.grow_tolerance_voxels, 0.0, 10.0, true);
  RequireRange("max_residual_voxels", o.max_residual_voxels, 0.0, 10.0, true);
  RequireRange("noise_tolerance_voxels", o.noise_tolerance_voxels, 0.0, 10.0, false);
  RequireRange("noise_max_cells", o.noise_max_cells, 0, 1000, false);
  RequireRange("enclosed_unseen_radius_cells", o.enclosed_unseen_radius_cells, 0, 64, false);
  RequireRange("seed_roughness_voxels", o.seed_roughness_voxels, 0.0, 10.0, true);
  RequireRange("plane_tolerance_voxels", o.plane_tolerance_voxels, 0.0, 10.0, false);
  RequireRange("target_coverage", o.target_coverage, 0.0, 1.0, true);
  RequireRange("max_regions_per_patch", o.max_regions_per_patch, 1, 10000, false);
  RequireRange("max_region_vertices", o.max_region_vertices, 3, 64, false);
  RequireRange("convex_alone_cells", o.convex_alone_cells, 0, std::numeric_limits<int>::max(), false);
  RequireRange("convex_alone_outline", o.convex_alone_outline, 0.0, 1e6, false);
  RequireRange("convex_alone_outline_share", o.convex_alone_outline_share, 0.0, 1.0, false);
  RequireRange("convex_shrunk_seed_min_cells", o.convex_shrunk_seed_min_cells, 1, std::numeric_limits<int>::max(), false);
  RequireRange("regions_per_m2", o.regions_per_m2, 0.0, 1e4, false);
  RequireRange("max_regions", o.max_regions, 0, 100000, false);
  RequireRange("axis_snap_rad", o.axis_snap_rad, 0.0, M_PI / 4, false);
  RequireRange("threads", o.threads, 1, 64, false);
}

SurfaceLayers LayersOf(const OccupancyMap& map, const RegionExtractorOptions& options) {
  const double res_in = map.resolution_m;
  SurfaceLayerOptions layer_options;
  layer_options.clearance_m = options.clearance_m;
  layer_options.require_seen_from_above = options.require_seen_from_above;
  layer_options.enclosed_unseen_radius_cells = options.enclosed_unseen_radius_cells;
  layer_options.max_cells = options.max_height_map_cells;
  layer_options.threads = options.threads;
  // Neighbours on one surface differ by a voxel riser plus the slope across a cell.
  layer_options.step_gate_m = std::isfinite(res_in) && res_in > 0
                                  ? res_in * (options.grow_tolerance_voxels + std::tan(options.max_slope_rad)) * (1.0 + 1e-3)
                                  : 0.0;
  return BuildSurfaceLayers(map, layer_options);
}

// Refuses a map whose surface fit would exceed max_fit_work cell visits.
void CheckFitWork(double res, int surface_cells, int window_half_cells, const RegionExtractorOptions& options) {
  const double work = FitWork(static_cast<size_t>(surface_cells), window_half_cells);
  if (work <= options.max_fit_work) return;
  std::ostringstream msg;
  msg << "the map's resolution " << res << " m is too fine for a foot of radius "
      << options.foot_radius_m << " m: fitting its " << surface_cells
      << " surface cells over " << 2 * window_half_cells + 1 << "^2-cell windows is " << work
      << " visits, more than the limit of " << options.max_fit_work
      << " (cell visits); give a coarser map (cells of "
      << std::max(0.5 * options.foot_radius_m, 1e-3) << " m or more suit this foot)";
  throw InputError(msg.str());
}

// Every layer's surface fit (AnalyzeSurface), in parts of at most kFitPartCells cells on
// options.threads threads: one large layer (a campus's ground) splits between the threads.
std::vector<SurfaceAnalysis> FitLayers(const std::vector<HeightMap>& layers, int window_half_cells, double res,
                                       const RegionExtractorOptions& options) {
  constexpr size_t kFitPartCells = 8192;
  struct Part {
    size_t layer, begin, end;
  };
  // Each layer's surface cells (a scan of the whole grid, whatever the layer holds) on the
  // threads too.
  std::vector<SurfaceAnalysis> surfaces(layers.size());
  ParallelFor(static_cast<int>(layers.size()), options.threads,
              [&](int l) { surfaces[static_cast<size_t>(l)] = SurfaceCellsOf(layers[static_cast<size_t>(l)]); });
  std::vector<Part> parts;
  for (size_t l = 0; l < layers.size(); ++l) {
    const size_t n = surfaces[l].cells.size();
    for (size_t begin = 0; begin < n; begin += kFitPartCells) parts.push_back({l, begin, std::min(n, begin + kFitPartCells)});
  }
  std::vector<uint8_t> stopped(parts.size(), 0);
  ParallelFor(static_cast<int>(parts.size()), options.threads, [&](int i) {
    const Part& part = parts[static_cast<size_t>(i)];
    stopped[static_cast<size_t>(i)] =
        !FitSurfaceCells(layers[part.layer], window_half_cells, options.grow_tolerance_voxels * res,
                         options.max_slope_rad, options.deadline, part.begin, part.end, &surfaces[part.layer]);
  });
  for (size_t i = 0; i < parts.size(); ++i) surfaces[parts[i].layer].stopped |= stopped[i] != 0;
  return surfaces;
}

// What decomposing one planar patch gave, before it is added to the result.
struct PatchOutcome {
  enum Kind { kNotStarted, kSteep, kSmall, kDecomposed } kind = kNotStarted;
  std::vector<Polygon2d> polygons;  // kDecomposed: the patch's regions in the plane's x-y
  std::vector<CellFate> fates;      // kDecomposed with record_cell_fates: per patch cell
  bool cut_short = false;           // kDecomposed: the deadline had expired at its end
  bool pieces_alone = false;        // kDecomposed: by the convex pieces alone (DecomposePatch)
  // kDecomposed: per polygon its region (id unset), or none where MakeRegionFromPolygon
  // threw (made again in order, so that the error names the region's id).
  std::vector<std::optional<ConvexRegion>> regions;
};

struct LayerPatch {
  int layer;
  PlanarPatch patch;
  // Decomposed while the largest layer was still being segmented (SegmentLayers'
  // early_decompose); none: not yet.
  std::optional<PatchOutcome> outcome;
};

// A patch's outcome (DecomposeOne of the patch of layer `layer`), for SegmentLayers.
using EarlyDecompose = std::function<PatchOutcome(int layer, const PlanarPatch& patch)>;

// The planar patches of every layer, largest first.
// `unseen`: SurfaceLayers::unseen (empty: no cell is).
// early_decompose (optional): each patch of a layer after the first is decomposed by it,
// layer by layer and in each layer's order, as soon as that layer is segmented and for as
// long as the first layer (the largest: one item) is still being segmented, so the
// threads that finished the small layers do not wait for it. An outcome does not depend
// on when it is made (the deadline aside), so the regions are the same.
std::vector<LayerPatch> SegmentLayers(const std::vector<HeightMap>& layers,
                                      const std::vector<SurfaceAnalysis>& surfaces,
                                      const std::vector<std::vector<uint8_t>>& unseen, double res,
                                      const RegionExtractorOptions& options, const EarlyDecompose& early_decompose) {
  SegmentationOptions seg;
  // The small margin keeps exact one-voxel risers of a voxelised tilt inside the tolerance.
  seg.grow_tolerance_m = options.grow_tolerance_voxels * res * (1.0 + 1e-3);
  seg.max_residual_m = options.max_residual_voxels * res;
  seg.max_seed_roughness_m = options.seed_roughness_voxels * res;
  seg.noise_tolerance_m = options.noise_tolerance_voxels * res;
  seg.noise_max_cells = options.noise_max_cells;
  // A patch holds a foot when one of its cells holds the disk a foot needs: its radius
  // with the margin and the edge uncertainty (the inset beside a drop).
  if (options.noise_max_cells > 0) {
    seg.noise_patch_foot_radius_m =
        options.foot_radius_m + options.edge_margin_m + options.edge_uncertainty_voxels * res;
  }
  // The noise levels' off cells of every layer in bands of rows (a large layer's split
  // between the threads), then each layer's patches on its own (options.threads threads),
  // gathered in layer order.
  const bool noise_levels = seg.noise_patch_foot_radius_m > 0.0 && seg.noise_max_cells > 0;
  std::vector<std::vector<OffCell>> off;
  if (noise_levels) off = OffCellsOfLayers(layers, surfaces, seg.noise_tolerance_m, options.threads);
  std::vector<std::vector<PlanarPatch>> per_layer(layers.size());
  std::vector<std::vector<std::optional<PatchOutcome>>> early(layers.size());
  std::atomic<bool> first_done{false};
  ParallelFor(static_cast<int>(layers.size()), options.threads, [&](int l) {
    SegmentationOptions own = seg;
    own.unseen = static_cast<size_t>(l) < unseen.size() ? &unseen[static_cast<size_t>(l)] : nullptr;
    NoiseLevels levels;
    if (noise_levels) {
      levels = NoiseFreeLevelsFrom(layers[static_cast<size_t>(l)], off[static_cast<size_t>(l)], seg.noise_max_cells);
      own.noise_levels = &levels;
    }
    const auto layer = static_cast<size_t>(l);
    per_layer[layer] = SegmentPlanarPatches(layers[layer], surfaces[layer], own);
    if (l == 0) {
      first_done = true;
      return;
    }
    early[layer].resize(per_layer[layer].size());
    for (size_t k = 0; k < per_layer[layer].size() && early_decompose && !first_done; ++k) {
      PatchOutcome outcome = early_decompose(l, per_layer[layer][k]);
      if (outcome.kind != PatchOutcome::kNotStarted) early[layer][k] = std::move(outcome);
    }
  });
  std::vector<LayerPatch> patches;
  for (size_t l = 0; l < layers.size(); ++l) {
    for (size_t k = 0; k < per_layer[l].size(); ++k) {
      patches.push_back({static_cast<int>(l), std::move(per_layer[l][k]),
                         k < early[l].size() ? std::move(early[l][k]) : std::nullopt});
    }
  }
  std::stable_sort(patches.begin(), patches.end(), [](const LayerPatch& a, const LayerPatch& b) {
    return a.patch.cells.size() > b.patch.cells.size();
  });
  return patches;
}

PatchDecompositionOptions DecompositionOptions(double res, const RegionExtractorOptions& options) {
  PatchDecompositionOptions dec;
  dec.inset_m = options.foot_radius_m + options.edge_margin_m;
  // The true edge may lie inside the outermost occupied voxel only where the surface has
  // no material rising beside it (a drop or unseen space), not at a wall or a riser.
  dec.drop_inset_m = options.edge_uncertainty_voxels * res;
  dec.riser_inset_m = options.riser_uncertainty_voxels * res;
  dec.axis_snap_rad = options.axis_snap_rad;
  dec.cover.target_coverage = options.target_coverage;
  dec.cover.max_rects = options.max_regions_per_patch;
  dec.cover.grow_over_covered = options.overlapping_regions;
  dec.cover.deadline = options.deadline;
  dec.convex_pieces = options.convex_cover;
  dec.max_piece_vertices = options.max_region_vertices;
  dec.convex_alone_cells = options.convex_alone_cells;
  dec.convex_alone_outline = options.convex_alone_outline;
  dec.convex_alone_outline_share = options.convex_alone_outline_share;
  dec.shrunk_seeds = options.convex_shrunk_seeds;
  dec.shrunk_seed_min_cells = options.convex_shrunk_seed_min_cells;
  // Slivers along a ragged outline: a piece narrower than the foot's radius (its inscribed
  // disk smaller than half the foot) adds little floor and one more region to choose.
  dec.min_piece_width_m = options.foot_radius_m;
  return dec;
}

// A plan-view polygon's corners lifted onto the patch's plane.
std::vector<Eigen::Vector3d> OnPlane(const PlanarPatch& patch, const Polygon2d& polygon) {
  std::vector<Eigen::Vector3d> vertices;
  vertices.reserve(polygon.size());
  for (const Eigen::Vector2d& xy : polygon) vertices.emplace_back(xy.x(), xy.y(), patch.HeightAt(xy));
  return vertices;
}

// The patch's polygons as regions on its plane (PatchOutcome::regions).
std::vector<std::optional<ConvexRegion>> RegionsOf(const PlanarPatch& patch, const std::vector<Polygon2d>& polygons,
                                                   double plane_tolerance_m) {
  std::vector<std::optional<ConvexRegion>> regions(polygons.size());
  for (size_t k = 0; k < polygons.size(); ++k) {
    try {
      regions[k] = MakeRegionFromPolygon(-1, OnPlane(patch, polygons[k]), plane_tolerance_m);
    } catch (const InputError&) {
      regions[k].reset();
    }
  }
  return regions;
}

// The patch's outcome; kNotStarted when the deadline has expired.
PatchOutcome DecomposeOne(int patch_layer, const PlanarPatch& patch, const std::vector<HeightMap>& layers,
                          const std::vector<std::vector<uint8_t>>& solid_beside,
                          const std::vector<std::vector<uint8_t>>& filled, double res,
                          const RegionExtractorOptions& options, PatchDecompositionOptions dec) {
  PatchOutcome out;
  if (options.deadline.Expired()) return out;
  const double slope = patch.SlopeRad();
  if (slope > options.max_slope_rad) {
    out.kind = PatchOutcome::kSteep;
    return out;
  }
  const double cos_slope = std::cos(slope);
  const double patch_area_m2 = patch.cells.size() * res * res / cos_slope;
  if (patch_area_m2 < M_PI * options.foot_radius_m * options.foot_radius_m) {
    out.kind = PatchOutcome::kSmall;
    return out;
  }
  const double min_area_m2 = options.min_region_area_voxels > 0.0
                                 ? std::min(options.min_region_area_m2, options.min_region_area_voxels * res * res)
                                 : options.min_region_area_m2;
  // Region area on the plane = projected area / cos(slope).
  dec.min_area_xy_m2 = min_area_m2 * cos_slope;
  const auto layer = static_cast<size_t>(patch_layer);
  dec.solid_beside = &solid_beside[layer];
  if (layer < filled.size() && !filled[layer].empty()) dec.filled = &filled[layer];
  dec.cover.max_rects = static_cast<int>(std::min(
      1e4, std::max<double>(options.max_regions_per_patch, std::ceil(options.regions_per_m2 * patch_area_m2))));
  out.kind = PatchOutcome::kDecomposed;
  out.polygons = DecomposePatch(layers[layer], patch, dec,
                                options.record_cell_fates ? &out.fates : nullptr, &out.pieces_alone);
  out.regions = RegionsOf(patch, out.polygons, options.plane_tolerance_voxels * res);
  // The cover checks the deadline before each piece: one that expired during this patch
  // may have cut its cover short, which the result must say (not count as a small patch).
  out.cut_short = options.deadline.Expired();
  return out;
}

// The patches' outcomes in order, on options.threads threads. Patches after the one whose
// regions pass max_regions are not needed (they stay kNotStarted or are ignored).
// Patches decomposed already (LayerPatch::outcome) are not decomposed again.
std::vector<PatchOutcome> DecomposeAll(std::vector<LayerPatch>* patches,
                                       const std::vector<std::vector<uint8_t>>& solid_beside,
                                       const std::vector<std::vector<uint8_t>>& filled, double res,
                                       const RegionExtractorOptions& options, const std::vector<HeightMap>& layers) {
  const PatchDecompositionOptions dec = DecompositionOptions(res, options);
  std::vector<PatchOutcome> outcomes(patches->size());
  // The finished prefix: patches [0, prefix) done, holding prefix_regions polygons.
  std::mutex progress;
  std::vector<uint8_t> done(patches->size(), 0);
  size_t prefix = 0, prefix_regions = 0;
  std::atomic<bool> enough{false};
  ParallelFor(static_cast<int>(patches->size()), options.threads, [&](int i) {
    if (enough) return;
    LayerPatch& lp = (*patches)[static_cast<size_t>(i)];
    PatchOutcome outcome = lp.outcome ? std::move(*lp.outcome)
                                      : DecomposeOne(lp.layer, lp.patch, layers, solid_beside, filled, res, options, dec);
    const std::lock_guard<std::mutex> lock(progress);
    outcomes[static_cast<size_t>(i)] = std::move(outcome);
    done[static_cast<size_t>(i)] = 1;
    for (; prefix < done.size() && done[prefix]; ++prefix) prefix_regions += outcomes[prefix].polygons.size();
    if (prefix_regions > static_cast<size_t>(options.max_regions)) enough = true;
  });
  return outcomes;
}

// Decomposes the patches, largest first, into result's regions until the deadline or
// max_regions; counts the patches too steep or too small in result's stats.
void DecomposePatches(std::vector<LayerPatch>* patch_list, const std::vector<std::vector<uint8_t>>& solid_beside,
                      double res, const RegionExtractorOptions& options, RegionExtractionResult* result) {
  RegionExtractionStats& stats = result->stats;
  const double plane_tolerance_m = options.plane_tolerance_voxels * res;
  const bool record = options.record_cell_fates;
  auto mark = [&](const LayerPatch& lp, CellFate fate) {
    if (!record) return;
    for (int cell : lp.patch.cells) result->cell_fates[static_cast<size_t>(lp.layer)][static_cast<size_t>(cell)] = fate;
  };
  std::vector<PatchOutcome> outcomes = DecomposeAll(patch_list, solid_beside, result->filled, res, options, result->layers);
  const std::vector<LayerPatch>& patches = *patch_list;
  int patches_done = 0;
  bool capped = false;   // max_regions reached: the patches left are not decomposed
  bool expired = false;  // a patch found the deadline expired: it and those after are not decomposed
  for (size_t k = 0; k < patches.size(); ++k) {
    const LayerPatch& layer_patch = patches[k];
    PatchOutcome& outcome = outcomes[k];
    expired = expired || outcome.kind == PatchOutcome::kNotStarted;
    if (capped || expired) {
      mark(layer_patch, CellFate::kNotDecomposed);
      if (capped || result->stopped) continue;
      result->stopped = true;
      result->message = "time limit reached after " + std::to_string(patches_done) + " of " +
                        std::to_string(patches.size()) + " planar patches (the largest first)";
      continue;
    }
    ++patches_done;
    if (outcome.kind == PatchOutcome::kSteep || outcome.kind == PatchOutcome::kSmall) {
      ++(outcome.kind == PatchOutcome::kSteep ? stats.patches_too_steep : stats.patches_too_small);
      mark(layer_patch, outcome.kind == PatchOutcome::kSteep ? CellFate::kSteepPatch : CellFate::kSmallPatch);
      continue;
    }
    const PlanarPatch& patch = layer_patch.patch;
    if (outcome.cut_short && !result->stopped) {
      result->stopped = true;
      result->message = "time limit reached during planar patch " + std::to_string(patches_done) + " of " +
                        std::to_string(patches.size()) + " (the largest first); its cover may be incomplete";
    }
    if (outcome.polygons.empty() && !outcome.cut_short) ++stats.patches_too_small;
    if (outcome.pieces_alone) ++stats.patches_convex_alone;
    if (record) {
      const CellFate empty_fate = outcome.cut_short ? CellFate::kNotDecomposed : CellFate::kSmallPatch;
      for (size_t i = 0; i < patch.cells.size(); ++i) {
        const CellFate fate = outcome.polygons.empty() ? empty_fate : outcome.fates[i];
        result->cell_fates[static_cast<size_t>(layer_patch.layer)][static_cast<size_t>(patch.cells[i])] = fate;
      }
    }
    for (size_t k = 0; k < outcome.polygons.size(); ++k) {
      if (static_cast<int>(result->regions.size()) >= options.max_regions) {
        capped = true;
        break;
      }
      const int id = static_cast<int>(result->regions.size());
      if (outcome.regions[k]) {
        result->regions.push_back(std::move(*outcome.regions[k]));
        result->regions.back().id = id;
      } else {
        result->regions.push_back(MakeRegionFromPolygon(id, OnPlane(patch, outcome.polygons[k]), plane_tolerance_m));
      }
      result->region_layer.push_back(layer_patch.layer);
    }
  }
  if (capped) {
    result->message = "kept the " + std::to_string(options.max_regions) +
                      " regions of the largest planar patches (max_regions); smaller footholds are missing";
  }
}

// Every surface cell not in a patch yet; empty cells kNoSurface.
void InitCellFates(RegionExtractionResult* result) {
  result->cell_fates.clear();
  for (const HeightMap& hm : result->layers) {
    std::vector<CellFate> fates(hm.height_m.size(), CellFate::kNoSurface);
    for (size_t i = 0; i < fates.size(); ++i) {
      if (!std::isnan(hm.height_m[i])) fates[i] = CellFate::kNotInPatch;
    }
    result->cell_fates.push_back(std::move(fates));
  }
}

std::string NoRegionsMessage(const RegionExtractionStats& stats, const RegionExtractorOptions& options) {
  std::ostringstream msg;
  msg << "no walkable regions: " << stats.patches << " planar patches, " << stats.patches_too_steep
      << " steeper than " << options.max_slope_rad << " rad, " << stats.patches_too_small
      << " too small for a foot of radius " << options.foot_radius_m << " m";
  return msg.str();
}

// The stages after the surface layers: surface fit, planar patches, decomposition.
// `result` holds the layers' statistics already; `start` is when the extraction began.
void ExtractFromLayers(const SurfaceLayers& layers, const RegionExtractorOptions& options,
                       Clock::time_point start, RegionExtractionResult* result) {
  RegionExtractionStats& stats = result->stats;
  const double res = result->height_map.resolution_m;

  Clock::time_point t = Clock::now();
  // The fit window is at least a foot wide (and at least 3 cells).
  const int window_half_cells = std::max(1, static_cast<int>(std::ceil(options.foot_radius_m / res)));
  CheckFitWork(res, stats.surface_cells, window_half_cells, options);
  std::vector<SurfaceAnalysis> surfaces = FitLayers(result->layers, window_half_cells, res, options);
  stats.analysis_s = SecondsSince(t);
  if (std::any_of(surfaces.begin(), surfaces.end(), [](const SurfaceAnalysis& s) { return s.stopped; })) {
    result->stopped = true;
    result->message = "time limit reached during the surface fit: no regions";
    stats.total_s = SecondsSince(start);
    return;
  }

  t = Clock::now();
  const PatchDecompositionOptions dec = DecompositionOptions(res, options);
  const EarlyDecompose early = [&](int layer, const PlanarPatch& patch) {
    return DecomposeOne(layer, patch, result->layers, layers.solid_beside, result->filled, res, options, dec);
  };
  std::vector<LayerPatch> patches = SegmentLayers(result->layers, surfaces, layers.unseen, res, options, early);
  stats.segmentation_s = SecondsSince(t);
  stats.patches = static_cast<int>(patches.size());

  if (options.record_cell_fates) InitCellFates(result);
  t = Clock::now();
  DecomposePatches(&patches, layers.solid_beside, res, options, result);
  stats.decomposition_s = SecondsSince(t);
  stats.total_s = SecondsSince(start);
  if (result->regions.empty() && !result->stopped) result->message = NoRegionsMessage(stats, options);
}

}  // namespace

RegionExtractionResult ExtractRegions(const OccupancyMap& map,
                                      const RegionExtractorOptions& options) {
  ValidateOptions(options);
  const Clock::time_point start = Clock::now();
  RegionExtractionResult result;
  RegionExtractionStats& stats = result.stats;
  SurfaceLayers layers = LayersOf(map, options);
  result.layers = std::move(layers.layers);
  result.moved_as_seen = std::move(layers.moved_as_seen);
  result.filled = std::move(layers.filled);
  result.height_map = result.layers.front();
  stats.layers = static_cast<int>(result.layers.size());
  stats.no_room_above = layers.no_room_above;
  stats.not_seen_from_above = layers.not_seen_from_above;
  stats.isolated_voxels = layers.isolated_voxels;
  stats.height_map_s = SecondsSince(start);
  if (map.leaves.empty()) {
    result.message = "the map has no occupied voxels, so it has no regions";
    stats.total_s = SecondsSince(start);
    return result;
  }
  stats.surface_cells = layers.candidates;
  ExtractFromLayers(layers, options, start, &result);
  if (options.body_obstacles) {
    MapObstacleOptions body = *options.body_obstacles;
    body.deadline = options.deadline;
    result.body_obstacles = MapBodyObstacles(map, body);
  }
  return result;
}

RegionExtractionResult ExtractRegionsFromLayers(SurfaceLayers layers,
                                                const RegionExtractorOptions& options) {
  ValidateOptions(options);
  MFP_CHECK(!layers.layers.empty() && layers.layers.size() == layers.solid_beside.size());
  const Clock::time_point start = Clock::now();
  RegionExtractionResult result;
  result.layers = std::move(layers.layers);
  result.moved_as_seen = std::move(layers.moved_as_seen);
  result.filled = std::move(layers.filled);
  result.height_map = result.layers.front();
  result.stats.layers = static_cast<int>(result.layers.size());
  result.stats.surface_cells = layers.candidates;
  result.stats.height_map_s = 0.0;
  if (layers.candidates == 0) {
    result.message = "the map has no known surface cells, so it has no regions";
    return result;
  }
  ExtractFromLayers(layers, options, start, &result);
  return result;
}

RegionExtractionResult ExtractRegionsFromTerrain(const TerrainDescription& terrain,
                                                 const RegionExtractorOptions& options) {
  RegionExtractorOptions own = options;
  if (terrain.scan.sensors_world_m.empty() && !terrain.noise.Any()) {
    // A plain voxelisation marks a voxel occupied when its centre is inside a box, so a
    // true edge lies within half a voxel of the occupied cells' faces.
    own.edge_uncertainty_voxels = std::min(own.edge_uncertainty_voxels, 0.5);
  } else if (!terrain.scan.sensors_world_m.empty()) {
    // Occupancy from rays: a voxel any ray hits is occupied, so a wall reaching into a
    // surface's top voxel would have occupied the voxel above it.
    own.riser_uncertainty_voxels = 0.0;
  }
  if (terrain.scan.sensors_world_m.empty() && own.body_obstacles) {
    // The same for the body's obstacles: a wall's true face up to half a voxel outside.
    own.body_obstacles->grow_m = std::max(own.body_obstacles->grow_m, 0.5 * terrain.resolution_m);
  }
  return ExtractRegions(MakeTerrainMap(terrain), own);
}

}  // namespace mfp

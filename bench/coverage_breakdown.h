#pragma once
// Where the certifiable floor of a real scan goes: each certifiable floor cell the
// regions miss (voxel_quality.h), put down to what the extractor did with the height
// map cell under it (cell_fate.h).
#include <array>
#include <string>

#include "terrain/extraction/cell_fate.h"
#include "terrain/extraction/region_extractor.h"
#include "terrain/quality/voxel_quality.h"

namespace mfp {

// Causes of a missed cell: the extractor's fates, plus two only the judge can tell.
struct CoverageBreakdown {
  int certifiable = 0;
  int missed = 0;
  std::array<int, kCellFateCount> by_fate{};  // kCovered here: covered, at the wrong height
  int no_layer_surface = 0;  // no layer has a surface within a voxel of the judge's floor there
};

// The fate of the layer cell under a floor point (the furthest fate of the layers with a
// surface, or a patch's unseen cell, within a voxel of the point's height), or -1 when
// none has; `result` extracted with record_cell_fates.
int FateUnder(const Eigen::Vector3d& point, const RegionExtractionResult& result);

// `quality` judged with list_missed; `result` extracted with record_cell_fates.
CoverageBreakdown BreakDownMissedFloor(const VoxelQuality& quality, const RegionExtractionResult& result);

// The table's header and one row (percent of the certifiable floor per cause).
void PrintBreakdownHeader();
void PrintBreakdownRow(const std::string& name, const CoverageBreakdown& breakdown);

}  // namespace mfp

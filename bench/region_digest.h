#pragma once
// mfp-terrain-bench --digest: per map (the real scans given and the catalogue's simulated
// maps), the regions' count and a hash of their vertices' exact bits, with each extraction
// stage's time and the whole extraction's CPU and wall time. Two builds printing the same
// digests extract the same regions (the check for a change meant to keep them).
#include <string>
#include <vector>

#include "terrain/extraction/region_extractor.h"

namespace mfp {

// One line per map; `runs` extractions per map, the stage times of the run of median CPU
// printed, and the median wall time. scans_only: the scans alone (no catalogue maps).
void PrintRegionDigests(const std::vector<std::string>& scans, const RegionExtractorOptions& options, int runs,
                        bool scans_only);

}  // namespace mfp

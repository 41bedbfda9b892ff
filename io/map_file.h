#pragma once
// A terrain map file of any kind mfp reads, to regions: an OctoMap (.bt, .ot) or a height
// map (.npy with its YAML, or the YAML: height_map_file.h). What `mfp-plan --terrain`,
// `mfp-regions` and a scenario's `terrain: {map: FILE}` accept.
#include <string>

#include "terrain/extraction/region_extractor.h"

namespace mfp {

// Throws InputError naming the file when its extension is none of .bt, .ot, .npy, .yaml,
// .yml, or as LoadMapFile, LoadHeightGridFile and the extractors do.
RegionExtractionResult ExtractRegionsFromMapFile(const std::string& path,
                                                 const RegionExtractorOptions& options);

// True when ExtractRegionsFromMapFile reads this kind of file (by its extension).
bool IsMapFilePath(const std::string& path);

}  // namespace mfp

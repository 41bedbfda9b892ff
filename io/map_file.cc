#include "io/map_file.h"

#include "base/check.h"
#include "io/file_paths.h"
#include "io/height_map_file.h"
#include "terrain/extraction/height_grid.h"
#include "terrain/octomap/octomap_io.h"

namespace mfp {
namespace {

bool IsOctomapPath(const std::string& path) {
  const std::string ext = FileExtension(path);
  return ext == "bt" || ext == "ot";
}

}  // namespace

bool IsMapFilePath(const std::string& path) { return IsOctomapPath(path) || IsHeightMapPath(path); }

RegionExtractionResult ExtractRegionsFromMapFile(const std::string& path,
                                                 const RegionExtractorOptions& options) {
  if (IsOctomapPath(path)) return ExtractRegions(LoadMapFile(path), options);
  if (IsHeightMapPath(path)) {
    return ExtractRegionsFromHeightGrid(LoadHeightGridFile(path, options.max_height_map_cells), options);
  }
  throw InputError(path + ": expected a .bt or .ot map, or a height map (.npy with its .yaml, or the .yaml)");
}

}  // namespace mfp

#include "terrain/octomap/octomap_io.h"

#include <octomap/OcTree.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>

#include "base/bounded_file.h"
#include "base/check.h"
#include "terrain/extraction/voxelize.h"

namespace mfp {
namespace {

bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

OccupancyMap FromOcTree(const octomap::OcTree& tree) {
  OccupancyMap map;
  map.resolution_m = tree.getResolution();
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    const octomap::point3d c = it.getCoordinate();
    const OccupiedLeaf leaf{Eigen::Vector3d(c.x(), c.y(), c.z()), it.getSize()};
    (tree.isNodeOccupied(*it) ? map.leaves : map.free_leaves).push_back(leaf);
  }
  return map;
}

std::unique_ptr<octomap::OcTree> ToOcTree(const OccupancyMap& map) {
  if (!std::isfinite(map.resolution_m) || map.resolution_m < 0.001 || map.resolution_m > 1.0) {
    throw InputError("map resolution must be in [0.001, 1] m");
  }
  auto tree = std::make_unique<octomap::OcTree>(map.resolution_m);
  const double limit_m = OctreeHalfExtentM(map.resolution_m) - map.resolution_m;
  // Free leaves first, so a voxel listed as both ends up occupied.
  auto set_leaf = [&](const OccupiedLeaf& leaf, bool occupied) {
    if (!leaf.center_world_m.allFinite() || leaf.center_world_m.cwiseAbs().maxCoeff() > limit_m) {
      throw InputError("map leaf outside the octree's range of +-" + std::to_string(limit_m) + " m");
    }
    // Larger leaves are written voxel by voxel; pruning merges them again.
    const int n = std::max(1, static_cast<int>(std::lround(leaf.size_m / map.resolution_m)));
    const Eigen::Vector3d corner =
        leaf.center_world_m - Eigen::Vector3d::Constant(0.5 * leaf.size_m - 0.5 * map.resolution_m);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        for (int k = 0; k < n; ++k) {
          const Eigen::Vector3d c = corner + map.resolution_m * Eigen::Vector3d(i, j, k);
          tree->setNodeValue(octomap::point3d(c.x(), c.y(), c.z()),
                             occupied ? tree->getClampingThresMaxLog() : tree->getClampingThresMinLog(),
                             true);
        }
      }
    }
  };
  for (const OccupiedLeaf& leaf : map.free_leaves) set_leaf(leaf, false);
  for (const OccupiedLeaf& leaf : map.leaves) set_leaf(leaf, true);
  tree->updateInnerOccupancy();
  tree->prune();
  return tree;
}

OccupancyMap LoadMapData(const uint8_t* data, size_t size, const std::string& what,
                         const OctreeStreamLimits& limits) {
  // Everything OctoMap would trip over is rejected here first, and so is a tree whose
  // leaves would expand into more column cells than the limit.
  const OctreeStreamInfo info = CheckOctreeStream(data, size, what, limits);
  // Read only the data section, with the header already checked: OctoMap's own header
  // readers print progress to stderr, and libraries here do not print.
  octomap::OcTree tree(info.resolution_m);
  if (info.declared_nodes > 0) {
    std::istringstream in(std::string(reinterpret_cast<const char*>(data) + info.data_offset,
                                      size - info.data_offset),
                          std::ios::binary);
    if (info.kind == OctreeFileKind::kBinary) {
      tree.readBinaryData(in);
    } else {
      tree.readData(in);
    }
    // The checker walked the same encoding, so a mismatch here is a bug in it.
    MFP_CHECK_MSG(tree.size() == info.declared_nodes, what + ": node count differs after reading");
  }
  return FromOcTree(tree);
}

}  // namespace

OccupancyMap LoadMapBytes(const std::vector<uint8_t>& bytes, const std::string& what,
                          const OctreeStreamLimits& limits) {
  return LoadMapData(bytes.data(), bytes.size(), what, limits);
}

OccupancyMap LoadMapFile(const std::string& path, const OctreeStreamLimits& limits) {
  // Only a regular file (never a FIFO or a device), at most limits.max_bytes.
  const std::string bytes = ReadBoundedRegularFile(path, limits.max_bytes, "map file");
  return LoadMapData(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), path, limits);
}

std::vector<uint8_t> OccupancyMapBytes(const OccupancyMap& map, bool binary) {
  const std::unique_ptr<octomap::OcTree> tree = ToOcTree(map);
  // The header is written here and the data by OctoMap's data writers: its whole-file
  // writers print progress to stderr, and libraries here do not print.
  std::ostringstream out(std::ios::binary);
  out.precision(17);
  if (binary) tree->toMaxLikelihood();
  tree->prune();
  out << (binary ? "# Octomap OcTree binary file\n" : "# Octomap OcTree file\n")
      << "# written by mfp\nid " << tree->getTreeType() << "\nsize " << tree->size()
      << "\nres " << tree->getResolution() << "\ndata\n";
  if (binary) {
    tree->writeBinaryData(out);
  } else {
    tree->writeData(out);
  }
  MFP_CHECK_MSG(static_cast<bool>(out), "OctoMap failed to serialise a tree");
  const std::string s = out.str();
  return std::vector<uint8_t>(s.begin(), s.end());
}

void WriteOccupancyMap(const OccupancyMap& map, const std::string& out_path) {
  bool binary = true;
  if (EndsWith(out_path, ".ot")) {
    binary = false;
  } else if (!EndsWith(out_path, ".bt")) {
    throw InputError(out_path + ": the map file name must end in .bt or .ot");
  }
  const std::vector<uint8_t> bytes = OccupancyMapBytes(map, binary);
  std::ofstream file(out_path, std::ios::binary | std::ios::trunc);
  if (!file) throw InputError(out_path + ": cannot open the file for writing");
  file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!file) throw InputError(out_path + ": writing the map failed");
}

void WriteTerrainMap(const TerrainDescription& terrain, const std::string& out_path) {
  if (!EndsWith(out_path, ".ot") && !EndsWith(out_path, ".bt")) {
    throw InputError(out_path + ": the map file name must end in .bt or .ot");
  }
  WriteOccupancyMap(VoxelizeTerrain(terrain), out_path);
}

std::vector<ConvexRegion> RegionsFromMapFile(const std::string& path, double foot_radius_m,
                                             double max_slope_rad, const Deadline& deadline,
                                             std::string* note, double clearance_m) {
  RegionExtractorOptions options;
  options.clearance_m = clearance_m;
  options.foot_radius_m = foot_radius_m;
  options.max_slope_rad = max_slope_rad;
  options.deadline = deadline;
  RegionExtractionResult result = ExtractRegions(LoadMapFile(path), options);
  if (note != nullptr) *note = result.message;
  return std::move(result.regions);
}

}  // namespace mfp

#pragma once
// Validates a whole OctoMap file (.bt binary or .ot full) before OctoMap reads it.
// OctoMap's reader trusts its input: it recurses without a depth limit, reads past the
// end of the data, and keeps a partial tree when the data is short. This checker walks
// the same encoding with hard limits (16 levels, node count, byte count), so every stream
// it accepts is complete and consistent and OctoMap reads it without surprises.
// No OctoMap headers: the format is re-implemented here from its documentation.
#include <cstddef>
#include <cstdint>
#include <string>

#include "terrain/extraction/leaf_budget.h"

namespace mfp {

enum class OctreeFileKind { kBinary, kFull };  // .bt ("binary file"), .ot ("file")

struct OctreeStreamLimits {
  size_t max_bytes = size_t{256} << 20;  // whole file [bytes]
  // Nodes of the tree (inner and leaves). OctoMap holds about 115 bytes a node while
  // reading, so this caps a map's memory near 0.5 GB (and its reading time at seconds).
  uint64_t max_nodes = 4'000'000;
  // Column cells the leaves cover: a leaf of n x n x n voxels counts n^2, since the
  // surface extraction cuts every leaf into one run per x-y column it covers (about 16
  // bytes a run, plus the same again while sorting). Caps a map's extraction memory near
  // 0.5 GB whatever its node count: a 91-byte tree of a few 4096^3-voxel leaves would
  // otherwise expand to hundreds of millions of runs.
  uint64_t max_leaf_columns = kDefaultMaxLeafColumns;
  double min_resolution_m = 1e-4;
  double max_resolution_m = 10.0;
};

struct OctreeStreamInfo {
  OctreeFileKind kind = OctreeFileKind::kBinary;
  std::string id;               // tree type, "OcTree"
  double resolution_m = 0.0;
  uint64_t declared_nodes = 0;  // the header's "size"
  size_t data_offset = 0;       // first byte after the "data" line
  uint64_t nodes = 0;           // nodes found in the data
  uint64_t leaf_columns = 0;    // column cells the leaves cover (sum of n^2 over leaves)
};

// Throws InputError naming `what` (a file name or "map message") and the problem when the
// header is missing or malformed, the tree type is not OcTree, the resolution or declared
// size is out of range, the data ends early, nests deeper than 16 levels, holds more
// nodes than declared or allowed, has leaves covering more than limits.max_leaf_columns
// column cells, carries a non-finite occupancy, or has trailing bytes.
OctreeStreamInfo CheckOctreeStream(const uint8_t* data, size_t size, const std::string& what,
                                   const OctreeStreamLimits& limits = OctreeStreamLimits());

}  // namespace mfp

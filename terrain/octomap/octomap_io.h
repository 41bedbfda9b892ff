#pragma once
// OctoMap adapter: .bt / .ot files (or the bytes of one, as the LCM map message carries
// them) to and from the plain OccupancyMap. The only header of the terrain code whose
// implementation includes OctoMap; nothing OctoMap leaks through this interface.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "geometry/terrain_description.h"
#include "terrain/extraction/occupancy_map.h"
#include "terrain/extraction/region_extractor.h"
#include "terrain/octomap/internal/octree_stream_check.h"

namespace mfp {

// Reads a map file. Throws InputError (naming the file) when it is missing, unreadable,
// larger than limits.max_bytes, or not a complete, consistent OcTree map (see
// CheckOctreeStream). An empty map (no nodes) gives an OccupancyMap without leaves.
OccupancyMap LoadMapFile(const std::string& path,
                         const OctreeStreamLimits& limits = OctreeStreamLimits());

// The same for the bytes of a whole .bt or .ot file; `what` names them in messages.
OccupancyMap LoadMapBytes(const std::vector<uint8_t>& bytes, const std::string& what,
                          const OctreeStreamLimits& limits = OctreeStreamLimits());

// Writes the map of a terrain description (VoxelizeTerrain) as an OcTree file: binary
// .bt, or full .ot when out_path ends in ".ot". Throws InputError on a bad description,
// another extension, or a file that cannot be written.
void WriteTerrainMap(const TerrainDescription& terrain, const std::string& out_path);

// Writes an occupancy map the same way (leaves must lie on the map's grid).
void WriteOccupancyMap(const OccupancyMap& map, const std::string& out_path);

// The bytes of an occupancy map as a .bt (binary = true) or .ot file.
std::vector<uint8_t> OccupancyMapBytes(const OccupancyMap& map, bool binary);

// Loads a map file and extracts its regions with the default options and the given foot
// radius, slope limit and clearance (free space a surface needs above it; infinity: the
// highest surface of each column), until the deadline. Throws InputError as LoadMapFile
// and ExtractRegions do. `note` (optional) receives the extractor's message.
std::vector<ConvexRegion> RegionsFromMapFile(const std::string& path, double foot_radius_m,
                                             double max_slope_rad,
                                             const Deadline& deadline = Deadline(),
                                             std::string* note = nullptr,
                                             double clearance_m = std::numeric_limits<double>::infinity());

}  // namespace mfp

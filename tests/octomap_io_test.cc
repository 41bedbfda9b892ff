// OctoMap files: round trips through .bt and .ot, and malformed, truncated, random and
// huge inputs, which must give an InputError (never a crash, never a partial map).
#include "terrain/octomap/octomap_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "base/check.h"
#include "terrain/extraction/region_extractor.h"
#include "terrain/extraction/voxelize.h"
#include "terrain/quality/terrain_catalogue.h"
#include "tests/input_error_of.h"
#include "tests/test_temp_path.h"

namespace mfp {
namespace {

std::vector<uint8_t> Bytes(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }

std::string ErrorOf(const std::vector<uint8_t>& bytes,
                    const OctreeStreamLimits& limits = OctreeStreamLimits()) {
  return InputErrorOf([&] { LoadMapBytes(bytes, "test map", limits); });
}

const char kBinaryHeader[] = "# Octomap OcTree binary file\nid OcTree\nsize 5\nres 0.1\ndata\n";

TEST(OctomapIoTest, BinaryAndFullFilesRoundTripToTheSameRegions) {
  const TerrainDescription t = StepTerrain();
  const RegionExtractorOptions options;
  // The same voxels extracted directly (ExtractRegionsFromTerrain would know they are a
  // plain voxelisation and use half a voxel of edge uncertainty; a file does not say).
  const RegionExtractionResult direct = ExtractRegions(VoxelizeTerrain(t), options);
  for (const std::string ext : {".bt", ".ot"}) {
    const std::string path = TestTempPath("step" + ext);
    WriteTerrainMap(t, path);
    const OccupancyMap map = LoadMapFile(path);
    std::filesystem::remove(path);
    EXPECT_NEAR(map.resolution_m, 0.02, 1e-12);
    // Pruning merged voxels into larger leaves.
    bool pruned = false;
    for (const OccupiedLeaf& leaf : map.leaves) pruned = pruned || leaf.size_m > 0.03;
    EXPECT_TRUE(pruned) << ext;
    const RegionExtractionResult loaded = ExtractRegions(map, options);
    ASSERT_EQ(loaded.regions.size(), direct.regions.size()) << ext;
    for (size_t i = 0; i < loaded.regions.size(); ++i) {
      EXPECT_NEAR(loaded.regions[i].area_m2, direct.regions[i].area_m2, 1e-9) << ext;
    }
  }
  const std::string path = TestTempPath("flat.bt");
  WriteTerrainMap(FlatTerrain(), path);
  EXPECT_EQ(RegionsFromMapFile(path, 0.01, 0.4).size(), 1u);
  std::filesystem::remove(path);
}

TEST(OctomapIoTest, ColorOcTreeBinaryReadsAsOcTree) {
  // Public sample maps (OctoMap's fr_078_tidyup.bt) are colour trees saved as .bt: the
  // binary data is occupancy only, so only the header's id differs from an OcTree's.
  std::vector<uint8_t> bytes = OccupancyMapBytes(VoxelizeTerrain(StepTerrain()), true);
  std::string text(bytes.begin(), bytes.end());
  const size_t id = text.find("id OcTree\n");
  ASSERT_NE(id, std::string::npos);
  const OccupancyMap plain = LoadMapBytes(bytes, "plain");
  for (const std::string tree : {"ColorOcTree", "OcTreeStamped"}) {
    std::string renamed = text;
    renamed.replace(id, std::strlen("id OcTree\n"), "id " + tree + "\n");
    const OccupancyMap map = LoadMapBytes(Bytes(renamed), tree);
    EXPECT_EQ(map.leaves.size(), plain.leaves.size()) << tree;
    EXPECT_EQ(map.free_leaves.size(), plain.free_leaves.size()) << tree;
  }
}

TEST(OctomapIoTest, MissingFileAndBadExtensionAreInputErrors) {
  EXPECT_THROW(LoadMapFile("/nonexistent/map.bt"), InputError);
  EXPECT_THROW(WriteTerrainMap(FlatTerrain(), TestTempPath("map.png")), InputError);
}

TEST(OctomapIoTest, EmptyMapLoadsWithoutLeavesAndHasNoRegions) {
  TerrainDescription none;
  const std::vector<uint8_t> bytes = OccupancyMapBytes(VoxelizeTerrain(none), true);
  const OccupancyMap map = LoadMapBytes(bytes, "empty");
  EXPECT_TRUE(map.leaves.empty());
  const RegionExtractionResult result = ExtractRegions(map, RegionExtractorOptions());
  EXPECT_TRUE(result.regions.empty());
  EXPECT_FALSE(result.message.empty());
}

TEST(OctomapIoTest, ValidHeaderFollowedByJunkIsRejected) {
  std::string s = kBinaryHeader;
  s += std::string(64, '\xff');  // every child an inner node: deeper than 16 levels
  EXPECT_NE(ErrorOf(Bytes(s)).find("depth"), std::string::npos) << ErrorOf(Bytes(s));
  std::string t = kBinaryHeader;
  t += "this is not octree data at all";
  EXPECT_NE(ErrorOf(Bytes(t)), "");
}

TEST(OctomapIoTest, TruncatedFilesAreRejectedAtEveryLength) {
  const std::vector<uint8_t> good = OccupancyMapBytes(VoxelizeTerrain(SteppingStonesTerrain()), true);
  ASSERT_EQ(ErrorOf(good), "");
  // Every cut inside the data, stepping to keep the test fast.
  for (size_t len = 1; len < good.size(); len += 1 + len / 16) {
    const std::vector<uint8_t> cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(len));
    EXPECT_NE(ErrorOf(cut), "") << "length " << len;
  }
  const std::vector<uint8_t> full = OccupancyMapBytes(VoxelizeTerrain(SteppingStonesTerrain()), false);
  ASSERT_EQ(ErrorOf(full), "");
  const std::vector<uint8_t> cut(full.begin(), full.end() - 3);
  EXPECT_NE(ErrorOf(cut).find("ends early"), std::string::npos);
}

TEST(OctomapIoTest, RandomBytesAndRandomDataAfterAHeaderNeverCrash) {
  std::mt19937 rng(42);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> bytes(rng() % 300);
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng());
    if (trial % 2 == 0) {
      const std::string header = "# Octomap OcTree binary file\nid OcTree\nsize " +
                                 std::to_string(rng() % 100) + "\nres 0.05\ndata\n";
      bytes.insert(bytes.begin(), header.begin(), header.end());
    }
    EXPECT_NE(ErrorOf(bytes), "") << "trial " << trial;
  }
}

TEST(OctomapIoTest, CorruptedValidFilesLoadOrFailCleanly) {
  const std::vector<uint8_t> good = OccupancyMapBytes(VoxelizeTerrain(GapTerrain()), true);
  std::mt19937 rng(7);
  int rejected = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> bytes = good;
    for (int k = 0; k < 3; ++k) bytes[rng() % bytes.size()] ^= static_cast<uint8_t>(1 + rng() % 255);
    try {
      const OccupancyMap map = LoadMapBytes(bytes, "corrupted");
      ExtractRegions(map, RegionExtractorOptions());
    } catch (const InputError&) {
      ++rejected;
    }
  }
  EXPECT_GT(rejected, 0);
}

TEST(OctomapIoTest, HugeDeclaredSizesAreRejectedBeforeReading) {
  const std::string s = "# Octomap OcTree binary file\nid OcTree\nsize 4000000000\nres 0.05\ndata\n";
  EXPECT_NE(ErrorOf(Bytes(s)).find("node limit"), std::string::npos) << ErrorOf(Bytes(s));
  // The 8 MB map of the report declared 15.9 M nodes (1.8 GB while OctoMap read it): above
  // the default cap of 4 M, refused from its header.
  const std::string report = "# Octomap OcTree binary file\nid OcTree\nsize 15900000\nres 0.02\ndata\n";
  EXPECT_NE(ErrorOf(Bytes(report)).find("15900000 nodes, more than the 4000000 node limit"), std::string::npos)
      << ErrorOf(Bytes(report));
  const std::string big = "# Octomap OcTree binary file\nid OcTree\nsize 99999999999999999999999\nres 0.05\ndata\n";
  EXPECT_NE(ErrorOf(Bytes(big)), "");
  OctreeStreamLimits small;
  small.max_bytes = 16;
  EXPECT_NE(ErrorOf(Bytes(kBinaryHeader), small).find("byte limit"), std::string::npos);
}

TEST(OctomapIoTest, HeaderProblemsNameTheField) {
  EXPECT_NE(ErrorOf({}).find("empty"), std::string::npos);
  EXPECT_NE(ErrorOf(Bytes("hello\n")).find("first line"), std::string::npos);
  // A full (.ot) colour tree stores colours in its data: refused. Its .bt holds only
  // occupancy, the same encoding as an OcTree's (ColorOcTreeBinaryReadsAsOcTree).
  EXPECT_NE(ErrorOf(Bytes("# Octomap OcTree file\nid ColorOcTree\nsize 1\nres 0.1\ndata\n"))
                .find("ColorOcTree"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Bytes("# Octomap OcTree binary file\nid CountingOcTree\nsize 1\nres 0.1\ndata\n"))
                .find("CountingOcTree"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Bytes("# Octomap OcTree binary file\nid OcTree\nsize 1\nres -3\ndata\n"))
                .find("'res'"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Bytes("# Octomap OcTree binary file\nid OcTree\nsize 1\nres 0.1\n")).find("data"),
            std::string::npos);
}

TEST(OctomapIoTest, CountMismatchTrailingBytesAndNonFiniteValuesAreRejected) {
  // Root with one occupied leaf child: 2 nodes.
  std::string s = "# Octomap OcTree binary file\nid OcTree\nsize 3\nres 0.1\ndata\n";
  s += std::string("\x02\x00", 2);
  EXPECT_NE(ErrorOf(Bytes(s)).find("declares 3"), std::string::npos);
  std::string ok = "# Octomap OcTree binary file\nid OcTree\nsize 2\nres 0.1\ndata\n";
  ok += std::string("\x02\x00", 2);
  // Its leaf is 32768 voxels wide (2^30 column cells): well formed, but over the default
  // leaf-column cap, so read with that cap raised.
  OctreeStreamLimits raised;
  raised.max_leaf_columns = uint64_t{1} << 30;
  EXPECT_EQ(ErrorOf(Bytes(ok), raised), "");
  EXPECT_NE(ErrorOf(Bytes(ok)).find("max_leaf_columns"), std::string::npos);
  EXPECT_NE(ErrorOf(Bytes(ok + "xx")).find("after the tree"), std::string::npos);
  // .ot: a root whose value is NaN.
  std::string ot = "# Octomap OcTree file\nid OcTree\nsize 1\nres 0.1\ndata\n";
  const float nan = NAN;
  char raw[4];
  std::memcpy(raw, &nan, 4);
  ot += std::string(raw, 4) + std::string("\x00", 1);
  EXPECT_NE(ErrorOf(Bytes(ot)).find("finite"), std::string::npos);
}

}  // namespace
}  // namespace mfp

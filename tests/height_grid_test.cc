// Height maps in: the bounded .npy reader, the YAML beside it, and region extraction from
// height grids judged against the true heights the grids were sampled from (steps, gaps,
// unknown patches, noise), never against mfp's own regions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>

#include "base/check.h"
#include "io/height_map_file.h"
#include "io/internal/npy_array.h"
#include "io/map_file.h"
#include "terrain/extraction/height_grid.h"
#include "terrain/quality/height_grid_sampling.h"
#include "terrain/quality/terrain_catalogue.h"
#include "terrain/quality/terrain_quality.h"
#include "tests/input_error_of.h"
#include "tests/test_temp_path.h"

namespace mfp {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

void WriteText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// A .npy file by hand: magic, version 1.0, the header, the data.
std::vector<uint8_t> HandNpy(const std::string& header, const std::vector<uint8_t>& data) {
  std::vector<uint8_t> out = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0};
  out.push_back(static_cast<uint8_t>(header.size() & 0xff));
  out.push_back(static_cast<uint8_t>(header.size() >> 8));
  out.insert(out.end(), header.begin(), header.end());
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

std::string ErrorOf(const std::function<void()>& f) { return InputErrorOf(f); }

TEST(NpyArray, RoundTripKeepsShapeAndValues) {
  NpyArray a;
  a.rows = 2;
  a.cols = 3;
  a.values = {1, 2, 3, 4, kNaN, 6};
  const NpyArray b = ParseNpy(NpyBytes(a), "t", 100);
  EXPECT_EQ(b.rows, 2u);
  EXPECT_EQ(b.cols, 3u);
  EXPECT_EQ(b.values[2], 3.0f);
  EXPECT_TRUE(std::isnan(b.values[4]));
  EXPECT_EQ(b.values[5], 6.0f);
}

TEST(NpyArray, ReadsFloat64InFortranOrder) {
  // [[1, 2], [3, 4]] stored column by column: 1, 3, 2, 4.
  const double values[4] = {1.0, 3.0, 2.0, 4.0};
  std::vector<uint8_t> data(sizeof(values));
  std::memcpy(data.data(), values, sizeof(values));
  const NpyArray a = ParseNpy(HandNpy("{'descr': '<f8', 'fortran_order': True, 'shape': (2, 2), }\n", data), "t", 10);
  EXPECT_EQ(a.values, (std::vector<float>{1, 2, 3, 4}));
}

// Whether `error` says `words` (printed when it does not).
::testing::AssertionResult Says(const std::string& error, const std::string& words) {
  if (error.find(words) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "error \"" << error << "\" does not say \"" << words << "\"";
}

// The error ParseNpy gives for a hand-made file of this header and four floats' bytes.
std::string NpyHeaderError(const std::string& header, size_t max_cells = 10) {
  return ErrorOf([&] { ParseNpy(HandNpy(header, std::vector<uint8_t>(16, 0)), "f", max_cells); });
}

TEST(NpyArray, RejectsBadFilesNamingTheProblem) {
  EXPECT_TRUE(Says(ErrorOf([&] { ParseNpy({1, 2, 3}, "f", 10); }), "not a .npy file"));
  EXPECT_TRUE(Says(NpyHeaderError("{'descr': '<i4', 'fortran_order': False, 'shape': (2, 2), }"), "dtype is '<i4'"));
  EXPECT_TRUE(Says(NpyHeaderError("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 2, 1), }"), "3 dimensions"));
  EXPECT_TRUE(Says(NpyHeaderError("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }"), "needs 24"));
  // A huge shape is refused before anything is allocated.
  EXPECT_TRUE(Says(NpyHeaderError("{'descr': '<f4', 'fortran_order': False, 'shape': (999999999999, 999999999999), }", 1000),
                   "between 1 and 1000 cells"));
  EXPECT_TRUE(Says(NpyHeaderError("{'fortran_order': False, 'shape': (2, 2), }"), "no 'descr'"));
}

TEST(HeightMapFile, NpyWithYamlBesideAndYamlNamingTheArray) {
  const std::string base = TestTempPath("map");
  NpyArray a;
  a.rows = 3;
  a.cols = 2;
  a.values = {0.1f, 0.2f, -9.0f, 0.4f, 0.5f, 0.6f};
  WriteBytes(base + ".npy", NpyBytes(a));
  WriteText(base + ".yaml", "resolution: 0.05\norigin: [1.0, -2.0]\nunknown: -9\n");
  const HeightGrid g = LoadHeightGridFile(base + ".npy");
  EXPECT_EQ(g.nx, 3);
  EXPECT_EQ(g.ny, 2);
  EXPECT_DOUBLE_EQ(g.resolution_m, 0.05);
  EXPECT_DOUBLE_EQ(g.origin_m.y(), -2.0);
  EXPECT_FLOAT_EQ(g.heights_m[g.Index(2, 1)], 0.6f);
  EXPECT_TRUE(std::isnan(g.heights_m[g.Index(1, 0)]));  // the unknown value
  const std::string other = TestTempPath("named.yaml");
  WriteText(other, "heights: " + base + ".npy\nresolution: 0.05\norigin: [0, 0]\n");
  EXPECT_FLOAT_EQ(LoadHeightGridFile(other).heights_m[1], 0.2f);
  EXPECT_TRUE(IsMapFilePath(other));
}

TEST(HeightMapFile, ErrorsNameTheFieldAndTheFix) {
  const std::string base = TestTempPath("bad");
  NpyArray a;
  a.rows = a.cols = 2;
  a.values = {0, 0, 0, 0};
  WriteBytes(base + ".npy", NpyBytes(a));
  EXPECT_NE(ErrorOf([&] { LoadHeightGridFile(base + ".npy"); }).find("needs " + base + ".yaml beside it"), std::string::npos);
  WriteText(base + ".yaml", "origin: [0, 0]\n");
  EXPECT_NE(ErrorOf([&] { LoadHeightGridFile(base + ".npy"); }).find("resolution: missing"), std::string::npos);
  WriteText(base + ".yaml", "resolution: -1\norigin: [0, 0]\n");
  EXPECT_NE(ErrorOf([&] { LoadHeightGridFile(base + ".npy"); }).find("resolution"), std::string::npos);
  WriteText(base + ".yaml", "resolution: 0.02\norigin: [0, 0]\nresolutoin: 3\n");
  EXPECT_NE(ErrorOf([&] { LoadHeightGridFile(base + ".npy"); }).find("resolutoin"), std::string::npos);
  a.values = {0, std::numeric_limits<float>::infinity(), 0, 0};
  WriteBytes(base + ".npy", NpyBytes(a));
  WriteText(base + ".yaml", "resolution: 0.02\norigin: [0, 0]\n");
  EXPECT_NE(ErrorOf([&] { LoadHeightGridFile(base + ".npy"); }).find("cell (0, 1) has height inf"), std::string::npos);
}

// Judges regions against the truth: every sampled region point's foot disk (foot radius
// plus edge margin) lies on a true top surface within half a cell in height.
void ExpectSound(const std::vector<ConvexRegion>& regions, const TerrainDescription& truth,
                 const RegionExtractorOptions& options, double tolerance_m) {
  ASSERT_FALSE(regions.empty());
  const RegionSoundness s =
      MeasureSoundness(regions, truth, options.foot_radius_m + options.edge_margin_m, tolerance_m);
  EXPECT_EQ(s.fraction, 1.0) << "unsound at " << s.worst_point.transpose();
}

// The height of the region covering (x, y), or NaN.
double RegionHeightAt(const std::vector<ConvexRegion>& regions, double x, double y) {
  for (const ConvexRegion& r : regions) {
    const Eigen::Vector3d p(x, y, r.HeightAt(x, y));
    if ((r.A * p - r.b).maxCoeff() <= 1e-9) return p.z();
  }
  return std::nan("");
}

RegionExtractorOptions Options() {
  RegionExtractorOptions o;
  o.foot_radius_m = 0.02;
  o.edge_margin_m = 0.01;
  return o;
}

TEST(HeightGridRegions, StepGivesBothTreadsAtTheirTrueHeights) {
  const TerrainDescription truth = StepTerrain();
  const HeightGrid grid = SampleHeightGrid(truth, 0.02);
  const RegionExtractionResult r = ExtractRegionsFromHeightGrid(grid, Options());
  ExpectSound(r.regions, truth, Options(), 0.01);
  EXPECT_NEAR(RegionHeightAt(r.regions, 0.5, 0.0), TrueTopHeight(truth, 0.5, 0.0), 1e-3);
  EXPECT_NEAR(RegionHeightAt(r.regions, -0.5, 0.0), TrueTopHeight(truth, -0.5, 0.0), 1e-3);
}

TEST(HeightGridRegions, GapIsNeverBridged) {
  const TerrainDescription truth = GapTerrain();
  const RegionExtractionResult r = ExtractRegionsFromHeightGrid(SampleHeightGrid(truth, 0.02), Options());
  ExpectSound(r.regions, truth, Options(), 0.01);
}

TEST(HeightGridRegions, SteppingStonesEachKeepARegionAndNoneReachesTheDrop) {
  const TerrainDescription truth = SteppingStonesTerrain();
  const RegionExtractionResult r = ExtractRegionsFromHeightGrid(SampleHeightGrid(truth, 0.01), Options());
  ExpectSound(r.regions, truth, Options(), 0.005);
  for (const TerrainBox& stone : truth.boxes) {
    const double top = TrueTopHeight(truth, stone.center_world_m.x(), stone.center_world_m.y());
    EXPECT_NEAR(RegionHeightAt(r.regions, stone.center_world_m.x(), stone.center_world_m.y()), top, 1e-3) << stone.name;
  }
}

TEST(HeightGridRegions, UnknownPatchIsNotFloor) {
  const TerrainDescription truth = FlatTerrain();
  HeightGrid grid = SampleHeightGrid(truth, 0.02);
  // Unknown: a 0.2 m square around the origin (the true ground is there, but unseen).
  for (int i = 0; i < grid.nx; ++i) {
    for (int j = 0; j < grid.ny; ++j) {
      const Eigen::Vector2d c = grid.origin_m + 0.02 * Eigen::Vector2d(i, j);
      if (c.cwiseAbs().maxCoeff() <= 0.1) grid.heights_m[grid.Index(i, j)] = kNaN;
    }
  }
  const RegionExtractorOptions o = Options();
  const RegionExtractionResult r = ExtractRegionsFromHeightGrid(grid, o);
  ASSERT_FALSE(r.regions.empty());
  // No foot disk of any region point overlaps the unknown square (its cells reach |c| = 0.11).
  for (const ConvexRegion& region : r.regions) {
    for (double x = -1.0; x <= 1.0; x += 0.005) {
      for (double y = -1.0; y <= 1.0; y += 0.005) {
        const Eigen::Vector3d p(x, y, region.HeightAt(x, y));
        if ((region.A * p - region.b).maxCoeff() > 1e-9) continue;
        EXPECT_GE(p.head<2>().cwiseAbs().maxCoeff(), 0.11 + o.foot_radius_m + o.edge_margin_m - 1e-9)
            << "region " << region.id << " holds " << p.transpose();
      }
    }
  }
  EXPECT_NEAR(RegionHeightAt(r.regions, 0.6, 0.6), 0.0, 1e-3);
}

TEST(HeightGridRegions, NoisyStepsStaySoundAndCovered) {
  const TerrainDescription truth = StepTerrain();
  HeightGrid grid = SampleHeightGrid(truth, 0.02);
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 0.002f);  // 2 mm, a good depth camera's
  for (float& h : grid.heights_m) {
    if (!std::isnan(h)) h += noise(rng);
  }
  const RegionExtractionResult r = ExtractRegionsFromHeightGrid(grid, Options());
  ExpectSound(r.regions, truth, Options(), 0.012);
  EXPECT_NEAR(RegionHeightAt(r.regions, 0.5, 0.0), TrueTopHeight(truth, 0.5, 0.0), 0.006);
  EXPECT_NEAR(RegionHeightAt(r.regions, -0.5, 0.3), TrueTopHeight(truth, -0.5, 0.3), 0.006);
}

TEST(HeightGridRegions, LargeVarianceCellsAreUnknown) {
  const TerrainDescription truth = FlatTerrain();
  HeightGrid grid = SampleHeightGrid(truth, 0.02);
  grid.variances_m2.assign(grid.heights_m.size(), 1e-6f);
  grid.max_variance_m2 = 1e-4;
  for (int i = 0; i < grid.nx; ++i) grid.variances_m2[grid.Index(i, grid.ny / 2)] = 1.0f;  // a row across y = 0
  const RegionExtractionResult r = ExtractRegionsFromHeightGrid(grid, Options());
  ASSERT_FALSE(r.regions.empty());
  const double y_row = grid.origin_m.y() + 0.02 * (grid.ny / 2);
  for (const ConvexRegion& region : r.regions) {
    double lo = 1e9, hi = -1e9;
    for (const Eigen::Vector3d& v : region.vertices_world_m) {
      lo = std::min(lo, v.y());
      hi = std::max(hi, v.y());
    }
    EXPECT_TRUE(hi <= y_row - 0.01 || lo >= y_row + 0.01) << "region " << region.id << " crosses the uncertain row";
  }
}

TEST(HeightGridRegions, BadGridsAreInputErrors) {
  HeightGrid g;
  g.resolution_m = 0.02;
  g.nx = g.ny = 2;
  g.heights_m = {0, 0, 0};
  EXPECT_NE(ErrorOf([&] { ValidateHeightGrid(g); }).find("3 values for 4 cells"), std::string::npos);
  g.heights_m = {0, 0, 0, 0};
  g.resolution_m = 0.0;
  EXPECT_NE(ErrorOf([&] { ValidateHeightGrid(g); }).find("resolution 0 m"), std::string::npos);
  g.resolution_m = 0.02;
  g.variances_m2 = {0, 0, -1, 0};
  EXPECT_NE(ErrorOf([&] { ValidateHeightGrid(g); }).find("cell (1, 0) has variance -1"), std::string::npos);
  HeightGrid all_unknown;
  all_unknown.resolution_m = 0.02;
  all_unknown.nx = all_unknown.ny = 4;
  all_unknown.heights_m.assign(16, kNaN);
  const RegionExtractionResult r = ExtractRegionsFromHeightGrid(all_unknown, Options());
  EXPECT_TRUE(r.regions.empty());
  EXPECT_NE(r.message.find("no known surface cells"), std::string::npos);
}

}  // namespace
}  // namespace mfp

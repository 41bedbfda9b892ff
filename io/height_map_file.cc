#include "io/height_map_file.h"

#include <cmath>
#include <fstream>
#include <limits>

#include "base/check.h"
#include "io/file_paths.h"
#include "io/yaml_fields.h"

namespace mfp {
namespace {

// `unknown:` is a number or nan (.nan, NaN); NaN cells are unknown in any case.
double ReadUnknownValue(const YAML::Node& yaml, const YamlContext& ctx) {
  if (!yaml["unknown"]) return std::numeric_limits<double>::quiet_NaN();
  const YAML::Node node = yaml["unknown"];
  if (node.IsScalar()) {
    const std::string text = node.Scalar();
    if (text == "nan" || text == "NaN" || text == ".nan" || text == ".NaN" || text == ".NAN") {
      return std::numeric_limits<double>::quiet_NaN();
    }
  }
  return ReadDouble(node, ctx.Child("unknown"), -1e30, 1e30);
}

HeightGrid LoadUnguarded(const std::string& path, size_t max_cells) {
  const std::string ext = FileExtension(path);
  std::string yaml_path = path, npy_path;
  if (ext == "npy") {
    yaml_path = WithoutFileExtension(path) + ".yaml";
    if (!std::ifstream(yaml_path)) {
      throw InputError(path + ": a .npy height map needs " + yaml_path +
                       " beside it (resolution: CELL_M, origin: [X, Y]; see the README)");
    }
    npy_path = path;
  }
  const YAML::Node yaml = LoadYamlFile(yaml_path);
  const YamlContext ctx{yaml_path, ""};
  if (!yaml.IsMap()) throw InputError(yaml_path + ": expected a height map description (a mapping)");
  RejectUnknownKeys(yaml, ctx, {"heights", "resolution", "origin", "unknown", "variance", "max_variance", "frame"});
  if (npy_path.empty()) {
    if (!yaml["heights"]) {
      throw InputError(ctx.Child("heights").Where() + ": missing: name the .npy array of heights");
    }
    npy_path = ResolveRelative(yaml_path, ReadString(yaml["heights"], ctx.Child("heights")));
  }
  if (!yaml["resolution"]) throw InputError(ctx.Child("resolution").Where() + ": missing: the cell edge [m]");
  if (!yaml["origin"]) throw InputError(ctx.Child("origin").Where() + ": missing: [x, y] of the centre of cell (0, 0) [m]");
  const double resolution = ReadDouble(yaml["resolution"], ctx.Child("resolution"), 1e-4, 10.0);
  const std::vector<double> origin = ReadNumbers(yaml["origin"], ctx.Child("origin"), 2);
  HeightGrid grid = HeightGridFromArray(ReadNpyFile(npy_path, max_cells), resolution, origin[0], origin[1],
                                        ReadUnknownValue(yaml, ctx), max_cells);
  if (yaml["variance"]) {
    const std::string var_path = ResolveRelative(yaml_path, ReadString(yaml["variance"], ctx.Child("variance")));
    NpyArray var = ReadNpyFile(var_path, max_cells);
    if (var.rows != static_cast<size_t>(grid.nx) || var.cols != static_cast<size_t>(grid.ny)) {
      throw InputError(ctx.Child("variance").Where() + ": the variance array is " + std::to_string(var.rows) +
                       " x " + std::to_string(var.cols) + ", the heights " + std::to_string(grid.nx) + " x " +
                       std::to_string(grid.ny) + ": give one variance per cell");
    }
    grid.variances_m2 = std::move(var.values);
    grid.max_variance_m2 = OptionalDouble(yaml, ctx, "max_variance", 0.0, 1e6)
                               .value_or(0.25 * resolution * resolution);
  } else if (yaml["max_variance"]) {
    throw InputError(ctx.Child("max_variance").Where() + ": given without a variance array");
  }
  try {
    ValidateHeightGrid(grid, max_cells);
  } catch (const InputError& e) {
    throw InputError(npy_path + ": " + e.what());
  }
  return grid;
}

}  // namespace

bool IsHeightMapPath(const std::string& path) {
  const std::string ext = FileExtension(path);
  return ext == "npy" || ext == "yaml" || ext == "yml";
}

HeightGrid HeightGridFromArray(const NpyArray& heights, double resolution_m, double origin_x_m,
                               double origin_y_m, double unknown_value, size_t max_cells) {
  if (heights.rows > static_cast<size_t>(std::numeric_limits<int>::max()) ||
      heights.cols > static_cast<size_t>(std::numeric_limits<int>::max())) {
    throw InputError("height map of " + std::to_string(heights.rows) + " x " + std::to_string(heights.cols) +
                     " cells is too large");
  }
  HeightGrid grid;
  grid.resolution_m = resolution_m;
  grid.origin_m = Eigen::Vector2d(origin_x_m, origin_y_m);
  grid.nx = static_cast<int>(heights.rows);
  grid.ny = static_cast<int>(heights.cols);
  grid.heights_m = heights.values;
  if (std::isfinite(unknown_value)) {
    const float unknown = static_cast<float>(unknown_value);
    for (float& h : grid.heights_m) {
      if (h == unknown) h = std::numeric_limits<float>::quiet_NaN();
    }
  }
  ValidateHeightGrid(grid, max_cells);
  return grid;
}

HeightGrid LoadHeightGridFile(const std::string& path, size_t max_cells) {
  return GuardYaml(path, [&] { return LoadUnguarded(path, max_cells); });
}

}  // namespace mfp

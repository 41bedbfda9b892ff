#include "terrain/terrain_catalogue.h"

#include <cmath>

namespace mfp {
namespace {

TerrainBox Box(const std::string& name, Eigen::Vector3d center, Eigen::Vector3d size,
               Eigen::Vector3d rpy = Eigen::Vector3d::Zero()) {
  TerrainBox box;
  box.name = name;
  box.center_world_m = center;
  box.size_m = size;
  box.rpy_rad = rpy;
  return box;
}

double Deg(double deg) { return deg * M_PI / 180.0; }

}  // namespace

TerrainDescription FlatTerrain() {
  TerrainDescription t;
  t.boxes = {Box("ground", {0, 0, -0.05}, {2, 2, 0.1})};
  return t;
}

TerrainDescription StepTerrain() {
  TerrainDescription t;
  t.boxes = {Box("ground", {0, 0, -0.05}, {2, 2, 0.1}), Box("step", {0.5, 0, 0.0}, {1, 2, 0.2})};
  return t;
}

TerrainDescription SteppingStonesTerrain() {
  TerrainDescription t;
  const double heights[3] = {0.0, 0.04, 0.08};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double top = heights[(i + j) % 3];
      t.boxes.push_back(Box("stone" + std::to_string(i) + std::to_string(j),
                            {0.3 * i, 0.3 * j, top - 0.1}, {0.2, 0.2, 0.2}));
    }
  }
  return t;
}

TerrainDescription TiltTerrain(double pitch_rad, double yaw_rad) {
  TerrainDescription t;
  t.boxes = {Box("tilted", {0, 0, 0}, {1.2, 1.2, 0.1}, {0, pitch_rad, yaw_rad})};
  return t;
}

TerrainDescription GapTerrain() {
  TerrainDescription t;
  t.boxes = {Box("left", {-0.6, 0, -0.05}, {1, 1, 0.1}), Box("right", {0.6, 0, -0.05}, {1, 1, 0.1})};
  return t;
}

TerrainDescription WallTerrain() {
  TerrainDescription t;
  t.boxes = {Box("ground", {0, 0, -0.05}, {2, 2, 0.1}), Box("wall", {0, 0, 0.2}, {0.04, 2, 0.6})};
  return t;
}

TerrainDescription CourseTerrain4m() {
  TerrainDescription t;
  // Ground in two halves with a 0.2 m gap along x = 0.
  t.boxes.push_back(Box("ground_w", {-1.05, 0, -0.05}, {1.9, 4, 0.1}));
  t.boxes.push_back(Box("ground_e", {1.05, 0, -0.05}, {1.9, 4, 0.1}));
  // West half: a step, stepping stones, a wall.
  t.boxes.push_back(Box("step", {-1.5, 1.4, 0.0}, {0.8, 1.0, 0.2}));
  for (int i = 0; i < 4; ++i) {
    t.boxes.push_back(Box("stone" + std::to_string(i), {-1.6 + 0.3 * i, -0.2, 0.0},
                          {0.2, 0.2, 0.04 * (i % 3) + 0.1}));
  }
  t.boxes.push_back(Box("wall", {-0.6, -1.2, 0.25}, {0.04, 1.2, 0.5}));
  // East half: a 3 degree and a yawed 15 degree tilt, and a 40 degree ramp.
  t.boxes.push_back(Box("tilt3", {1.0, 1.2, 0.05}, {1.0, 1.0, 0.1}, {0, Deg(3), 0}));
  t.boxes.push_back(Box("tilt15", {1.1, -0.1, 0.1}, {0.8, 0.8, 0.1}, {0, Deg(15), Deg(30)}));
  t.boxes.push_back(Box("ramp40", {1.2, -1.4, 0.1}, {0.6, 0.6, 0.1}, {0, Deg(40), 0}));
  return t;
}

std::vector<NamedTerrain> TerrainCatalogue() {
  return {{"flat", FlatTerrain()},
          {"step", StepTerrain()},
          {"stepping_stones", SteppingStonesTerrain()},
          {"tilt_3deg", TiltTerrain(Deg(3), 0.0)},
          {"tilt_15deg_yaw30", TiltTerrain(Deg(15), Deg(30))},
          {"slope_40deg", TiltTerrain(Deg(40), 0.0)},
          {"gap", GapTerrain()},
          {"wall", WallTerrain()},
          {"course_4m", CourseTerrain4m()}};
}

}  // namespace mfp

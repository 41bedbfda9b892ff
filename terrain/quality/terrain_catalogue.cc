#include "terrain/quality/terrain_catalogue.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace mfp {
namespace {

TerrainBox Box(const std::string& name, Eigen::Vector3d center, Eigen::Vector3d size,
               Eigen::Vector3d rpy = Eigen::Vector3d::Zero()) {
  return TerrainBox{name, center, size, rpy};
}

double Deg(double deg) { return deg * M_PI / 180.0; }

TerrainDescription WithBoxes(std::vector<TerrainBox> boxes) {
  TerrainDescription t;
  t.boxes = std::move(boxes);
  return t;
}

}  // namespace

TerrainDescription FlatTerrain() { return WithBoxes({Box("ground", {0, 0, -0.05}, {2, 2, 0.1})}); }

TerrainDescription StepTerrain() {
  return WithBoxes({Box("ground", {0, 0, -0.05}, {2, 2, 0.1}), Box("step", {0.5, 0, 0.0}, {1, 2, 0.2})});
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
  return WithBoxes({Box("tilted", {0, 0, 0}, {1.2, 1.2, 0.1}, {0, pitch_rad, yaw_rad})});
}

TerrainDescription GapTerrain() {
  return WithBoxes({Box("left", {-0.6, 0, -0.05}, {1, 1, 0.1}), Box("right", {0.6, 0, -0.05}, {1, 1, 0.1})});
}

TerrainDescription WallTerrain() {
  return WithBoxes({Box("ground", {0, 0, -0.05}, {2, 2, 0.1}), Box("wall", {0, 0, 0.2}, {0.04, 2, 0.6})});
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

TerrainDescription BridgeTerrain() {
  return WithBoxes({Box("ground", {0, 0, -0.05}, {2, 2, 0.1}), Box("bridge", {0, 0, 0.55}, {0.6, 2, 0.1}),
                    Box("pier_s", {0, -0.9, 0.25}, {0.6, 0.2, 0.5}), Box("pier_n", {0, 0.9, 0.25}, {0.6, 0.2, 0.5})});
}

TerrainDescription TableTerrain() {
  TerrainDescription t =
      WithBoxes({Box("floor", {0, 0, -0.05}, {2, 2, 0.1}), Box("table", {0, 0, 0.68}, {1.0, 0.6, 0.04})});
  for (int i = 0; i < 4; ++i) {
    const double x = (i & 1) ? 0.46 : -0.46, y = (i & 2) ? 0.26 : -0.26;
    t.boxes.push_back(Box("leg" + std::to_string(i), {x, y, 0.33}, {0.04, 0.04, 0.66}));
  }
  return t;
}

TerrainDescription OverhangTerrain() {
  return WithBoxes({Box("ground", {0, 0, -0.05}, {2, 2, 0.1}), Box("tread1", {0.2, 0, 0.05}, {0.4, 2, 0.1}),
                    Box("tread2", {0.6, 0, 0.1}, {0.4, 2, 0.2}), Box("overhang", {0.3, 0, 0.7}, {1.0, 2, 0.1})});
}

TerrainDescription CorridorTerrain(double length_m, double resolution_m, const MapNoise& noise) {
  TerrainDescription t;
  t.resolution_m = resolution_m;
  const double width = 1.6, height = 2.8, wall = 0.16, slab = 0.16;
  const double cx = 0.5 * length_m;
  t.boxes.push_back(Box("floor", {cx, 0, -0.5 * slab}, {length_m + 2 * wall, width + 2 * wall, slab}));
  t.boxes.push_back(Box("ceiling", {cx, 0, height + 0.5 * slab}, {length_m + 2 * wall, width + 2 * wall, slab}));
  t.boxes.push_back(Box("end_w", {-0.5 * wall, 0, 0.5 * height}, {wall, width, height}));
  t.boxes.push_back(Box("end_e", {length_m + 0.5 * wall, 0, 0.5 * height}, {wall, width, height}));
  // Side walls with a 0.96 m wide, 2.08 m high door every 2.4 m (alternating sides).
  for (int side = -1; side <= 1; side += 2) {
    const double y = side * (0.5 * width + 0.5 * wall);
    double x = 0.0;
    int k = 0;
    for (double door = side < 0 ? 1.2 : 2.4; x < length_m; door += 2.4, ++k) {
      const double d0 = std::min(door, length_m), d1 = std::min(door + 0.96, length_m);
      const std::string name = std::string(side < 0 ? "wall_s" : "wall_n") + std::to_string(k);
      if (d0 > x) t.boxes.push_back(Box(name, {0.5 * (x + d0), y, 0.5 * height}, {d0 - x, wall, height}));
      if (d1 > d0) {
        t.boxes.push_back(Box(name + "_lintel", {0.5 * (d0 + d1), y, 0.5 * (2.08 + height)},
                              {d1 - d0, wall, height - 2.08}));
      }
      x = d1;
    }
  }
  for (double x = 0.75; x < length_m; x += 1.5) t.scan.sensors_world_m.push_back({x, 0.0, 1.0});
  t.scan.max_range_m = 6.0;
  t.noise = noise;
  return t;
}

TerrainDescription BuildingFloorTerrain() {
  TerrainDescription t;
  t.resolution_m = 0.08;
  const double h = 2.4, w = 0.16;
  t.boxes.push_back(Box("floor", {20, 7.5, -0.08}, {40, 15, 0.16}));
  // Outer walls, and a wall every 5 m along x with a 0.96 m door, and a corridor wall at
  // y = 5 with a door into each room.
  t.boxes.push_back(Box("wall_s", {20, 0.08, 0.5 * h}, {40, w, h}));
  t.boxes.push_back(Box("wall_n", {20, 14.92, 0.5 * h}, {40, w, h}));
  for (int i = 0; i <= 8; ++i) {
    const double x = std::min(39.92, std::max(0.08, 5.0 * i));
    if (i == 0 || i == 8) {
      t.boxes.push_back(Box("wall_x" + std::to_string(i), {x, 7.5, 0.5 * h}, {w, 15, h}));
      continue;
    }
    t.boxes.push_back(Box("wall_x" + std::to_string(i), {x, 10.48, 0.5 * h}, {w, 8.96, h}));
  }
  for (int i = 0; i < 8; ++i) {
    const double x0 = 5.0 * i, door = x0 + 2.0;
    t.boxes.push_back(Box("corr_a" + std::to_string(i), {0.5 * (x0 + door), 6.0, 0.5 * h}, {door - x0, w, h}));
    t.boxes.push_back(Box("corr_b" + std::to_string(i), {0.5 * (door + 0.96 + x0 + 5.0), 6.0, 0.5 * h},
                          {x0 + 5.0 - door - 0.96, w, h}));
    t.boxes.push_back(Box("table" + std::to_string(i), {x0 + 2.5, 10.5, 0.72}, {1.6, 0.8, 0.08}));
  }
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
          {"course_4m", CourseTerrain4m()},
          {"bridge", BridgeTerrain()},
          {"table", TableTerrain()},
          {"overhang", OverhangTerrain()}};
}

}  // namespace mfp

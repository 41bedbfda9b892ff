#include "bench/course_digest.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "io/robot_loader.h"

namespace mfp {
namespace {

class Fnv1a {
 public:
  explicit Fnv1a(double quantum_m) : quantum_m_(quantum_m) {}
  void Bytes(const void* data, size_t size) {
    const unsigned char* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash_ = (hash_ ^ bytes[i]) * 1099511628211ull;
  }
  void Text(const std::string& s) { Bytes(s.data(), s.size() + 1); }
  void Int(int64_t v) { Bytes(&v, sizeof(v)); }
  void Real(double v) {
    if (quantum_m_ > 0.0) {
      Int(std::llround(v / quantum_m_));
    } else {
      Bytes(&v, sizeof(v));
    }
  }
  void Vector(const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) Real(v[i]);
  }
  void Pose(const Pose2D& p) {
    Real(p.x_m);
    Real(p.y_m);
    Real(p.yaw_rad);
  }
  uint64_t hash() const { return hash_; }

 private:
  double quantum_m_;
  uint64_t hash_ = 1469598103934665603ull;
};

}  // namespace

uint64_t CourseHash(const Course& course, double quantum_m) {
  Fnv1a h(quantum_m);
  h.Text(course.name);
  h.Int(course.route_exists ? 1 : 0);
  h.Real(course.edge_margin_m);
  h.Real(course.terrain.resolution_m);
  h.Int(static_cast<int64_t>(course.terrain.boxes.size()));
  for (const TerrainBox& box : course.terrain.boxes) {
    h.Text(box.name);
    h.Vector(box.center_world_m);
    h.Vector(box.size_m);
    h.Vector(box.rpy_rad);
  }
  h.Pose(course.start);
  h.Pose(course.goal);
  h.Int(static_cast<int64_t>(course.route.size()));
  for (const Pose2D& pose : course.route) h.Pose(pose);
  return h.hash();
}

void PrintCourseDigests(const CourseBenchOptions& options) {
  const CourseRotation rotation = MakeCourseRotation(options);
  std::printf("%-5s %-32s %-5s %5s %8s %16s %16s\n", "index", "course", "route", "boxes", "res_m", "hash_bits",
              "hash_nm");
  for (int i = options.first; i < options.courses; ++i) {
    Course course;
    try {
      course = rotation.Generate(i, options.seed);
    } catch (const std::runtime_error& e) {
      std::printf("%-5d generator gave up: %s\n", i, e.what());
      continue;
    }
    if (!options.only.empty() && course.name.find(options.only) == std::string::npos) continue;
    std::printf("%-5d %-32s %-5s %5zu %8.5f %016llx %016llx\n", i, course.name.c_str(),
                course.route_exists ? "yes" : "cut", course.terrain.boxes.size(), course.terrain.resolution_m,
                static_cast<unsigned long long>(CourseHash(course, 0.0)),
                static_cast<unsigned long long>(CourseHash(course, 1e-9)));
  }
}

}  // namespace mfp

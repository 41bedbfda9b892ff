// Generated courses (bench/course_generator.h) are those of their seeds: the first 48 of
// mfp-bench --courses (every kind for LittleDog, the hexapod and the octopod) keep the
// digests pinned here. A change meant to keep the courses (a refactor of the generator)
// keeps them; a change meant to alter courses updates the pins and says so (the 200-course
// check: mfp-bench --courses 200 --course-digest before and after).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <stdexcept>
#include <string>

#include "bench/course_bench.h"
#include "bench/course_digest.h"

namespace mfp {
namespace {

constexpr double kNanometre_m = 1e-9;

CourseRotation DefaultRotation() {
  CourseBenchOptions options;
  options.robots_dir = std::string(MFP_SOURCE_DIR) + "/config/robots";
  return MakeCourseRotation(options);
}

std::string Hex(uint64_t v) {
  char text[24];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
  return text;
}

// CourseHash(course, 1 nm) of courses 0..47 of the default rotation, seed 1 (course i: seed
// 1 + i); 0: the generator gives up (course 41, the octopod's doorway: its body is too near
// square for a door that needs a turn). The octopod's courses follow its d_lim: its robot
// YAML (derived from a URDF) states no reach shape, and both defaults it has had (the 16-gon
// from stop 36, the footprint from stop 38) keep the 16-gon's d_lim.
constexpr uint64_t kPinned[48] = {
    0xa62416f4e72f8ac8ull, 0x9725142a1aa0f5e1ull, 0xa019a1dd3b453495ull, 0x6a3927b498944f60ull,
    0x8146a394d94c563aull, 0x64937d433f096798ull, 0x8e625699da0c1b87ull, 0x593b88db7e3f92e0ull,
    0x1f827087f372f807ull, 0x29e48c2969be53a8ull, 0x250fc91283a6a21full, 0xf48587a0a6aaef87ull,
    0x3ed6e5440d5d453bull, 0x90da46b1c4f1246bull, 0x617ab74cbcb07ad5ull, 0xe08c4b9c35be2069ull,
    0xeac1fbfbb6313f1dull, 0x62d27b23a8ec52e3ull, 0xd3b168ab29298dc0ull, 0x17ff9c833945fb9cull,
    0xf718ede65271ff79ull, 0xc97dbb00a7045476ull, 0x066b112790127ad8ull, 0x650134d91d3b1770ull,
    0xca7f28b3793d5933ull, 0x6e212174d0425576ull, 0x7033249d072476abull, 0x705253e6d4643e14ull,
    0xd1748409ec19987full, 0x03f3fbcf676014e9ull, 0x7263028faf34907eull, 0xe3709d272854d7b1ull,
    0x888e715f341a72acull, 0x286116b2bc5eda9cull, 0xf2d5ded10061d2cbull, 0x59095a0a917e6095ull,
    0x836fe5abed68f4a0ull, 0x1cfbaf2657efc785ull, 0x6b59ae23c62eae89ull, 0x9b25fa1c5c3c35b7ull,
    0x25b34799528cd74eull, 0, 0xe9ec85e15ca196d0ull, 0x2455f1dae181cfe8ull,
    0xb42149135047bfc4ull, 0xf7e106af994ec077ull, 0xb2319c2857ff8383ull, 0x107b35efd8cd5fedull,
};

TEST(CourseDigestTest, TheFirstCoursesOfTheBenchsRotationKeepTheirDigests) {
  const CourseRotation rotation = DefaultRotation();
  ASSERT_EQ(rotation.robots.size() * rotation.kinds.size(), std::size(kPinned));
  for (int i = 0; i < static_cast<int>(std::size(kPinned)); ++i) {
    if (kPinned[i] == 0) {
      EXPECT_THROW(rotation.Generate(i, 1), std::runtime_error) << "course " << i;
      continue;
    }
    const Course course = rotation.Generate(i, 1);
    EXPECT_EQ(Hex(CourseHash(course, kNanometre_m)), Hex(kPinned[i])) << "course " << i << ": " << course.name;
  }
}

TEST(CourseDigestTest, AMovedBoxChangesTheDigestAndALastBitDoesNot) {
  const Course course = DefaultRotation().Generate(0, 1);
  ASSERT_FALSE(course.terrain.boxes.empty());
  Course moved = course;
  moved.terrain.boxes.back().center_world_m.x() += 1e-6;
  EXPECT_NE(CourseHash(moved, kNanometre_m), CourseHash(course, kNanometre_m));
  EXPECT_NE(CourseHash(moved, 0.0), CourseHash(course, 0.0));
  Course nudged = course;
  double& x = nudged.terrain.boxes.back().center_world_m.x();
  x = std::nextafter(x, x + 1.0);
  EXPECT_NE(CourseHash(nudged, 0.0), CourseHash(course, 0.0));
  EXPECT_EQ(CourseHash(nudged, kNanometre_m), CourseHash(course, kNanometre_m));
  Course other_route = course;
  other_route.route_exists = !course.route_exists;
  EXPECT_NE(CourseHash(other_route, kNanometre_m), CourseHash(course, kNanometre_m));
}

}  // namespace
}  // namespace mfp

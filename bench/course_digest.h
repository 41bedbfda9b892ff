#pragma once
// mfp-bench --courses N --course-digest: one line per generated course (the bench's
// rotation of robots, kinds and seeds) with a hash of what the generator made, and no
// planning. Two builds printing the same digests generate the same courses (the check for
// a change meant to keep them).
#include <cstdint>

#include "bench/course_bench.h"
#include "bench/course_generator.h"

namespace mfp {

// FNV-1a over a course's name, route flag, edge margin, map resolution, boxes (names,
// centres, sizes, rpy), start, goal and route. quantum_m > 0: every real number rounded to
// a multiple of quantum_m first (a test's pin that survives a libm's last bit; any change of
// the generator's draws moves boxes by far more); 0: the numbers' exact bits.
uint64_t CourseHash(const Course& course, double quantum_m);

// The courses RunCourseBench would plan (options.first to options.courses, options.only),
// one line each: name, route, boxes, resolution, the exact-bit hash and the nanometre hash.
void PrintCourseDigests(const CourseBenchOptions& options);

}  // namespace mfp

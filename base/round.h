#pragma once
// Rounding to the nearest integer, halves away from zero, without a library call, for
// the map readers' inner loops (a few coordinates per octree leaf, millions of leaves per
// scan; docs/measurements.md, extraction time round 3). Std and nothing else.
#include <cmath>

namespace mfp {

// Equal to std::llround(x) for every double (finite values below 2^52 in magnitude take
// the fast path; the rest, NaN included, are left to std::llround).
inline long long RoundToLongLong(double x) {
  if (!(std::abs(x) < 4503599627370496.0)) return std::llround(x);  // 2^52: already an integer
  long long t = static_cast<long long>(x);     // towards zero
  const double frac = x - static_cast<double>(t);  // exact below 2^52
  if (frac >= 0.5) ++t;
  if (frac <= -0.5) --t;
  return t;
}

// Equal to std::round(x) in value for every finite double (a zero may lose its sign);
// non-finite values are returned as std::round returns them.
inline double RoundToDouble(double x) {
  if (!(std::abs(x) < 4503599627370496.0)) return std::round(x);
  return static_cast<double>(RoundToLongLong(x));
}

}  // namespace mfp

#pragma once
// The binary arithmetic of a linear expression type, written once: a type T that defines
// T& operator+=(const T&), T& operator-=(const T&) and T& operator*=(double) derives from
// ExpressionArithmetic<T> and gets a + b, a - b and scale * a (found by argument-dependent
// lookup, as hidden friends).

namespace mfp {

template <class T>
struct ExpressionArithmetic {
  friend T operator+(T a, const T& b) { return a += b; }
  friend T operator-(T a, const T& b) { return a -= b; }
  friend T operator*(double scale, T a) { return a *= scale; }
};

}  // namespace mfp

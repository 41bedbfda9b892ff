#pragma once
// Numbers in messages and provenance lines: one formatting for every library and tool.
#include <string>

namespace mfp {

// Fixed-point with the given number of decimals ("0.0700").
std::string Fixed(double value, int decimals = 4);

// Shortest natural form, as an ostream prints it ("0.07", "1e-06", "nan").
std::string Number(double value);

}  // namespace mfp

#pragma once
// Numbers and names in messages and provenance lines: one formatting for every library
// and tool.
#include <string>

namespace mfp {

// Fixed-point with the given number of decimals ("0.0700").
std::string Fixed(double value, int decimals = 4);

// Shortest natural form, as an ostream prints it ("0.07", "1e-06", "nan").
std::string Number(double value);

// `text` (a robot name, a frame, a message quoting one) with every control byte written
// as an escape - "\n", "\r", "\t", "\0", else "\xNN" - so a name can neither end a
// log line early nor forge one, and an LCM string (which ends at its first NUL) carries
// it whole. Every other byte (printable ASCII, UTF-8) stays as it is.
std::string EscapedText(const std::string& text);

}  // namespace mfp

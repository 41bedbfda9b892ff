#pragma once
// Writing a tool's text output (JSON, SVG) to a file, or to stdout for "-".
#include <string>

namespace mfp {

// Throws InputError naming the path when it cannot be written.
void WriteTextOutput(const std::string& path, const std::string& text);

}  // namespace mfp

#include "io/text_output.h"

#include <fstream>
#include <iostream>

#include "base/check.h"

namespace mfp {

void WriteTextOutput(const std::string& path, const std::string& text) {
  if (path == "-") {
    std::cout << text;
    return;
  }
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot open for writing");
  out << text;
  out.flush();
  if (!out) throw InputError(path + ": write failed");
}

}  // namespace mfp

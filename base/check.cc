#include "base/check.h"

#include <cstdio>
#include <cstdlib>

namespace mfp {

void AbortOnFailedCheck(const char* condition, const char* file, int line,
                        const std::string& detail) {
  // The one place library code writes to stderr: the process is about to abort and
  // the check's location is the only useful thing left to say.
  std::fprintf(stderr, "mfp: internal check failed: %s at %s:%d%s%s\n", condition, file, line,
               detail.empty() ? "" : ": ", detail.c_str());
  std::abort();
}

}  // namespace mfp

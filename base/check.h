#pragma once
// Three tiers of checks, as in the design:
//  - MFP_CHECK: programmer errors. Always on; aborts with file and line.
//  - InputError: bad input at a boundary (file, flag, message, config). Thrown with a
//    message that names the field and the allowed range; the CLI exits 2 on it and the
//    daemon replies with a status.
//  - TimeLimitError: a loading step that is not a solver (deriving a robot from its URDF)
//    ran out of the request's time. The CLI exits 3 on it (as on a plan's time limit), the
//    daemon logs it and keeps its previous configuration.
//  - Solver outcomes are SolveStatus values (solve_status.h), never exceptions.
#include <stdexcept>
#include <string>

namespace mfp {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

class TimeLimitError : public std::runtime_error {
 public:
  explicit TimeLimitError(const std::string& what) : std::runtime_error(what) {}
};

[[noreturn]] void AbortOnFailedCheck(const char* condition, const char* file, int line,
                                     const std::string& detail);

}  // namespace mfp

#define MFP_CHECK(condition)                                               \
  do {                                                                     \
    if (!(condition)) ::mfp::AbortOnFailedCheck(#condition, __FILE__, __LINE__, ""); \
  } while (false)

#define MFP_CHECK_MSG(condition, detail)                                   \
  do {                                                                     \
    if (!(condition)) ::mfp::AbortOnFailedCheck(#condition, __FILE__, __LINE__, (detail)); \
  } while (false)

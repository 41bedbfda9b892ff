// The message of the InputError a call throws: for tests that check that bad input is
// refused with a message naming the problem.
#pragma once

#include <string>

#include "base/check.h"

namespace mfp {

// What `call` throws as InputError, or `accepted` when it throws none.
template <class Call>
std::string InputErrorOf(const Call& call, const std::string& accepted = "") {
  try {
    call();
  } catch (const InputError& e) {
    return e.what();
  }
  return accepted;
}

}  // namespace mfp

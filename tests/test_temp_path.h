// Scratch files for tests. ctest runs every test case as its own process and
// several at once, so a fixed name in the temp folder is a race between cases:
// the path carries the process id and the running test's name.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace mfp {

inline std::string TestTempPath(const std::string& name) {
  const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
  std::string test = info != nullptr ? std::string(info->test_suite_name()) + "." + info->name() : "no_test";
  for (char& c : test) {
    if (c == '/') c = '_';  // parameterised names contain '/'
  }
  return (std::filesystem::temp_directory_path() /
          ("mfp_" + std::to_string(::getpid()) + "_" + test + "_" + name))
      .string();
}

}  // namespace mfp

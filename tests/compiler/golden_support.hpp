#pragma once
// Golden files (tests/golden/): compare a phase's output with its file, or rewrite the file when
// SANDPAPER_UPDATE_GOLDEN is set (the update-golden target).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace sandpaper::test {

inline std::string read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void check_golden(const std::filesystem::path& golden, const std::string& actual) {
  if (std::getenv("SANDPAPER_UPDATE_GOLDEN")) {
    std::filesystem::create_directories(golden.parent_path());
    std::ofstream(golden, std::ios::binary) << actual;
    return;
  }
  ASSERT_TRUE(std::filesystem::exists(golden)) << golden << " is missing: build the update-golden target";
  EXPECT_EQ(read_bytes(golden), actual) << "differs from " << golden;
}

}  // namespace sandpaper::test

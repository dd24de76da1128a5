#pragma once
// Workspaces built in code for the runtime tests: patches of constant force, springs and dampers.
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sandpaper/schema/workspace_program.hpp"

namespace sandpaper::testws {

// A patch whose force is the constant `force_N` along x everywhere on it: a grating whose table
// holds the same value at both samples, so the interpolated force is that value whatever the phase.
inline schema::PatchProgram constant_force_program(double force_N) {
  schema::PatchProgram p;
  p.name = "constant";
  p.device = "sim";
  schema::GratingTerm g;
  g.period_m = 0.01;
  g.force_N = {static_cast<float>(force_N), static_cast<float>(force_N)};
  p.terms.push_back(g);
  return p;
}

inline schema::PlacedPatch placed(schema::PatchProgram program, double cx_m, double cy_m, double w_m, double h_m,
                                  std::string source = "test") {
  const double centre[2] = {cx_m, cy_m};
  const double size[2] = {w_m, h_m};
  return schema::place_patch(std::move(program), centre, size, std::move(source));
}

// A uniform double in [0, 1) from 53 bits of a 64-bit generator: the same on every standard library.
template <class Rng>
double unit(Rng& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Compares `actual` with the golden file, or rewrites it when SANDPAPER_UPDATE_GOLDEN is set.
inline void check_golden(const std::string& golden, const std::string& actual) {
  if (std::getenv("SANDPAPER_UPDATE_GOLDEN")) {
    std::ofstream(golden, std::ios::binary) << actual;
    return;
  }
  std::ifstream probe(golden);
  ASSERT_TRUE(probe.good()) << golden << " is missing: build the update-golden target";
  EXPECT_EQ(read_file(golden), actual) << "differs from " << golden;
}

}  // namespace sandpaper::testws

#include "test_support.hpp"

#include <cmath>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

namespace sandpaper::test {

const compiler::Compiler& shipped_compiler() {
  static const compiler::Compiler c([] {
    compiler::CompileOptions o;
    o.library_dir = std::string(SANDPAPER_SOURCE_DIR) + "/library";
    o.calibration_dir = std::string(SANDPAPER_SOURCE_DIR) + "/calibration";
    return o;
  }());
  return c;
}

std::vector<std::string> codes(const compiler::CompileResult& r, compiler::Severity severity) {
  std::vector<std::string> out;
  for (const auto& d : r.diagnostics.all())
    if (d.severity == severity) out.push_back(d.code);
  return out;
}

const schema::Provenance& provenance(const schema::PatchProgram& p, const std::string& parameter) {
  for (const auto& pv : p.provenance)
    if (pv.parameter == parameter) return pv;
  ADD_FAILURE() << "no provenance for " << parameter;
  static schema::Provenance none;
  return none;
}

std::string temp_dir(const std::string& tag) {
  std::random_device rd;
  auto p = std::filesystem::temp_directory_path() / ("sandpaper-" + tag + "-" + std::to_string(rd()));
  std::filesystem::create_directories(p);
  return p.string();
}

double expected_force_for_roughness(double r) { return 382 * 9.80665e-3 * std::pow(r, 1 / 0.759593); }

}  // namespace sandpaper::test

namespace {
// Paths in diagnostics and goldens are relative to the source tree, wherever the binary is run.
const bool kInSourceTree = [] {
  std::filesystem::current_path(SANDPAPER_SOURCE_DIR);
  return true;
}();
}  // namespace

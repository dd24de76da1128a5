#include "test_support.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
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

void write_text(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

void replace_in(const std::filesystem::path& file, const std::string& from, const std::string& to) {
  std::ifstream in(file, std::ios::binary);
  std::string text(std::istreambuf_iterator<char>(in), {});
  in.close();
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from << " not in " << file;
  text.replace(at, from.size(), to);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
}

double expected_force_for_roughness(double r) { return 382 * 9.80665e-3 * std::pow(r, 1 / 0.759593); }

std::vector<double> bar_gradient_8bit(int valley, int hill, double kernel) {
  const int n = valley + hill;
  const double sigma = kernel;  // the version-1 reading since issue 15: kernel n is sigma n px
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> w;
  double sum = 0;
  for (int j = -radius; j <= radius; ++j) {
    w.push_back(std::exp(-j * j / (2 * sigma * sigma)));
    sum += w.back();
  }
  std::vector<double> h(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    double s = 0;
    for (int j = -radius; j <= radius; ++j) {
      int q = ((i + j) % n + n) % n;
      s += w[static_cast<std::size_t>(j + radius)] / sum * (q >= valley ? 255.0 : 0.0);
    }
    h[static_cast<std::size_t>(i)] = std::round(s);
  }
  std::vector<double> d(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) d[static_cast<std::size_t>(i)] = h[static_cast<std::size_t>((i + 1) % n)] - h[static_cast<std::size_t>((i + n - 1) % n)];
  return d;
}


}  // namespace sandpaper::test

namespace {
// Paths in diagnostics and goldens are relative to the source tree, wherever the binary is run.
const bool kInSourceTree = [] {
  std::filesystem::current_path(SANDPAPER_SOURCE_DIR);
  return true;
}();
}  // namespace

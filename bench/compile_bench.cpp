// Compile time (off the servo thread, but what a user waits for): a perceptual one-liner, a height
// map from an image resampled to a 1024 x 1024 grid, and every material of the shipped library.
// The compiler (library and calibration loaded) is built once, outside the timing.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "sandpaper/compiler/compiler.hpp"

namespace sandpaper {
namespace {

const std::string kSource = SANDPAPER_SOURCE_DIR;

const compiler::Compiler& shipped() {
  static const compiler::Compiler c([] {
    compiler::CompileOptions o;
    o.library_dir = kSource + "/library";
    o.calibration_dir = kSource + "/calibration";
    return o;
  }());
  return c;
}

void expect_ok(benchmark::State& state, const compiler::CompileResult& r) {
  if (!r.ok()) state.SkipWithError(compiler::format_diagnostics(r.diagnostics).c_str());
}

void BM_CompileOneLiner(benchmark::State& state) {
  const auto& c = shipped();
  for (auto _ : state) {
    auto r = c.compile_text("roughness 0.6; grating period 2.5 mm");
    expect_ok(state, r);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_CompileOneLiner)->Unit(benchmark::kMicrosecond);

// library/images/brick.png is 512 x 512 pixels; 90 mm sampled every 90/1024 mm gives the runtime a
// 1024 x 1024 grid (the image read, resampled, smoothed and differentiated).
void BM_CompileImage1024(benchmark::State& state) {
  const auto& c = shipped();
  const std::string text = "heightmap \"" + kSource +
                           "/library/images/brick.png\" size 90 mm sampling 0.087890625 mm smoothing 0.15 mm invert "
                           "depth 0.5 mm press 2 N";
  for (auto _ : state) {
    auto r = c.compile_text(text);
    expect_ok(state, r);
    if (r.ok())
      for (const auto& term : r.program->terms)
        if (const auto* h = std::get_if<schema::HeightFieldTerm>(&term)) state.counters["grid_n"] = h->nx;
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_CompileImage1024)->Unit(benchmark::kMillisecond);

void BM_CompileWholeLibrary(benchmark::State& state) {
  const auto& c = shipped();
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(kSource + "/library"))
    if (e.path().extension() == ".hmat") files.push_back(e.path());
  for (auto _ : state)
    for (const auto& f : files) {
      auto r = c.compile_file(f);
      expect_ok(state, r);
      benchmark::DoNotOptimize(r);
    }
  state.counters["materials"] = static_cast<double>(files.size());
}
BENCHMARK(BM_CompileWholeLibrary)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sandpaper

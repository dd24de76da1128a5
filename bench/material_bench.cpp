// Tick cost of every shipped material (library/**/*.hmat, examples/**/*.hmat) as compiled by the
// shipped compiler: one PatchEvaluator::force_rt call, the hand wandering over the patch. Issue 5's
// target: well under 1 us per tick for any shipped material.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "compiled_material.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"

namespace sandpaper {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = SANDPAPER_SOURCE_DIR;


void BM_Material(benchmark::State& state, fs::path file) {
  const auto compiled = bench::compiled_material(file);
  if (!compiled) {
    state.SkipWithError("did not compile");
    return;
  }
  const schema::PatchProgram& program = *compiled;
  runtime::PatchEvaluator evaluator(program);
  runtime::HandState hand;
  hand.velocity_m_s = {0.05, -0.02};
  double t = 0;
  for (auto _ : state) {
    t += 1e-3;
    hand.position_m = {0.04 * std::sin(t * 1.3), 0.04 * std::cos(t * 0.7)};
    benchmark::DoNotOptimize(evaluator.force_rt(hand, 1e-3));
  }
  state.counters["terms"] = static_cast<double>(program.terms.size());
}

const int registered = [] {
  std::vector<fs::path> files;
  for (const auto& dir : {kSource / "library", kSource / "examples"})
    for (const auto& e : fs::recursive_directory_iterator(dir))
      if (e.is_regular_file() && e.path().extension() == ".hmat") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files)
    benchmark::RegisterBenchmark(("BM_Material/" + f.lexically_relative(kSource).string()).c_str(), BM_Material, f);
  return 0;
}();

}  // namespace
}  // namespace sandpaper

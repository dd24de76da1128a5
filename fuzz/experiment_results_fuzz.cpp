// Experiment results (experiments: results.hpp): the input is a results folder's
// results.jsonl, beside a design.toml copied from examples/experiments/ (the one whose checksum the
// input names, else roughness-magnitude.toml, so that a header can match). read_results as
// `experiment resume` and `analyse` read it; an accepted folder's records as JSON, then the analysis
// `experiment analyse` runs on it (pictures into the scratch folder; left out where the fuzz build
// cannot compile the analysis: fuzz/CMakeLists.txt, SANDPAPER_FUZZ_NO_ANALYSIS).
// Expected rejections: experiment::DesignError, calibration::FitError. Nothing else is caught.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_support.hpp"
#ifndef SANDPAPER_FUZZ_NO_ANALYSIS
#include "sandpaper/calibration/fit_error.hpp"
#include "sandpaper/experiment/analysis.hpp"
#endif
#include "sandpaper/experiment/design.hpp"
#include "sandpaper/experiment/results.hpp"

namespace {

struct ShippedDesign {
  std::string text, checksum;
};

const std::vector<ShippedDesign>& shipped_designs() {
  static const std::vector<ShippedDesign> all = [] {
    std::vector<ShippedDesign> v;
    for (const char* name : {"roughness-magnitude.toml", "roughness-sorting.toml", "texture-confidence.toml", "force-jnd.toml",
                             "softness-magnitude.toml"}) {
      std::ifstream in(sandpaper::fuzz::source_dir() / "examples" / "experiments" / name, std::ios::binary);
      std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      v.push_back({text, sandpaper::experiment::design_checksum(text)});
    }
    return v;
  }();
  return all;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const auto dir = fuzz::scratch_dir() / "results";
  std::filesystem::create_directories(dir);
  const ShippedDesign* design = &shipped_designs().front();
  for (const auto& d : shipped_designs())
    if (input.find(d.checksum) != std::string_view::npos) design = &d;
  fuzz::write_file(dir / "design.toml", design->text);
  fuzz::write_file(dir / "results.jsonl", input);

  experiment::Results results;
  try {
    results = experiment::read_results(dir);
  } catch (const experiment::DesignError&) {
    return 0;
  }
  fuzz::dump_json(experiment::to_json(results.header));
  for (const auto& a : results.answers) fuzz::dump_json(experiment::to_json(a));
  const int next = results.next_trial();
  fuzz::check(next >= 0, "next_trial() < 0");

#ifndef SANDPAPER_FUZZ_NO_ANALYSIS
  experiment::AnalyseOptions options;
  options.pictures_dir = fuzz::scratch_dir() / "analysis";
  try {
    const auto analysis = experiment::analyse(dir, options);
    fuzz::dump_json(analysis.report);
  } catch (const experiment::DesignError&) {
  } catch (const calibration::FitError&) {
  }
#endif
  return 0;
}

// Experiment design files (experiments: design.hpp, docs/EXPERIMENTS.md) through parse_design,
// as `sandpaper experiment run` reads them, anchored in examples/experiments/ so the shipped
// designs' relative material paths resolve. An accepted design is then scheduled for two subjects
// as `run` does; every trial must name stimuli of the design.
// Expected rejection: experiment::DesignError. Nothing else is caught.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "sandpaper/experiment/design.hpp"
#include "sandpaper/experiment/schedule.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::string text(reinterpret_cast<const char*>(data), size);
  experiment::Design design;
  try {
    design = experiment::parse_design(text, fuzz::source_dir() / "examples" / "experiments" / "fuzz.toml");
  } catch (const experiment::DesignError&) {
    return 0;
  }
  fuzz::check(!design.stimuli.empty(), "a design without stimuli was accepted");
  fuzz::check(design.checksum == experiment::design_checksum(text), "the design's checksum is not its text's");
  for (const char* subject : {"S01", "fuzz subject"}) {
    const auto schedule = experiment::make_schedule(design, subject);
    for (const auto& trial : schedule)
      for (int s : trial.stimuli)
        fuzz::check(s >= 0 && static_cast<std::size_t>(s) < design.stimuli.size(), "a trial names no stimulus of the design");
  }
  return 0;
}

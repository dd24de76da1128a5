// `sandpaper run SCENE --device sim3d`: the simulated 3-DOF device's hand presses onto each object
// and strokes across it while the proxy renderer plays the scene; then the run's figures and the
// energy check (shapes/scene_play.hpp; docs/SHAPES.md, "Running a scene").
#include <iostream>

#include "../scene_run_report.hpp"
#include "cli.hpp"
#include "scene_input.hpp"
#include "sandpaper/player/play_patch.hpp"

namespace sandpaper::cli {

int cmd_scene_run(const CommonOptions& o, const PlayRequest& r) {
  auto c = make_compiler(o);
  if (c.device().axes != 3) {
    std::cerr << "sandpaper run: a scene plays on a device with three axes: --device sim3d (the simulated one; "
                 "novint-falcon and haply-inverse3 have device files but no driver, docs/DEVICES.md); "
              << o.device << " has " << c.device().axes << "\n";
    return kExitUsage;
  }
  if (o.device != "sim3d") {
    std::cerr << "sandpaper run: " << o.device << " has no driver in Sandpaper (docs/DEVICES.md); "
                 "--device sim3d plays the scene on the simulated one\n";
    return kExitUsage;
  }
  auto loaded = load_scene(o, c);
  if (!loaded) return kExitBadInput;
  const auto play = shapes::play_scene_on_sim3d(*loaded->program, r.rate_hz, r.duration_s, r.speed_mm_s * 1e-3);
  const bool passed = report_scene_run(*loaded->program, o.device, play, r.speed_mm_s, o.json,
                                       {{"diagnostics", diagnostics_json(loaded->diagnostics)}});
  return passed ? kExitOk : kExitBadInput;
}

}  // namespace sandpaper::cli

// An application asks for a roughness level by name and plays it on the simulated joystick.
// Usage: play_roughness_level [coarse]   (levels: calibration/levels/roughness-levels.toml)
#include <iostream>

#include "sandpaper/sandpaper.hpp"

int main(int argc, char** argv) try {
  const std::string level = argc > 1 ? argv[1] : "coarse";
  sandpaper::Library library;
  sandpaper::Material material = library.roughness_level(level);  // unknown names list the known ones
  sandpaper::Player player = sandpaper::Player::simulated();
  player.load(material);
  player.start({.rate_hz = 1000, .duration_s = 0.5});
  auto report = player.wait();
  std::cout << "roughness level " << level << " (" << library.roughness_level_value(level) << "): " << report.ticks
            << " ticks at " << report.rate_hz << " Hz, max lateral force " << report.felt_max_lateral_force_N
            << " N (compiled " << material.compiled_max_lateral_force_N() << " N, roughness " << material.compiled_roughness() << ")\n";
  return report.stop_cause == sandpaper::runtime::StopCause::Completed ? 0 : 1;
} catch (const sandpaper::Error& e) {
  std::cerr << e.what() << '\n';
  return 1;
}

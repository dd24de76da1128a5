// An application asks for a material by name (or by description) and plays it on the simulated
// joystick. Usage: play_material ["like corduroy; roughness 0.6" | corduroy | "roughness 0.6"]
#include <iostream>

#include "sandpaper/sandpaper.hpp"

int main(int argc, char** argv) try {
  sandpaper::Library library;  // the shipped library and calibration, device "sim"
  sandpaper::Material material = library.compile(argc > 1 ? argv[1] : "like corduroy; roughness 0.6");
  sandpaper::Player player = sandpaper::Player::simulated();
  player.load(material);
  player.start({.rate_hz = 1000, .duration_s = 0.5});
  auto report = player.wait();
  std::cout << material.name() << ": " << report.ticks << " ticks at " << report.rate_hz << " Hz, max lateral force "
            << report.felt_max_lateral_force_N << " N (compiled " << material.compiled_max_lateral_force_N() << " N)\n";
  return report.stop_cause == sandpaper::runtime::StopCause::Completed ? 0 : 1;
} catch (const sandpaper::Error& e) {  // a compile error prints as `sandpaper compile` prints it
  std::cerr << e.what() << '\n';
  return 1;
}

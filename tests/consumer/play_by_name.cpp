// Plays a library material by name on the simulated joystick. Usage: play_by_name [corduroy]
#include <iostream>

#include <sandpaper/sandpaper.hpp>

int main(int argc, char** argv) try {
  sandpaper::Library library;
  std::cout << "library " << library.library_dir().string() << "\n";
  sandpaper::Material material = library.compile(argc > 1 ? argv[1] : "corduroy");
  sandpaper::Player player = sandpaper::Player::simulated();
  player.load(material);
  player.start({.rate_hz = 1000, .duration_s = 0.5});
  sandpaper::runtime::ServoReport report = player.wait();
  std::cout << "material " << material.name() << " compiled_max_lateral_force_N " << material.compiled_max_lateral_force_N()
            << "\nplayed " << report.ticks << " ticks, felt_max_lateral_force_N " << report.felt_max_lateral_force_N
            << ", stop " << sandpaper::runtime::stop_cause_name(report.stop_cause) << "\n";
  return report.stop_cause == sandpaper::runtime::StopCause::Completed ? 0 : 1;
} catch (const sandpaper::Error& e) {
  std::cerr << e.what() << "\n";
  return 1;
}

// An application asks for a material by name and plays it on the simulated joystick: the C++ API
// in a few lines. Usage: play_material ["like corduroy; roughness 0.6"]
#include <iostream>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"

int main(int argc, char** argv) {
  using namespace sandpaper;
  compiler::Compiler compiler({});  // shipped library and calibration, device "sim"
  auto result = compiler.compile_text(argc > 1 ? argv[1] : "like corduroy; roughness 0.6");
  if (!result.ok()) {
    std::cerr << compiler::format_diagnostics(result.diagnostics);
    return 1;
  }
  runtime::SimJoystick joystick(runtime::sim_device_limits(), {}, 500);
  runtime::PatchEvaluator evaluator(*result.program);
  auto report = runtime::run_servo_thread_nonrt(joystick, evaluator, {.rate_hz = 1000, .duration_s = 0.5});
  std::cout << result.program->name << ": " << report.ticks << " ticks at " << report.rate_hz << " Hz, max lateral force "
            << report.max_lateral_force_N << " N (compiled " << result.program->max_lateral_force_N << " N)\n";
  return report.stop_reason == "completed" ? 0 : 1;
}

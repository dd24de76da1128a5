// One design, one emulated device, both clocks: a study of the thesis' joystick run on the virtual
// clock (simulated observers) and one run live (a person) present the same device, with its 12-bit
// force commands and its sample-and-hold tables (Minsky 1995, Table 6, Appendix B 2.1), because both
// presenters open it through the device factory and play it through runtime::LiveServo.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/experiment/design.hpp"
#include "sandpaper/experiment/presenter.hpp"
#include "sandpaper/experiment/stimuli.hpp"
#include "sandpaper/runtime/devices/open_device.hpp"

namespace sandpaper::experiment {
namespace {

const std::filesystem::path kSource(SANDPAPER_SOURCE_DIR);

// How many whole command steps `force_N` is, and how far from a whole number (0 on the grid).
double off_grid(double force_N, double step_N) { return std::abs(force_N / step_N - std::round(force_N / step_N)); }

TEST(EmulatedPresenters, OneDesignPlaysTheSameEmulatedDeviceOnBothClocks) {
  auto d = load_design(kSource / "examples/experiments/roughness-magnitude.toml");
  d.device = "sandpaper-1995";
  compiler::CompileOptions co;
  co.device = d.device;
  co.library_dir = kSource / "library";
  co.calibration_dir = kSource / "calibration";
  const compiler::Compiler c(co);
  const auto stimuli = prepare_stimuli(d, c);
  ASSERT_GE(stimuli.size(), 2u);

  const auto set = calibration::CalibrationSet::load(kSource / "calibration");
  const calibration::DeviceCalibration* joystick = set.find_device("sandpaper-1995");
  ASSERT_NE(joystick, nullptr);
  const double step_N = joystick->force_step_N(0);  // 4.814 mN (Table 6: 0.490909 gf)
  ASSERT_NEAR(step_N, 0.00481417, 1e-6);

  runtime::DeviceSpec spec;
  spec.device = "sandpaper-1995";
  spec.script.speed_m_s = d.hand_speed_m_s;
  spec.script.amplitude_m = d.hand_amplitude_m;
  PresentOptions po;
  po.rate_hz = 900;  // the thesis joystick's only rate (sandpaper-1995.toml)
  po.ramp_s = 0.05;
  po.hold_s = 0.4;  // long enough for the scan to cross the coarsest stimulus' ridges a few times

  runtime::DeviceSpec virtual_spec = spec;
  virtual_spec.virtual_clock = true;
  VirtualPresenter on_virtual([&] { return runtime::open_device(set, virtual_spec).device; }, "virtual", po);
  LivePresenter on_steady(runtime::open_device(set, spec).device, "live", po);

  // A gain off 1 (as a two-interval comparison plays) takes the compiled force, already whole units,
  // off the grid; the loop puts it back only on a device that says it takes whole units. What the
  // virtual clock played before the device described itself, the plain simulated joystick, does not.
  const double gain = 0.73;  // 760 units (the last stimulus) x 0.7 would happen to be whole
  VirtualPresenter plain(spec.script, po);
  EXPECT_GT(off_grid(plain.present(stimuli.back().program, gain).felt_max_N, step_N), 1e-3);

  for (const auto& s : {stimuli.front(), stimuli.back()}) {
    const Presentation v = on_virtual.present(s.program, gain);
    const Presentation l = on_steady.present(s.program, gain);
    ASSERT_FALSE(v.interrupted) << v.cause;
    ASSERT_FALSE(l.interrupted) << l.cause;
    // What each clock's loop sent is in whole joystick units: the device's, not the config's.
    EXPECT_LT(off_grid(v.felt_max_N, step_N), 1e-6) << s.name << ": " << v.felt_max_N << " N on the virtual clock";
    EXPECT_LT(off_grid(l.felt_max_N, step_N), 1e-6) << s.name << ": " << l.felt_max_N << " N on the steady clock";
    // The same held table crossed by the same scan: the peaks agree to a few units (the steady
    // clock's ticks land a little off the virtual clock's positions).
    EXPECT_NEAR(v.felt_max_N, l.felt_max_N, 3 * step_N + 0.02 * v.felt_max_N) << s.name;
    EXPECT_GT(v.felt_max_N, 0.5 * gain * s.force_N) << s.name;
  }
}

}  // namespace
}  // namespace sandpaper::experiment

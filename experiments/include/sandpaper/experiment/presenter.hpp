#pragma once
// Playing one stimulus to the subject's hand: the program's force times an envelope that ramps up
// from zero, holds, and ramps back to zero (runtime/envelope_source.hpp), so consecutive trials
// never step the force. Two ways to run it: on the running real-time loop (a person at a joystick:
// each trial is hot-swapped in, runtime/swappable_source.hpp), or on the virtual clock with the
// simulated joystick's scripted hand (a simulated observer: a whole study in seconds).
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "sandpaper/runtime/device.hpp"
#include "sandpaper/runtime/live_servo.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::experiment {

struct PresentOptions {
  double rate_hz = 1000;   // servo rate, Hz
  double ramp_s = 0.25;    // force ramp either side of the hold, s
  double hold_s = 2.0;     // full force, s
  // Set (by a signal handler) to stop the live loop at its next tick; the presentation is then
  // interrupted with cause stop_requested. nullptr: none.
  const std::atomic<bool>* stop = nullptr;
  double deadline_guard_periods = runtime::ServoConfig{}.deadline_guard_periods;  // the live loop's (ServoConfig)
  double velocity_limit_m_s = runtime::ServoConfig{}.velocity_limit_m_s;          // the live loop's, m/s
};

// What the loop did while the stimulus played.
struct Presentation {
  double felt_max_N = 0;        // largest |F| written to the device during the envelope, N
  bool interrupted = false;     // the loop stopped (a stop cause) before the envelope ended
  std::string cause;            // runtime::stop_cause_name when interrupted
};

class Presenter {
 public:
  virtual ~Presenter() = default;
  // Plays `program` with its force scaled by `gain` (>= 0) for ramp + hold + ramp; returns when the
  // force is back at zero or the loop stopped. Throws std::invalid_argument for a program the
  // runtime cannot evaluate.
  virtual Presentation present(std::shared_ptr<const schema::PatchProgram> program, double gain) = 0;
  // After an interruption: start the loop again (a resumed session does this by starting afresh).
  virtual std::string describe() const = 0;
};

// Opens a fresh device for one presentation on the virtual clock (through runtime::open_device,
// with DeviceSpec::virtual_clock), its simulated hand at the start of its script.
using DeviceOpener = std::function<std::unique_ptr<runtime::Device>()>;

// A simulated device on the virtual clock: each presentation is one run of the servo loop through a
// runtime::LiveServo host on a device of its own, so an emulated device (sandpaper-1995) plays with
// its quantisation and its sample-and-hold tables, as it does on the live loop. Deterministic.
class VirtualPresenter final : public Presenter {
 public:
  // `open` gives the device of each presentation; `description` is what describe() says. Throws
  // std::invalid_argument for a rate or duration the device's limits refuse (runtime::validate_config)
  // or a device that cannot follow the virtual clock.
  VirtualPresenter(DeviceOpener open, std::string description, PresentOptions options);
  // The simulated joystick (calibration/devices/sim.toml, through the device factory) moved by `hand`.
  VirtualPresenter(runtime::HandScript hand, PresentOptions options);
  Presentation present(std::shared_ptr<const schema::PatchProgram> program, double gain) override;
  std::string describe() const override { return description_; }

 private:
  DeviceOpener open_;
  std::string description_;
  PresentOptions options_;
};

// A device played in real time by one continuously running servo thread (a runtime::LiveServo host);
// each presentation is offered to it as a hot swap and measured from the telemetry ring.
class LivePresenter final : public Presenter {
 public:
  // Starts the servo thread at once (zero force until the first trial). Throws std::invalid_argument
  // for a rate the device refuses.
  LivePresenter(std::unique_ptr<runtime::Device> device, std::string description, PresentOptions options);
  ~LivePresenter() override;  // stops the loop (zero force written last)
  Presentation present(std::shared_ptr<const schema::PatchProgram> program, double gain) override;
  std::string describe() const override { return description_; }

 private:
  std::unique_ptr<runtime::Device> device_;
  std::string description_;
  PresentOptions options_;
  runtime::LiveServo host_;  // one run from construction until a stop cause or the destructor
  bool stopped_ = false;
  runtime::ServoReport report_;
};

}  // namespace sandpaper::experiment

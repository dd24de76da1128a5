#pragma once
// The simulated 2-axis joystick: a scripted hand moves the handle (position-controlled, so the
// forces do not deflect it) and every tick's time, position and commanded force are recorded
// into storage reserved before the loop starts.
#include <cstddef>
#include <vector>

#include "sandpaper/runtime/recording_device.hpp"

namespace sandpaper::runtime {

enum class HandPath {
  Scan,    // back and forth through the patch centre along `direction_rad`, constant speed, turning at
           // +-amplitude; starts on the centre at t = 0 heading toward +direction
  Circle,  // a circle of radius `amplitude` about the patch centre at constant speed, counter-clockwise
           // from (amplitude, 0)
};

struct HandScript {
  HandPath path = HandPath::Scan;
  double speed_m_s = 0.05;        // along the path
  double amplitude_m = 0.03;      // scan half-width, or circle radius
  double direction_rad = 0;       // scan direction (0 = along x)
  double start_m = 0;             // distance along the path already travelled at t = 0, m
};

// Where `script` puts the hand at time t (s), m. Pure; shared by the position-controlled and the
// dynamic-hand joysticks.
glm::dvec2 scripted_hand_position(const HandScript& script, double t_s) noexcept;

class SimJoystick final : public RecordingDevice {
 public:
  // `capacity_ticks`: how many ticks to record; ticks beyond it are played but not recorded.
  SimJoystick(DeviceLimits limits, HandScript script, std::size_t capacity_ticks);
  const DeviceLimits& limits() const noexcept override { return limits_; }
  bool read_position_rt(double t_s, glm::dvec2& position_m) noexcept override;
  // Records {t, position, force} of the tick whose read came just before. A write with no read
  // before it (the loop's closing zero-force command) is accepted but is not a tick.
  bool write_force_rt(glm::dvec2 force_N) noexcept override;

  // Where the script puts the hand at time t (s). Pure; used by read_position_rt and tests.
  glm::dvec2 hand_position(double t_s) const noexcept;

 private:
  DeviceLimits limits_;
  HandScript script_;
};

// The sim device's limits as calibration/devices/sim.toml states them (compiled in at build time):
// 10 N maximum force as the thesis joystick (Minsky 1995, Table 2), 900 Hz - 10 kHz, a 9-inch
// circular workspace. Throws calibration::CalibrationError only if the embedded file were invalid.
DeviceLimits sim_device_limits();

}  // namespace sandpaper::runtime

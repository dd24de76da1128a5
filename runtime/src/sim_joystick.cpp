#include "sandpaper/runtime/sim_joystick.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "embedded_device_files.hpp"
#include "sandpaper/runtime/device_limits.hpp"

namespace sandpaper::runtime {
namespace {

// Signed offset along the scan line after travelling `distance`: 0 -> +A -> -A -> 0 repeats every
// 4A of travel, so the hand starts on the patch centre heading in +direction.
double triangle_offset(double distance, double amplitude) noexcept {
  const double lap = 4 * amplitude;
  double phase = std::fmod(distance, lap);
  if (phase < 0) phase += lap;
  if (phase < amplitude) return phase;
  if (phase < 3 * amplitude) return 2 * amplitude - phase;
  return phase - lap;
}

}  // namespace

SimJoystick::SimJoystick(DeviceLimits limits, HandScript script, std::size_t capacity_ticks)
    : RecordingDevice(capacity_ticks), limits_(std::move(limits)), script_(script) {}

glm::dvec2 SimJoystick::hand_position(double t_s) const noexcept { return scripted_hand_position(script_, t_s); }

glm::dvec2 scripted_hand_position(const HandScript& script, double t_s) noexcept {
  const double amplitude = script.amplitude_m;
  if (!(amplitude > 0)) return {0, 0};  // a zero-size path is a hand held still on the centre
  const double distance = script.start_m + script.speed_m_s * t_s;
  switch (script.path) {
    case HandPath::Scan: {
      const double offset = triangle_offset(distance, amplitude);
      return offset * glm::dvec2{std::cos(script.direction_rad), std::sin(script.direction_rad)};
    }
    case HandPath::Circle: {
      const double angle = distance / amplitude;
      return amplitude * glm::dvec2{std::cos(angle), std::sin(angle)};
    }
  }
  return {0, 0};
}

bool SimJoystick::read_position_rt(double t_s, glm::dvec2& position_m) noexcept {
  position_m = hand_position(t_s);
  note_read_rt(t_s, position_m);
  return true;
}

bool SimJoystick::write_force_rt(glm::dvec2 force_N) noexcept {
  // Only a write answering a read is a tick; the loop's closing zero-force command is obeyed
  // (the sim has nothing to do) but must not show up as an extra tick in the record.
  note_write_rt(force_N);
  return true;
}

DeviceLimits sim_device_limits() {
  static const DeviceLimits limits = [] {
    const auto& file = detail::embedded_device_files().front();
    return limits_of(calibration::parse_device_text(std::string(file.text), std::string(file.shown_as)));
  }();
  return limits;
}

}  // namespace sandpaper::runtime

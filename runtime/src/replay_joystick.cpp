#include "sandpaper/runtime/replay_joystick.hpp"

#include <utility>

namespace sandpaper::runtime {

ReplayJoystick::ReplayJoystick(DeviceLimits limits, std::vector<glm::dvec2> positions_m)
    : RecordingDevice(positions_m.size()), limits_(std::move(limits)), positions_(std::move(positions_m)) {}

bool ReplayJoystick::read_position_rt(double t_s, glm::dvec2& position_m) noexcept {
  if (next_ >= positions_.size()) return false;
  position_m = positions_[next_++];
  note_read_rt(t_s, position_m);
  return true;
}

bool ReplayJoystick::write_force_rt(glm::dvec2 force_N) noexcept {
  note_write_rt(force_N);
  return true;
}

}  // namespace sandpaper::runtime

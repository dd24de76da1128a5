#pragma once
// A device that plays back recorded handle positions: tick k reports the k-th recorded position,
// whatever the clock says, so a trace replayed on the virtual clock at its own rate gives the loop
// exactly the inputs it had when it was recorded (regression tests; comparing two builds).
#include <cstddef>
#include <vector>

#include "sandpaper/runtime/recording_device.hpp"

namespace sandpaper::runtime {

class ReplayJoystick final : public RecordingDevice {
 public:
  // `positions_m`: one per tick, m. Records every tick it plays (capacity = positions.size()).
  ReplayJoystick(DeviceLimits limits, std::vector<glm::dvec2> positions_m);
  const DeviceLimits& limits() const noexcept override { return limits_; }
  // The next recorded position; false (a failed read) once the recording is used up.
  bool read_position_rt(double t_s, glm::dvec2& position_m) noexcept override;
  bool write_force_rt(glm::dvec2 force_N) noexcept override;
  std::size_t size() const noexcept { return positions_.size(); }

 private:
  DeviceLimits limits_;
  std::vector<glm::dvec2> positions_;
  std::size_t next_ = 0;
};

}  // namespace sandpaper::runtime

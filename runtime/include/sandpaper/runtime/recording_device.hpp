#pragma once
// A simulated device that records every tick's time, position and commanded force into storage
// reserved before the loop starts (SimJoystick, DynamicHandJoystick, ReplayJoystick). The servo
// loop's closing zero-force write, which answers no read, is obeyed but is not a tick.
#include <cstddef>
#include <vector>

#include "sandpaper/runtime/device.hpp"

namespace sandpaper::runtime {

struct TickRecord {
  double t_s;
  glm::dvec2 position_m;  // what the device reported at this tick's read (m, patch coordinates)
  glm::dvec2 force_N;     // what the loop commanded in answer (N)
};

class RecordingDevice : public Device {
 public:
  // Records of the ticks played so far (read after the loop has stopped).
  const std::vector<TickRecord>& records() const noexcept { return records_; }
  std::size_t ticks_played() const noexcept { return ticks_; }

 protected:
  // `capacity_ticks`: how many ticks to record; ticks beyond it are played but not recorded.
  explicit RecordingDevice(std::size_t capacity_ticks) : capacity_(capacity_ticks) { records_.reserve(capacity_ticks); }
  // Call from read_position_rt with what was reported.
  void note_read_rt(double t_s, glm::dvec2 position_m) noexcept {
    last_t_ = t_s;
    last_position_ = position_m;
    read_pending_ = true;
  }
  // Call from write_force_rt; returns true when the write answers a read (a tick), false for the
  // loop's closing command. push_back never reallocates: the storage was reserved up front.
  bool note_write_rt(glm::dvec2 force_N) noexcept {
    if (!read_pending_) return false;
    read_pending_ = false;
    if (records_.size() < capacity_) records_.push_back(TickRecord{last_t_, last_position_, force_N});
    ++ticks_;
    return true;
  }

 private:
  std::size_t capacity_ = 0;
  std::vector<TickRecord> records_;
  std::size_t ticks_ = 0;
  bool read_pending_ = false;
  double last_t_ = 0;
  glm::dvec2 last_position_{0, 0};
};

}  // namespace sandpaper::runtime

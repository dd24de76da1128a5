#pragma once
// Programs, devices and clocks the runtime tests share.
#include <cstdint>
#include <utility>
#include <vector>

#include "sandpaper/runtime/device.hpp"
#include "sandpaper/runtime/servo_clock.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::runtime::testing {

inline schema::PatchProgram program_of(std::vector<schema::Term> terms) {
  schema::PatchProgram program;
  program.name = "test";
  program.device = "sim";
  program.terms = std::move(terms);
  return program;
}

inline schema::GratingTerm grating(double period_m, double orientation_rad, std::vector<float> force_N) {
  schema::GratingTerm term;
  term.period_m = period_m;
  term.orientation_rad = orientation_rad;
  term.force_N = std::move(force_N);
  return term;
}

inline schema::SpringTerm spring(double stiffness_N_per_m, double cx = 0, double cy = 0) {
  schema::SpringTerm term;
  term.stiffness_N_per_m = stiffness_N_per_m;
  term.centre_m[0] = cx;
  term.centre_m[1] = cy;
  return term;
}

inline schema::DamperTerm damper(double damping_Ns_per_m) {
  schema::DamperTerm term;
  term.damping_Ns_per_m = damping_Ns_per_m;
  return term;
}

// A device that stands still at `position`, remembers every force commanded, and can be told to
// fail its n-th read or write (counting from 1; 0 = never).
class ScriptedDevice final : public Device {
 public:
  explicit ScriptedDevice(glm::dvec2 position = {0, 0}) : limits_(sim_device_limits()), position_(position) {
    writes.reserve(1 << 16);
  }
  const DeviceLimits& limits() const noexcept override { return limits_; }
  bool read_position_rt(double, glm::dvec2& position_m) noexcept override {
    ++reads;
    position_m = position_;
    return reads != fail_read_at;
  }
  bool write_force_rt(glm::dvec2 force_N) noexcept override {
    if (writes.size() < writes.capacity()) writes.push_back(force_N);
    return writes.size() != fail_write_at;
  }

  DeviceLimits limits_;
  glm::dvec2 position_;
  std::size_t reads = 0;
  std::size_t fail_read_at = 0;
  std::size_t fail_write_at = 0;
  std::vector<glm::dvec2> writes;
};

// A virtual clock that loses `stall_ns` right after waking for tick `stall_tick`, as if the
// scheduler had kept the servo thread off the CPU.
class StallingClock final : public ServoClock {
 public:
  StallingClock(std::uint64_t stall_tick, std::int64_t stall_ns) : stall_tick_(stall_tick), stall_ns_(stall_ns) {}
  std::int64_t now_ns() noexcept override { return clock_.now_ns(); }
  void sleep_until_ns(std::int64_t deadline_ns) noexcept override {
    clock_.sleep_until_ns(deadline_ns);
    if (sleeps_++ == stall_tick_) clock_.advance_ns(stall_ns_);
  }

 private:
  VirtualClock clock_;
  std::uint64_t stall_tick_;
  std::int64_t stall_ns_;
  std::uint64_t sleeps_ = 0;
};

}  // namespace sandpaper::runtime::testing

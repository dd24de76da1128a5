#pragma once
// The studio's servo loop: one device (the Dummy-mode simulated joystick, or a USB joystick) played
// through the runtime's one host (runtime::LiveServo: the servo thread, the hot-swappable source, the
// telemetry ring), and a supervisor thread that drains the ring into a snapshot the HTTP threads read. Nothing here runs on the servo thread but the loop
// itself; the HTTP server never touches it (docs/STUDIO.md, "Threads").
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <glm/vec2.hpp>

#include "sandpaper/runtime/device.hpp"
#include "sandpaper/runtime/dummy_joystick.hpp"
#include "sandpaper/runtime/live_servo.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/schema/patch_program.hpp"
#include "sandpaper/schema/workspace_program.hpp"

namespace sandpaper::studio {

// What the page and /api/state show. Forces N, positions mm, rates Hz.
struct LoopState {
  std::uint64_t ticks = 0;          // servo ticks since the studio started; never decreases
  double rate_hz = 0;               // achieved over about the last second
  std::uint64_t overruns = 0;       // ticks that started more than half a period late, since the start
  std::uint64_t telemetry_dropped = 0;
  std::string material;             // name of the material the servo thread is playing now
  std::uint64_t material_version = 0;  // which load it is (1, 2, ...); 0 before the first
  double compiled_max_lateral_force_N = 0;  // of that material
  double compiled_roughness = 0;            // of that material (its compile map)
  double felt_max_lateral_force_N = 0;      // largest |F| written over about the last second
  glm::dvec2 hand_mm{0, 0};
  glm::dvec2 force_N{0, 0};
  bool running = false;
  bool realtime = false;            // SCHED_FIFO granted
  std::string stop_cause;           // of the last run that ended by itself ("" while none has)
  std::uint64_t restarts = 0;       // runs restarted after a stop cause (simulated device only)
};

struct LoopOptions {
  double rate_hz = 1000;
  double crossfade_s = 0.02;        // the hot swap's crossfade (runtime::SwappableSource)
  bool restart_after_fault = true;  // a simulated hand cannot be hurt: start again after a stop cause
  double deadline_guard_periods = runtime::ServoConfig{}.deadline_guard_periods;  // ServoConfig's
  double velocity_limit_m_s = runtime::ServoConfig{}.velocity_limit_m_s;          // ServoConfig's, m/s
};

class LiveLoop {
 public:
  // `device` is played from start() until stop(). `dummy`, when the device is the Dummy-mode
  // joystick, is the same object, for set_hand_nonrt. Throws std::invalid_argument for a rate the
  // device refuses.
  LiveLoop(std::unique_ptr<runtime::Device> device, runtime::DummyJoystick* dummy, LoopOptions options);
  ~LiveLoop();  // stops (force to zero) if still running
  LiveLoop(const LiveLoop&) = delete;
  LiveLoop& operator=(const LiveLoop&) = delete;

  // Starts the servo thread (playing nothing until a load) and the supervisor.
  void start_nonrt();
  // Stops the loop with a zero force written last; joins both threads. Idempotent.
  void stop_nonrt();

  // Builds the force source here, off the servo thread, and offers it; the servo thread picks it up
  // at its next tick and crossfades. Never blocks the tick. Returns the load's version. Throws
  // std::invalid_argument if the program cannot be evaluated (runtime::PatchEvaluator's checks).
  std::uint64_t load_nonrt(std::shared_ptr<const schema::PatchProgram> program, double roughness);
  std::uint64_t load_workspace_nonrt(std::shared_ptr<const schema::WorkspaceProgram> workspace);

  // Dummy mode: where the simulated hand should move (mm, patch/workspace coordinates). Returns the
  // target it moves to (mm; clipped to the device's workspace radius), nullopt when the device is
  // not the simulated one.
  std::optional<glm::dvec2> set_hand_nonrt(double x_mm, double y_mm);
  bool has_dummy_hand() const noexcept { return dummy_ != nullptr; }
  const runtime::DeviceLimits& limits() const noexcept { return device_->limits(); }

  LoopState state_nonrt();

 private:
  void supervise();
  void promote_locked();  // with mutex_ held

  std::unique_ptr<runtime::Device> device_;
  runtime::DummyJoystick* dummy_;
  LoopOptions options_;
  runtime::LiveServo host_;
  std::atomic<bool> quitting_{false};
  std::thread supervisor_;
  bool started_ = false;

  mutable std::mutex mutex_;  // guards what follows (HTTP threads and the supervisor; never the servo thread)
  LoopState state_;
  std::mutex offer_mutex_;  // loads are numbered in the order they are offered to host_
  std::uint64_t offered_ = 0;  // loads offered
  // Offered loads not yet seen playing, oldest first; `playing` is set by the servo thread when it
  // picks the source up (one relaxed atomic store).
  struct Pending {
    std::uint64_t version;
    std::shared_ptr<std::atomic<bool>> playing;
    std::string name;
    double force, roughness;
  };
  std::vector<Pending> pending_;
};

}  // namespace sandpaper::studio

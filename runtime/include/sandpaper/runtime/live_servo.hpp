#pragma once
// One host for a servo loop that plays a device while the application thread changes what it plays
// (compare JUCE's AudioDeviceManager): the run (on a thread of its own on the steady clock, or on the
// calling thread on the virtual clock), the hot-swap slot (swappable_source.hpp), the telemetry ring
// the application drains, and force sources built the way the device reads tables
// (Device::table_sampling). The player, the C/C++/Python API, the studio and experiments all play
// through it, so one material on one device is one run whoever hosts it (docs/ARCHITECTURE.md).
#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>

#include "sandpaper/runtime/device.hpp"
#include "sandpaper/runtime/force_source.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/swappable_source.hpp"
#include "sandpaper/runtime/telemetry.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::runtime {

// A force source playing `program` as `device` reads tables (Device::table_sampling), owning the
// program; `picked_up` is raised when a SwappableSource's servo thread takes it over. Throws what
// PatchEvaluator throws for a bad program.
std::unique_ptr<ForceSource> patch_source_for(const Device& device, std::shared_ptr<const schema::PatchProgram> program,
                                              std::shared_ptr<std::atomic<bool>> picked_up = nullptr);

// How long a device that left the bus has to come back at its port for its run's stop to be named a
// reset (StopCause::DeviceReset) rather than an unplug: far longer than a firmware's reboot and the
// kernel's enumeration take (docs/DEVICES.md, "A reset, named", has the lab's figures); an unplugged
// device's run is reported this much later.
inline constexpr double kResetGraceS = 1.5;

class LiveServo {
 public:
  struct Options {
    // Tick records the ring holds between drains (0: no telemetry). A run on the virtual clock is
    // not drained while it runs: give it the whole run's ticks.
    std::size_t telemetry_records = 1 << 16;
    double crossfade_s = SwappableSource::kDefaultCrossfade_s;  // s, >= 0: a swap's blend
  };

  // `device` must outlive the host. `initial` plays from the first tick without a blend (may be
  // null: zero force until offer_nonrt). Throws std::invalid_argument for a bad crossfade.
  LiveServo(Device& device, std::unique_ptr<ForceSource> initial, Options options);
  // Asks a run still going to stop and waits for it.
  ~LiveServo();
  LiveServo(const LiveServo&) = delete;
  LiveServo& operator=(const LiveServo&) = delete;

  // patch_source_for(device(), ...).
  std::unique_ptr<ForceSource> patch_source_nonrt(std::shared_ptr<const schema::PatchProgram> program,
                                                  std::shared_ptr<std::atomic<bool>> picked_up = nullptr) const {
    return patch_source_for(device_, std::move(program), std::move(picked_up));
  }
  // Hands `next` to the servo thread (picked up at its next tick, or at the first of the next run)
  // and frees the sources it has finished with. Never waits for the servo thread; any application
  // thread may offer and collect while another joins.
  void offer_nonrt(std::unique_ptr<ForceSource> next);
  // Frees the sources the servo thread has finished with; returns how many.
  std::size_t collect_retired_nonrt();

  // Starts a run on a thread of its own on the steady clock. The host's stop flag and telemetry ring
  // replace config.stop_request and config.telemetry. Throws std::invalid_argument (validate_config)
  // and std::logic_error while a run is going.
  void start_nonrt(ServoConfig config);
  // Plays a whole run on this thread on the virtual clock (simulated time, as fast as it goes) and
  // returns its report. config.stop_request is kept as given (nothing else can stop a run on the
  // calling thread); the telemetry is the host's ring. Throws std::invalid_argument for a device that
  // cannot follow simulated time (Device::follows_virtual_clock) and what run_servo_loop throws.
  ServoReport run_virtual_nonrt(ServoConfig config);

  // A run was started and not yet joined.
  bool running() const noexcept { return thread_ != nullptr; }
  // The started run has returned (join_nonrt will not wait); true when none was started.
  bool finished() const noexcept { return thread_ == nullptr || thread_->finished(); }
  // The run stops at its next tick (StopRequested).
  void request_stop_nonrt() noexcept { stop_.store(true, std::memory_order_release); }
  // Waits for the started run, frees the retired sources, returns the report; rethrows what the
  // loop threw. A run stopped as DeviceUnplugged whose device came back at its port within
  // kResetGraceS (Device::came_back_nonrt, which gives a held device back first) is reported as
  // DeviceReset. Throws std::logic_error when no run was started.
  ServoReport join_nonrt();

  // The ring the ticks' records go to (drain it with TelemetryReader or pop_nonrt); nullptr without one.
  TelemetryRing* telemetry() noexcept { return ring_.get(); }
  SwappableSource& source() noexcept { return source_; }
  Device& device() noexcept { return device_; }

 private:
  Device& device_;
  SwappableSource source_;
  std::unique_ptr<TelemetryRing> ring_;
  std::atomic<bool> stop_{false};
  std::unique_ptr<ServoThread> thread_;
  std::mutex application_;  // the swap slot's application side is one caller at a time
};

}  // namespace sandpaper::runtime

#include "sandpaper/runtime/live_servo.hpp"

#include <mutex>
#include <stdexcept>

#include "sandpaper/runtime/owning_source.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"

namespace sandpaper::runtime {

LiveServo::LiveServo(Device& device, std::unique_ptr<ForceSource> initial, Options options)
    : device_(device),
      source_(std::move(initial), options.crossfade_s),
      ring_(options.telemetry_records > 0 ? std::make_unique<TelemetryRing>(options.telemetry_records) : nullptr) {}

LiveServo::~LiveServo() {
  if (!thread_) return;
  request_stop_nonrt();
  try {
    (void)thread_->join_nonrt();
  } catch (...) {  // a destructor must not throw; the run is over either way
  }
}

std::unique_ptr<ForceSource> patch_source_for(const Device& device, std::shared_ptr<const schema::PatchProgram> program,
                                              std::shared_ptr<std::atomic<bool>> picked_up) {
  return std::make_unique<OwningSource<schema::PatchProgram, PatchEvaluator>>(std::move(program), std::move(picked_up),
                                                                              device.table_sampling());
}

void LiveServo::offer_nonrt(std::unique_ptr<ForceSource> next) {
  std::lock_guard lock(application_);
  source_.offer_nonrt(std::move(next));
  source_.collect_retired_nonrt();
}

std::size_t LiveServo::collect_retired_nonrt() {
  std::lock_guard lock(application_);
  return source_.collect_retired_nonrt();
}

void LiveServo::start_nonrt(ServoConfig config) {
  if (thread_) throw std::logic_error("the servo loop is already running; join it first");
  stop_.store(false, std::memory_order_release);
  config.stop_request = &stop_;
  config.telemetry = ring_.get();
  auto thread = std::make_unique<ServoThread>();
  thread->start_nonrt(device_, source_, config);  // validates: may throw
  thread_ = std::move(thread);
}

ServoReport LiveServo::run_virtual_nonrt(ServoConfig config) {
  if (thread_) throw std::logic_error("the servo loop is already running; join it first");
  if (!device_.follows_virtual_clock())
    throw std::invalid_argument("device '" + device_.limits().name +
                                "' is moved by a person in real time; it cannot play on the virtual clock");
  config.telemetry = ring_.get();
  VirtualClock clock;
  ServoReport report = run_servo_loop(device_, source_, clock, config);
  collect_retired_nonrt();
  return report;
}

ServoReport LiveServo::join_nonrt() {
  if (!thread_) throw std::logic_error("no servo run to join; start one first");
  std::unique_ptr<ServoThread> thread = std::move(thread_);
  ServoReport report = thread->join_nonrt();
  collect_retired_nonrt();
  // The loop sees only that the device is gone; whether it came back is the bus's to tell. Offers
  // from other threads go on meanwhile (they play on the next run).
  if (report.stop_cause == StopCause::DeviceUnplugged && device_.came_back_nonrt(kResetGraceS)) {
    report.stop_cause = StopCause::DeviceReset;
    report.stop_reason = stop_cause_text(report.stop_cause);
  }
  return report;
}

}  // namespace sandpaper::runtime

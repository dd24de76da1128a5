#include "sandpaper/experiment/presenter.hpp"

#include <chrono>
#include <thread>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "sandpaper/runtime/envelope_source.hpp"
#include "sandpaper/runtime/owning_source.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"

namespace sandpaper::experiment {
namespace {

using PatchSource = runtime::OwningSource<schema::PatchProgram, runtime::PatchEvaluator>;


}  // namespace

VirtualPresenter::VirtualPresenter(runtime::DeviceLimits limits, runtime::HandScript hand, PresentOptions options)
    : limits_(std::move(limits)), hand_(hand), options_(options) {
  // Refuse a rate the device cannot take now, before a results folder is made, not at the first trial.
  runtime::ServoConfig probe;
  probe.rate_hz = options_.rate_hz;
  probe.duration_s = 2 * options_.ramp_s + options_.hold_s;
  probe.ramp_s = 0;
  runtime::validate_config(probe, limits_);
}

std::string VirtualPresenter::describe() const {
  return fmt::format("simulated joystick on the virtual clock, hand scanning at {:g} mm/s over +-{:g} mm, {:g} Hz",
                     hand_.speed_m_s * 1e3, hand_.amplitude_m * 1e3, options_.rate_hz);
}

Presentation VirtualPresenter::present(std::shared_ptr<const schema::PatchProgram> program, double gain) {
  runtime::EnvelopeSource source(std::make_unique<PatchSource>(std::move(program)), options_.ramp_s, options_.hold_s, gain);
  runtime::SimJoystick device(limits_, hand_, 0);
  runtime::VirtualClock clock;
  runtime::ServoConfig config;
  config.rate_hz = options_.rate_hz;
  config.duration_s = source.length_s();
  config.ramp_s = 0;  // the envelope ramps
  const auto report = runtime::run_servo_loop(device, source, clock, config);
  Presentation p;
  p.felt_max_N = report.felt_max_lateral_force_N;
  p.interrupted = report.stop_cause != runtime::StopCause::Completed;
  if (p.interrupted) p.cause = runtime::stop_cause_name(report.stop_cause);
  return p;
}

LivePresenter::LivePresenter(std::unique_ptr<runtime::Device> device, std::string description, PresentOptions options)
    : device_(std::move(device)), description_(std::move(description)), options_(options), source_(nullptr),
      ring_(1 << 16) {
  config_.rate_hz = options_.rate_hz;
  config_.deadline_guard_periods = options_.deadline_guard_periods;
  config_.velocity_limit_m_s = options_.velocity_limit_m_s;
  config_.duration_s = 0;  // until the session stops it
  config_.stop_request = &stop_;
  config_.telemetry = &ring_;
  thread_.start_nonrt(*device_, source_, config_);
}

LivePresenter::~LivePresenter() {
  stop_.store(true, std::memory_order_release);
  if (!stopped_) {
    try {
      thread_.join_nonrt();
    } catch (...) {
    }
  }
}

Presentation LivePresenter::present(std::shared_ptr<const schema::PatchProgram> program, double gain) {
  Presentation p;
  if (stopped_ || thread_.finished()) {
    if (!stopped_) report_ = thread_.join_nonrt();
    stopped_ = true;
    p.interrupted = true;
    p.cause = runtime::stop_cause_name(report_.stop_cause);
    return p;
  }
  auto picked = std::make_shared<std::atomic<bool>>(false);
  auto envelope = std::make_unique<runtime::EnvelopeSource>(std::make_unique<PatchSource>(std::move(program), picked),
                                                            options_.ramp_s, options_.hold_s, gain);
  const double length = envelope->length_s();
  runtime::TelemetryRecord r;
  while (ring_.pop_nonrt(r)) {
  }
  source_.offer_nonrt(std::move(envelope));
  bool started = false;
  double t0 = 0;
  for (;;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    if (options_.stop && options_.stop->load()) stop_.store(true, std::memory_order_release);
    const bool is_picked = picked->load(std::memory_order_acquire);
    while (ring_.pop_nonrt(r)) {
      if (!is_picked) continue;
      if (!started) {
        started = true;
        t0 = r.t_s;
      }
      p.felt_max_N = std::max(p.felt_max_N, glm::length(r.force_N));
      if (r.t_s - t0 >= length) {
        source_.collect_retired_nonrt();
        return p;
      }
    }
    if (thread_.finished()) {
      report_ = thread_.join_nonrt();
      stopped_ = true;
      p.interrupted = true;
      p.cause = runtime::stop_cause_name(report_.stop_cause);
      return p;
    }
  }
}

}  // namespace sandpaper::experiment

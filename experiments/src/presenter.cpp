#include "sandpaper/experiment/presenter.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "sandpaper/runtime/devices/builtin_devices.hpp"
#include "sandpaper/runtime/devices/open_device.hpp"
#include "sandpaper/runtime/envelope_source.hpp"

namespace sandpaper::experiment {
namespace {

runtime::ServoConfig presentation_config(const PresentOptions& options) {
  runtime::ServoConfig config;
  config.rate_hz = options.rate_hz;
  config.duration_s = 2 * options.ramp_s + options.hold_s;
  config.ramp_s = 0;  // the envelope ramps
  return config;
}

}  // namespace

VirtualPresenter::VirtualPresenter(DeviceOpener open, std::string description, PresentOptions options)
    : open_(std::move(open)), description_(std::move(description)), options_(options) {
  // Refuse a rate the device cannot take now, before a results folder is made, not at the first trial.
  const auto device = open_();
  if (!device->follows_virtual_clock())
    throw std::invalid_argument("device '" + device->limits().name + "' cannot play on the virtual clock");
  runtime::validate_config(presentation_config(options_), device->limits());
}

VirtualPresenter::VirtualPresenter(runtime::HandScript hand, PresentOptions options)
    : VirtualPresenter(
          [hand] {
            runtime::DeviceSpec spec;
            spec.script = hand;
            spec.virtual_clock = true;
            return runtime::open_device(runtime::builtin_devices(), std::move(spec)).device;
          },
          fmt::format("simulated joystick on the virtual clock, hand scanning at {:g} mm/s over +-{:g} mm, {:g} Hz",
                      hand.speed_m_s * 1e3, hand.amplitude_m * 1e3, options.rate_hz),
          options) {}

Presentation VirtualPresenter::present(std::shared_ptr<const schema::PatchProgram> program, double gain) {
  const auto device = open_();
  runtime::LiveServo::Options host_options;
  host_options.telemetry_records = 0;  // the report's felt maximum is all a trial needs
  auto source = std::make_unique<runtime::EnvelopeSource>(runtime::patch_source_for(*device, std::move(program)),
                                                          options_.ramp_s, options_.hold_s, gain);
  runtime::ServoConfig config = presentation_config(options_);
  config.duration_s = source->length_s();
  runtime::LiveServo host(*device, std::move(source), host_options);
  const auto report = host.run_virtual_nonrt(config);
  Presentation p;
  p.felt_max_N = report.felt_max_lateral_force_N;
  p.interrupted = report.stop_cause != runtime::StopCause::Completed;
  if (p.interrupted) p.cause = runtime::stop_cause_name(report.stop_cause);
  return p;
}

namespace {

runtime::LiveServo::Options live_host_options() {
  runtime::LiveServo::Options o;
  o.telemetry_records = 1 << 16;
  return o;
}

}  // namespace

LivePresenter::LivePresenter(std::unique_ptr<runtime::Device> device, std::string description, PresentOptions options)
    : device_(std::move(device)), description_(std::move(description)), options_(options),
      host_(*device_, nullptr, live_host_options()) {
  runtime::ServoConfig config;
  config.rate_hz = options_.rate_hz;
  config.deadline_guard_periods = options_.deadline_guard_periods;
  config.velocity_limit_m_s = options_.velocity_limit_m_s;
  config.duration_s = 0;  // until the session stops it
  host_.start_nonrt(config);
}

// The host stops the run (zero force written last) and joins it.
LivePresenter::~LivePresenter() = default;

Presentation LivePresenter::present(std::shared_ptr<const schema::PatchProgram> program, double gain) {
  Presentation p;
  const auto interrupted = [&] {
    if (!stopped_) report_ = host_.join_nonrt();
    stopped_ = true;
    p.interrupted = true;
    p.cause = runtime::stop_cause_name(report_.stop_cause);
    return p;
  };
  if (stopped_ || host_.finished()) return interrupted();
  auto picked = std::make_shared<std::atomic<bool>>(false);
  auto envelope = std::make_unique<runtime::EnvelopeSource>(host_.patch_source_nonrt(std::move(program), picked),
                                                            options_.ramp_s, options_.hold_s, gain);
  const double length = envelope->length_s();
  runtime::TelemetryRing& ring = *host_.telemetry();
  runtime::TelemetryRecord r;
  while (ring.pop_nonrt(r)) {
  }
  host_.offer_nonrt(std::move(envelope));
  bool started = false;
  double t0 = 0;
  for (;;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    if (options_.stop && options_.stop->load()) host_.request_stop_nonrt();
    const bool is_picked = picked->load(std::memory_order_acquire);
    while (ring.pop_nonrt(r)) {
      if (!is_picked) continue;
      if (!started) {
        started = true;
        t0 = r.t_s;
      }
      p.felt_max_N = std::max(p.felt_max_N, glm::length(r.force_N));
      if (r.t_s - t0 >= length) {
        host_.collect_retired_nonrt();
        return p;
      }
    }
    if (host_.finished()) return interrupted();
  }
}

}  // namespace sandpaper::experiment

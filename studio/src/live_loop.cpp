#include "sandpaper/studio/live_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>

#include "sandpaper/runtime/owning_source.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/workspace_evaluator.hpp"

namespace sandpaper::studio {
namespace {

// Ticks the ring holds between the supervisor's drains (every 10 ms): 0.65 s at 10 kHz.
constexpr std::size_t kRingRecords = 1 << 13;

template <class Program, class Evaluator>
using TrackedSource = runtime::OwningSource<Program, Evaluator>;

runtime::LiveServo::Options host_options(const LoopOptions& options) {
  runtime::LiveServo::Options o;
  o.telemetry_records = kRingRecords;
  o.crossfade_s = options.crossfade_s;
  return o;
}

}  // namespace

LiveLoop::LiveLoop(std::unique_ptr<runtime::Device> device, runtime::DummyJoystick* dummy, LoopOptions options)
    : device_(std::move(device)),
      dummy_(dummy),
      options_(options),
      host_(*device_, nullptr, host_options(options)) {
  const std::atomic<bool> probe_stop{false};
  runtime::ServoConfig probe;
  probe.rate_hz = options_.rate_hz;
  probe.duration_s = 0;  // until stopped, as the loop will run
  probe.stop_request = &probe_stop;
  runtime::validate_config(probe, device_->limits());
}

LiveLoop::~LiveLoop() { stop_nonrt(); }

void LiveLoop::start_nonrt() {
  if (started_) return;
  started_ = true;
  supervisor_ = std::thread([this] { supervise(); });
}

void LiveLoop::stop_nonrt() {
  if (!started_) return;
  quitting_.store(true);
  host_.request_stop_nonrt();  // the supervisor asks again, should a restart have begun meanwhile
  if (supervisor_.joinable()) supervisor_.join();
  started_ = false;
}

std::uint64_t LiveLoop::load_nonrt(std::shared_ptr<const schema::PatchProgram> program, double roughness) {
  auto playing = std::make_shared<std::atomic<bool>>(false);
  // Built here: the evaluator's allocations and checks happen on this thread (throws on a bad program).
  auto source = host_.patch_source_nonrt(program, playing);
  std::lock_guard offer_lock(offer_mutex_);
  std::uint64_t version;
  {
    std::lock_guard lock(mutex_);
    version = ++offered_;
    pending_.push_back({version, playing, program->name, program->max_lateral_force_N, roughness});
  }
  host_.offer_nonrt(std::move(source));
  return version;
}

std::uint64_t LiveLoop::load_workspace_nonrt(std::shared_ptr<const schema::WorkspaceProgram> workspace) {
  auto playing = std::make_shared<std::atomic<bool>>(false);
  auto source = std::make_unique<TrackedSource<schema::WorkspaceProgram, runtime::WorkspaceEvaluator>>(workspace, playing);
  double force = 0;
  for (const auto& p : workspace->patches) force = std::max(force, p.program->max_lateral_force_N);
  std::lock_guard offer_lock(offer_mutex_);
  std::uint64_t version;
  {
    std::lock_guard lock(mutex_);
    version = ++offered_;
    pending_.push_back({version, playing, workspace->name, force, 0});
  }
  host_.offer_nonrt(std::move(source));
  return version;
}

std::optional<glm::dvec2> LiveLoop::set_hand_nonrt(double x_mm, double y_mm) {
  if (!dummy_) return std::nullopt;
  return dummy_->set_target_nonrt({x_mm * 1e-3, y_mm * 1e-3}) * 1e3;
}

void LiveLoop::promote_locked() {
  // The newest pending load the servo thread has picked up is what plays now; older ones never will.
  for (auto it = pending_.rbegin(); it != pending_.rend(); ++it)
    if (it->playing->load(std::memory_order_acquire)) {
      state_.material = it->name;
      state_.material_version = it->version;
      state_.compiled_max_lateral_force_N = it->force;
      state_.compiled_roughness = it->roughness;
      pending_.erase(pending_.begin(), it.base());
      return;
    }
}

LoopState LiveLoop::state_nonrt() {
  std::lock_guard lock(mutex_);
  // Here too, not only in the supervisor's drains: what plays is known the moment the servo thread
  // has picked it up.
  promote_locked();
  return state_;
}

void LiveLoop::supervise() {
  std::uint64_t tick_base = 0, overrun_base = 0;
  // (time, ticks) about every 10 ms over the last second, for the achieved rate; the largest |F| of
  // each drain over the last second, for the felt maximum.
  std::deque<std::pair<double, std::uint64_t>> rate_window;
  std::deque<std::pair<double, double>> force_window;
  double time_base = 0;
  while (!quitting_.load()) {
    runtime::ServoConfig cfg;
    cfg.rate_hz = options_.rate_hz;
    cfg.deadline_guard_periods = options_.deadline_guard_periods;
    cfg.velocity_limit_m_s = options_.velocity_limit_m_s;
    cfg.duration_s = 0;  // until stopped (the loop's memory does not grow with its length)
    runtime::TelemetryRing& ring = *host_.telemetry();
    host_.start_nonrt(cfg);
    {
      std::lock_guard lock(mutex_);
      state_.running = true;
    }
    runtime::TelemetryRecord record;
    while (!host_.finished()) {
      if (quitting_.load()) host_.request_stop_nonrt();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      double drain_max = 0;
      bool any = false;
      while (ring.pop_nonrt(record)) {
        any = true;
        drain_max = std::max(drain_max, std::hypot(record.force_N.x, record.force_N.y));
        if (record.overrun) ++overrun_base;
      }
      host_.collect_retired_nonrt();
      std::lock_guard lock(mutex_);
      promote_locked();
      if (!any) continue;
      const double t = time_base + record.t_s;
      state_.ticks = tick_base + record.tick + 1;
      state_.overruns = overrun_base;
      state_.telemetry_dropped = ring.dropped();
      state_.hand_mm = record.position_m * 1e3;
      state_.force_N = record.force_N;
      rate_window.emplace_back(t, state_.ticks);
      while (rate_window.size() > 2 && rate_window.front().first < t - 1.0) rate_window.pop_front();
      const auto& [t0, n0] = rate_window.front();
      if (t > t0) state_.rate_hz = static_cast<double>(state_.ticks - n0) / (t - t0);
      force_window.emplace_back(t, drain_max);
      while (!force_window.empty() && force_window.front().first < t - 1.0) force_window.pop_front();
      state_.felt_max_lateral_force_N = 0;
      for (const auto& f : force_window) state_.felt_max_lateral_force_N = std::max(state_.felt_max_lateral_force_N, f.second);
    }
    // Loads go on while it joins (and, after an unplug, waits to see whether the device comes back).
    const runtime::ServoReport report = host_.join_nonrt();
    std::lock_guard lock(mutex_);
    state_.running = false;
    state_.realtime = report.realtime_scheduling;
    tick_base += report.ticks;
    state_.ticks = std::max(state_.ticks, tick_base);
    time_base += static_cast<double>(report.ticks) / options_.rate_hz;
    if (quitting_.load()) break;
    state_.stop_cause = runtime::stop_cause_name(report.stop_cause);
    if (!options_.restart_after_fault) break;
    ++state_.restarts;
  }
}

}  // namespace sandpaper::studio

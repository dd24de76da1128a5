#include "sandpaper/shapes/scene_servo.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/dynamic_hand3.hpp"

namespace sandpaper::shapes {
namespace {

constexpr double kNsPerS = 1e9;
// The servo rates the runtime plays at (runtime::validate_config): the thesis' 900 Hz to 10 kHz.
constexpr double kMinRate_hz = 900.0, kMaxRate_hz = 10000.0;

std::string g_text(double v) {
  char out[32];
  std::snprintf(out, sizeof out, "%g", v);
  return out;
}

bool finite(const glm::dvec3& v) noexcept { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool zero(const glm::dvec3& v) noexcept { return v.x == 0 && v.y == 0 && v.z == 0; }

// The magnitude held to the maximum without turning the vector; one ulp at a time below it, as the
// 2-D loop's limit_magnitude does (a scaled force can round a few ulp above the maximum).
glm::dvec3 limit_magnitude(glm::dvec3 force, double max_force_N, bool& clamped) noexcept {
  const double magnitude = glm::length(force);
  clamped = magnitude > max_force_N;
  if (!clamped) return force;
  force *= max_force_N / magnitude;
  constexpr double kOneUlpLess = 1.0 - 0x1p-53;
  for (int i = 0; i < 64 && glm::length(force) > max_force_N; ++i) force *= kOneUlpLess;
  return force;
}

void validate(const SceneServoConfig& c, const DeviceLimits3& limits) {
  if (!(c.rate_hz >= kMinRate_hz && c.rate_hz <= kMaxRate_hz))
    throw std::invalid_argument("servo rate must be between 900 Hz and 10 kHz");
  if (!(c.rate_hz >= limits.min_rate_hz * (1 - 1e-9) && c.rate_hz <= limits.max_rate_hz * (1 + 1e-9)))
    throw std::invalid_argument("device '" + limits.name + "' runs between " + g_text(limits.min_rate_hz) + " and " +
                                g_text(limits.max_rate_hz) + " Hz");
  if (!(c.duration_s > 0) || !std::isfinite(c.duration_s) || std::llround(c.duration_s * c.rate_hz) < 1)
    throw std::invalid_argument("a 3-D servo run lasts a positive, finite time of at least one tick");
  if (!(c.velocity_cutoff_hz > 0) || !std::isfinite(c.velocity_cutoff_hz))
    throw std::invalid_argument("velocity filter cutoff must be a positive, finite frequency in Hz");
  if (!(c.velocity_limit_m_s > 0)) throw std::invalid_argument("velocity limit must be a positive speed in m/s");
  if (!(c.ramp_s >= 0) || !std::isfinite(c.ramp_s)) throw std::invalid_argument("ramp must be a finite time of 0 s or more");
}

}  // namespace

const char* scene_stop_name(SceneStop stop) noexcept {
  switch (stop) {
    case SceneStop::Completed: return "completed";
    case SceneStop::DeviceReadFailed: return "device_read_failed";
    case SceneStop::PositionNotFinite: return "position_not_finite";
    case SceneStop::ForceNotFinite: return "force_not_finite";
    case SceneStop::VelocityLimit: return "velocity_limit";
    case SceneStop::DeviceWriteFailed: return "device_write_failed";
  }
  return "unknown";
}

SceneServoSummary run_scene_servo(SceneForce renderer, Device3& device, const SceneServoConfig& config,
                                  runtime::ServoClock& clock) {
  const DeviceLimits3& limits = device.limits();
  validate(config, limits);
  if (dynamic_cast<runtime::VirtualClock*>(&clock) != nullptr && !device.follows_virtual_clock())
    throw std::invalid_argument("device '" + limits.name + "' moves in real time only: play it on the steady clock");
  const auto ticks = static_cast<std::uint64_t>(std::llround(config.duration_s * config.rate_hz));
  const double period_ns = kNsPerS / config.rate_hz;
  const double rc_s = 1.0 / (2.0 * std::numbers::pi * config.velocity_cutoff_hz);
  const double speed_limit_sq = config.velocity_limit_m_s * config.velocity_limit_m_s;

  SceneServoSummary s;
  s.rate_hz = config.rate_hz;
  glm::dvec3 velocity{0.0}, previous_x{0.0}, previous_c{0.0}, previous_tex{0.0};
  double previous_t = 0;
  double contact_work = 0, law = 0, texture_work = 0;  // sum C . dx, E and T so far (EnergyBalance3)

  const std::int64_t start = clock.now_ns();
  for (std::uint64_t k = 0; k < ticks && s.stop == SceneStop::Completed; ++k) {
    clock.sleep_until_ns(start + static_cast<std::int64_t>(std::llround(static_cast<double>(k) * period_ns)));
    const double t = static_cast<double>(clock.now_ns() - start) / kNsPerS;
    ++s.ticks;
    s.duration_s = t;
    glm::dvec3 x{0.0}, sent{0.0}, texture{0.0};
    if (!device.read_position_rt(t, x)) {
      s.stop = SceneStop::DeviceReadFailed;
    } else if (!finite(x)) {
      s.stop = SceneStop::PositionNotFinite;
    } else {
      if (k == 0) {
        renderer.reset_rt(x);
      } else if (t > previous_t) {
        // First-order (RC) low-pass on the finite difference, over the measured interval (the 2-D
        // loop's FilteredDerivative).
        const double dt = t - previous_t;
        velocity += dt / (dt + rc_s) * ((x - previous_x) / dt - velocity);
      }
      if (!limits.workspace.contains(x)) ++s.ticks_outside_workspace;
      const double speed_sq = glm::dot(velocity, velocity);
      s.max_speed_m_s = std::max(s.max_speed_m_s, std::sqrt(speed_sq));
      // Checked before the renderer runs, so a runaway handle does not move the proxy either.
      if (speed_sq > speed_limit_sq) {
        s.stop = SceneStop::VelocityLimit;
      } else {
        glm::dvec3 force = renderer.update_rt(x, velocity);
        if (!finite(force)) {
          s.stop = SceneStop::ForceNotFinite;
        } else {
          if (config.ramp_s > 0 && t < config.ramp_s) {
            force *= t / config.ramp_s;
            ++s.ramped_ticks;
          }
          bool clamped = false;
          sent = limit_magnitude(force, limits.max_force_N, clamped);
          if (clamped) ++s.clamped_ticks;
          // The texture's share of what was sent: ramp and clamp scale the whole force alike.
          const double scale = clamped ? glm::length(sent) / glm::length(force) : 1.0;
          texture = renderer.texture_force_rt() * (scale * (config.ramp_s > 0 && t < config.ramp_s ? t / config.ramp_s : 1.0));
        }
      }
    }
    if (s.stop == SceneStop::Completed) {
      if (!device.write_force_rt(sent)) {
        s.stop = SceneStop::DeviceWriteFailed;
        sent = texture = glm::dvec3{0.0};
      }
    } else {
      device.write_force_rt(glm::dvec3{0.0});
    }
    if (s.stop != SceneStop::Completed) break;
    s.peak_force_N = std::max(s.peak_force_N, glm::length(sent));
    if (!zero(sent)) ++s.ticks_in_contact;
    // The port's energy over the interval the previous force was held (EnergyBalance3).
    const glm::dvec3 c = sent - texture;
    if (k > 0) {
      const glm::dvec3 dx = x - previous_x;
      contact_work += glm::dot(previous_c, dx);
      law += 0.5 * glm::dot(previous_c + c, dx);
      texture_work += glm::dot(previous_tex, dx);
      if (zero(previous_c) != zero(c)) s.energy.tolerance_J += 0.5 * glm::length(c - previous_c) * glm::length(dx);
    }
    if (zero(sent)) {
      ++s.energy.relaxed_ticks;
      s.energy.energy_gained_J = std::max(s.energy.energy_gained_J, law);
      s.energy.relaxed_environment_work_J = law;
    }
    previous_x = x;
    previous_c = c;
    previous_tex = texture;
    previous_t = t;
  }
  // Whatever ended the run, leave the handle unforced rather than holding the last command.
  device.write_force_rt(glm::dvec3{0.0});
  s.energy.work_on_handle_J = contact_work + texture_work;
  s.energy.environment_work_J = law;
  s.energy.hold_work_J = contact_work - law;
  s.energy.texture_work_J = texture_work;
  return s;
}

SceneServoSummary run_scene_servo(SceneForce renderer, Device3& device, double rate_hz, double seconds) {
  SceneServoConfig config;
  config.rate_hz = rate_hz;
  config.duration_s = seconds;
  SceneServoSummary s;
  if (device.follows_virtual_clock()) {
    runtime::VirtualClock clock;
    s = run_scene_servo(renderer, device, config, clock);
  } else {
    runtime::MonotonicClock clock;
    s = run_scene_servo(renderer, device, config, clock);
  }
  if (const auto* hand = dynamic_cast<const DynamicHand3*>(&device)) {
    const double free = free_hand_excursion_m(hand->path(), hand->model(), rate_hz, seconds);
    s.hand = judge_hand_run(*hand, s.peak_force_N, device.limits().max_force_N,
                            s.energy.hold_work_J + std::max(0.0, s.energy.texture_work_J), free);
  }
  return s;
}

}  // namespace sandpaper::shapes

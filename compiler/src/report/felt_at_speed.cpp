#include "sandpaper/compiler/felt_at_speed.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "sandpaper/compiler/patterns.hpp"
#include "sandpaper/compiler/textures.hpp"
#include "sandpaper/schema/grating_ridges.hpp"
#include "sandpaper/schema/no_coverage.hpp"

namespace sandpaper::compiler {
namespace {

// The runtime's read of the table at fractional sample index x (linear, wrapped): runtime/src/force_tables.cpp.
// Called for every tick of the walk below, so left out of the fuzzing build's coverage (no_coverage.hpp).
SANDPAPER_NO_COVERAGE double read(const std::vector<float>& t, double x) {
  const auto n = static_cast<double>(t.size());
  const double u = x - std::floor(x / n) * n;
  const double whole = std::floor(u);
  auto i = static_cast<std::size_t>(whole);
  const double frac = u - whole;
  if (i >= t.size()) i = 0;
  const double lo = t[i], hi = t[(i + 1) % t.size()];
  return lo + frac * (hi - lo);
}

// The largest sign * read(x) over x = x0, x0 + step, ... up to hi: what a servo reading the table
// once a tick, `step` samples apart, meets on one ridge. Under one sample a tick, read is linear
// between samples, so in each interval only the first and the last of the points in it can be the
// largest: the work is the ridge's width in samples, not width / step. A 500 m grating's step is
// 4e-5 of a sample at 20 mm/s, and that walk ran past 30 s; past about 2e11 m the step is under half
// the spacing of doubles near x, and it never ended (F40).
double best_on_lattice(const std::vector<float>& t, double sign, double x0, double step, double hi) {
  double best = 0;
  if (step >= 1) {
    for (double x = x0; x <= hi; x += step) best = std::max(best, sign * read(t, x));
    return best;
  }
  for (double i = std::floor(x0); i <= hi; ++i) {
    const double a = std::max(i, x0), b = std::min(i + 1, hi);
    const double j_first = std::ceil((a - x0) / step), j_last = std::floor((b - x0) / step);
    if (j_first > j_last) continue;
    best = std::max({best, sign * read(t, x0 + j_first * step), sign * read(t, x0 + j_last * step)});
  }
  return best;
}

// What a hand meets on a ridge the ticks read `best` on, with a steady force `damping_N` against
// its motion added. Scanning one way, the ridges whose force points against the motion rise to
// best + damping; the others fall to best - damping, and where they fall below it, the ridge's
// edges, where the grating's force is near zero, leave the damper's |F|. The two directions
// alternate, so each ridge counts once each way.
double with_damper(double best, double damping_N) {
  if (damping_N <= 0) return best;
  return 0.5 * ((best + damping_N) + std::max(damping_N, std::abs(best - damping_N)));
}

const schema::GratingTerm* first_grating(const schema::PatchProgram& p) {
  const schema::GratingTerm* g = nullptr;
  for (const auto& t : p.terms)
    if ((g = std::get_if<schema::GratingTerm>(&t))) break;
  if (!g || g->force_N.empty() || !(g->period_m > 0)) return nullptr;
  return g;
}

// The position the last of a chain of sample-and-holds carries at its sample y (table samples):
// each stage holds the latest sample of the stage before it.
double carried(double y, const std::vector<double>& step, const std::vector<double>& phase) {
  double x = y;
  for (std::size_t i = step.size() - 1; i-- > 0;) x = phase[i] + std::floor((x - phase[i]) / step[i]) * step[i];
  return x;
}

// The largest sign * read(x) a chain of sample-and-holds passes on with a ridge between lo and hi
// (table samples). Stage i samples the stage before it at phase[i] + k step[i] (stage 0 samples the
// hand's position); what the last stage holds reaches the motor. Each of the last stage's samples
// is traced back through the stages to the position it carries: a value a faster stage held for
// less than a slower one's step may never reach the motor, and one held long may reach it late.
double best_through_chain(const std::vector<float>& t, double sign, double lo, double hi, const std::vector<double>& step,
                          const std::vector<double>& phase) {
  const std::size_t last = step.size() - 1;
  double lag = 0;
  for (std::size_t i = 0; i < last; ++i) lag += step[i];
  const double first = phase[last] + std::ceil((lo - phase[last]) / step[last]) * step[last];
  double best = 0;
  for (double k = 0;; ++k) {
    const double y = first + k * step[last];
    if (y > hi + lag) break;
    const double x = carried(y, step, phase);
    if (x >= lo && x <= hi) best = std::max(best, sign * read(t, x));
  }
  return best;
}

// The last stage's samples best_through_chain walks per ridge at most; past it (stages far finer
// than the table's samples, or a very wide ridge) the slowest stage alone stands for the chain.
constexpr double kMaxChainWalk = 1 << 16;

// Phases for independent clocks, each in [0, 1): the R_d low-discrepancy sequence (Roberts 2018),
// so a few hundred tuples cover the stages' joint phases evenly.
class PhaseTuples {
 public:
  explicit PhaseTuples(std::size_t stages) : alpha_(stages) {
    double phi = 2;  // the generalised golden ratio: phi^(d+1) = phi + 1, by fixed-point iteration
    for (int i = 0; i < 64; ++i) phi = std::pow(1 + phi, 1.0 / static_cast<double>(stages + 1));
    double a = 1;
    for (auto& x : alpha_) x = (a /= phi);
  }
  // Tuple k scaled to each stage's step: where each stage's first sample falls (table samples).
  void phases(int k, const std::vector<double>& step, std::vector<double>& phase) const {
    phase.resize(alpha_.size());
    for (std::size_t i = 0; i < alpha_.size(); ++i) {
      const double v = 0.5 + (k + 1) * alpha_[i];
      phase[i] = (v - std::floor(v)) * step[i];
    }
  }

 private:
  std::vector<double> alpha_;
};

// A hand moving toward +x over `periods` periods of table `t` with a damper of `damping_N` against
// it, the force reaching the motor through the chain: the sum and count of the runs' peaks, where a
// run is what the motor applies from the first value of one sign to the first of the other (zeros
// do not end it) and its peak the largest |F - damping_N| in it, as the lab measures the firmware
// (usb-lab/measure.py, device_ridge_peaks). The first run and those past the last whole period's
// worth of `ridges` runs are left out: the walk cuts them, and ridges of either sign must count alike.
// The ridges' edges, where the damper alone acts, count only where a sample lands on them.
std::pair<double, int> run_peaks(const std::vector<float>& t, double damping_N, int periods, std::size_t ridges,
                                 const std::vector<double>& step, const std::vector<double>& phase) {
  const double end = static_cast<double>(periods) * static_cast<double>(t.size());
  std::vector<double> peaks;
  int sign = 0;
  for (double k = 0;; ++k) {
    const double y = phase.back() + k * step.back();
    if (y > end) break;
    const double f = read(t, carried(y, step, phase));
    const int s = f > 0 ? 1 : f < 0 ? -1 : 0;
    if (s != 0 && s != sign) peaks.push_back(0), sign = s;
    if (!peaks.empty()) peaks.back() = std::max(peaks.back(), std::abs(f - damping_N));
  }
  const std::size_t whole = peaks.size() < 2 ? 0 : (peaks.size() - 2) / ridges * ridges;
  double sum = 0;
  for (std::size_t i = 1; i <= whole; ++i) sum += peaks[i];
  return {sum, static_cast<int>(whole)};
}

constexpr int kPhases = 512;

// With a damper: the mean run peak over phases and both directions (run_peaks), or nothing when the
// walk finds no whole run.
std::optional<double> mean_run_peak(const std::vector<float>& table, std::size_t ridges, double damping_N, int periods,
                                    const std::vector<double>& step, const PhaseTuples& tuples) {
  // Scanning toward -x is scanning toward +x over the mirrored table, its force negated.
  std::vector<float> mirrored(table.size());
  for (std::size_t i = 0; i < table.size(); ++i) mirrored[i] = -table[(table.size() - i) % table.size()];
  const std::vector<float>* both_ways[] = {&table, &mirrored};
  std::vector<double> phase;
  double sum = 0;
  int runs = 0;
  for (int k = 0; k < kPhases; ++k) {
    tuples.phases(k, step, phase);
    for (const auto* t : both_ways) {
      const auto [ps, pc] = run_peaks(*t, damping_N, periods, ridges, step, phase);
      sum += ps, runs += pc;
    }
  }
  if (runs == 0) return std::nullopt;
  return sum / runs;
}

// The mean over ridges and phases of each ridge's best value through the chain, the damper taken
// off it (with_damper).
double mean_ridge_peak(const std::vector<float>& table, const std::vector<schema::GratingRidge>& ridges, double damping_N,
                       const std::vector<double>& step, const PhaseTuples& tuples) {
  if (ridges.empty()) return 0;
  const double slow = *std::max_element(step.begin(), step.end());
  double lag = 0;
  for (double s : step) lag += s;
  std::vector<double> phase;
  double sum = 0;
  for (const auto& r : ridges) {
    // The ridge's force lives between the zero-or-opposite samples on either side of it.
    const double lo = r.first - 1, hi = r.last + 1;
    if (step.size() == 1 || (hi - lo + lag) / step.back() > kMaxChainWalk) {
      for (int k = 0; k < kPhases; ++k)
        sum += with_damper(best_on_lattice(table, r.sign, lo + slow * (k + 0.5) / kPhases, slow, hi), damping_N);
      continue;
    }
    for (int k = 0; k < kPhases; ++k) {
      tuples.phases(k, step, phase);
      sum += with_damper(best_through_chain(table, r.sign, lo, hi, step, phase), damping_N);
    }
  }
  return sum / (kPhases * static_cast<double>(ridges.size()));
}

// Mean over ridges and phases of what a hand meets at speed v with the grating read through
// sample-and-holds at `chain_hz` (hand side first), with a damper of `damping_N(v)` against the
// motion (0: the reads alone).
template <class Damping>
std::vector<FeltAtSpeed> felt_with(const schema::GratingTerm& g, const std::vector<double>& speeds_m_s,
                                   const std::vector<double>& chain_hz, Damping damping_N) {
  std::vector<FeltAtSpeed> out;
  const auto& table = g.force_N;
  const auto n = static_cast<double>(table.size());
  const auto ridges = schema::grating_ridges(table);
  double continuous = 0;
  for (const auto& r : ridges) continuous += r.peak;
  continuous = ridges.empty() ? 0 : continuous / static_cast<double>(ridges.size());
  const double slowest_hz = *std::min_element(chain_hz.begin(), chain_hz.end());
  const PhaseTuples tuples(chain_hz.size());
  for (double v : speeds_m_s) {
    FeltAtSpeed f{v, slowest_hz, 0, 0};
    std::vector<double> step;  // each stage's travel between samples, in table samples
    for (double rate : chain_hz) step.push_back(v / rate / g.period_m * n);
    const double d = damping_N(v);
    // With a damper, which value reaches the motor decides whether a ridge's edge, where the damper
    // acts alone, is met at all: walk the runs both ways, unless even the slowest stage reads
    // finer than the table's samples (then every edge is met, and with_damper is exact).
    const double slow = *std::max_element(step.begin(), step.end());
    // Enough periods for 8 whole runs past the first, and for 64 of the slowest stage's samples: a
    // stage far slower than the ridges aliases them, and its runs are then long.
    const int periods = std::max(2 + static_cast<int>(std::ceil(8.0 / std::max(1.0, static_cast<double>(ridges.size())))),
                                 static_cast<int>(std::min(1e6, std::ceil(64 * slow / n))));
    std::optional<double> runs;
    if (d > 0 && !ridges.empty() && slow >= 1 && periods * n / step.back() <= kMaxChainWalk)
      runs = mean_run_peak(table, ridges.size(), d, periods, step, tuples);
    f.peak_N = runs ? *runs : mean_ridge_peak(table, ridges, d, step, tuples);
    f.fraction = continuous > 0 ? f.peak_N / continuous : 0;
    out.push_back(f);
  }
  return out;
}

}  // namespace

std::vector<FeltAtSpeed> felt_at_speed(const schema::PatchProgram& p, const std::vector<double>& speeds_m_s,
                                       const std::vector<double>& rates_hz) {
  const auto* g = first_grating(p);
  if (!g) return {};
  std::vector<FeltAtSpeed> out;
  for (double rate : rates_hz)
    for (const auto& f : felt_with(*g, speeds_m_s, {rate}, [](double) { return 0.0; })) out.push_back(f);
  return out;
}

std::vector<DeviceOutputAtSpeed> device_output_at_speed(const schema::PatchProgram& p,
                                                        const calibration::DeviceCalibration& device,
                                                        const std::vector<double>& speeds_m_s, const DeviceRates& rates) {
  std::vector<DeviceOutputAtSpeed> out;
  const auto* g = first_grating(p);
  if (!g || !device.has_firmware()) return out;
  // The hand moves along the grating's normal; each axis's damper acts on its part of the speed.
  const double nx = std::cos(g->orientation_rad), ny = std::sin(g->orientation_rad);
  const auto damping = [&](double v) {
    return device.firmware_damping_N(0, v * nx) * std::abs(nx) + device.firmware_damping_N(1, v * ny) * std::abs(ny);
  };
  const double servo = rates.servo_hz > 0 ? rates.servo_hz : default_servo_rate_hz(device);
  // A grating along an axis changes that axis's force alone; at an angle both change, and the
  // driver sends each axis that changed in its own transfer, one per bus interval.
  const int axes_driven = (std::abs(nx) > 1e-9 ? 1 : 0) + (std::abs(ny) > 1e-9 ? 1 : 0);
  const double command = rates.command_hz > 0               ? rates.command_hz
                         : device.usb_out_interval_s > 0 ? 1 / device.usb_out_interval_s / std::max(1, axes_driven)
                                                          : 0;
  std::vector<double> ticks;
  if (rates.position_hz > 0) ticks.push_back(rates.position_hz);
  ticks.push_back(servo);
  std::vector<double> chain = ticks;
  if (command > 0) chain.push_back(command);
  chain.push_back(device.firmware.update_rate_hz);
  const auto commanded = felt_with(*g, speeds_m_s, ticks, [](double) { return 0.0; });
  const auto output = felt_with(*g, speeds_m_s, chain, damping);
  for (std::size_t i = 0; i < speeds_m_s.size(); ++i) {
    DeviceOutputAtSpeed o;
    o.speed_m_s = speeds_m_s[i];
    o.rate_hz = *std::min_element(chain.begin(), chain.end());
    o.servo_rate_hz = servo;
    o.position_rate_hz = rates.position_hz > 0 ? rates.position_hz : servo;
    o.command_rate_hz = command > 0 ? command : servo;
    o.update_rate_hz = device.firmware.update_rate_hz;
    o.commanded_peak_N = commanded[i].peak_N;
    o.damping_N = damping(speeds_m_s[i]);
    o.peak_N = output[i].peak_N;
    out.push_back(o);
  }
  return out;
}

double default_servo_rate_hz(const calibration::DeviceCalibration& device) {
  return std::clamp(1000.0, device.min_rate_hz, device.max_rate_hz);
}

namespace {

std::string fmt(double v, int digits = 3) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

// `m`'s grating rebuilt with Gaussian sigma `sigma_m`, the way codegen builds it (float, or the 8-bit seed).
schema::PatchProgram rebuilt(const ResolvedGrating& g, const ResolvedMaterial& m, double sigma_m, double max_force_N) {
  schema::PatchProgram p;
  if (m.quantize_bits)
    p.terms.emplace_back(make_seed_grating(g.period.si, g.hill.si, g.orientation.si, sigma_m / g.period.si * kSeedPixels,
                                           static_cast<int>(m.quantize_bits->si), max_force_N));
  else
    p.terms.emplace_back(make_grating(g.period.si, g.hill.si, g.orientation.si, sigma_m, max_force_N));
  return p;
}

}  // namespace

FeltRemedies felt_remedies(const ResolvedMaterial& m, const schema::PatchProgram& p, double speed_m_s, double rate_hz,
                           double fast_rate_hz, double weber_fraction) {
  FeltRemedies r;
  const auto* g = std::get_if<ResolvedGrating>(&m.texture);
  const auto felt = felt_at_speed(p, {speed_m_s}, {rate_hz});
  if (!g || felt.empty()) return r;
  r.speed_m_s = speed_m_s;
  r.rate_hz = rate_hz;
  r.now = felt.front();
  if (fast_rate_hz > rate_hz) {
    r.fast_rate_hz = fast_rate_hz;
    r.fast = felt_at_speed(p, {speed_m_s}, {fast_rate_hz}).front();
  }
  // The least sigma (bisection between the compiled one and a quarter period) within half a JND.
  const double target = 1 - weber_fraction / 2;
  const double force = p.max_lateral_force_N;
  const double start = g->smoothing ? g->smoothing->si : g->period.si * kSeedSigmaPerPeriod;
  double lo = start, hi = g->period.si / 4;
  const auto fraction_at = [&](double sigma) { return felt_at_speed(rebuilt(*g, m, sigma, force), {speed_m_s}, {rate_hz}).front(); };
  if (!(hi > lo) || fraction_at(hi).fraction < target) return r;
  for (int i = 0; i < 30 && hi - lo > 1e-3 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (fraction_at(mid).fraction >= target ? hi : lo) = mid;
  }
  // Rounded up to a stated length (micrometres), then measured as it will be compiled.
  r.smoothing_m = std::ceil(hi * 1e6) * 1e-6;
  r.smoothed = fraction_at(r.smoothing_m);
  return r;
}

void warn_felt_at_speed(const ResolvedMaterial& m, const schema::PatchProgram& p, const calibration::CalibrationSet& cal,
                        const calibration::DeviceCalibration& device, Diagnostics& diags) {
  const auto* g = std::get_if<ResolvedGrating>(&m.texture);
  if (!g || !(p.max_lateral_force_N > 0)) return;
  const double weber = cal.knowledge().force_jnd.weber_fraction;
  const double rate = default_servo_rate_hz(device);
  const auto felt = felt_at_speed(p, kCommonHandSpeeds_m_s, {rate});
  const FeltAtSpeed* worst = nullptr;
  for (const auto& f : felt)
    if (f.fraction < 1 - weber && (!worst || f.fraction < worst->fraction)) worst = &f;
  if (!worst) return;
  const auto& map = cal.roughness_map();
  const auto r = felt_remedies(m, p, worst->speed_m_s, rate, std::max(rate, device.max_rate_hz), weber);
  const std::string at = fmt(worst->speed_m_s * 1e3) + " mm/s";
  std::string help;
  if (r.fast_rate_hz > 0)
    help += "play at " + fmt(r.fast_rate_hz, 6) + " Hz (`run --rate " + fmt(r.fast_rate_hz, 6) + "`): " + fmt(r.fast.peak_N) +
            " N felt at " + at + ", roughness " + fmt(map.percept_of(r.fast.peak_N)) + "; ";
  if (r.smoothing_m > 0)
    help += "or widen the walls for " + at + " with `smoothing " + fmt(r.smoothing_m * 1e3, 3) + " mm` on the grating: " +
            fmt(r.smoothed.peak_N) + " N felt, roughness " + fmt(map.percept_of(r.smoothed.peak_N));
  else
    help += "no smoothing up to a quarter of the period keeps it within half a JND at " + at;
  diags.warning("W0350", g->location,
                "at " + at + ", a common hand speed, the " + fmt(rate, 6) + " Hz servo on " + device.name +
                    " reads this grating's force walls at " + fmt(worst->peak_N) + " N of the " + fmt(p.max_lateral_force_N) +
                    " N compiled (" + fmt(worst->fraction * 100) + " %): more than one force JND (" + fmt(weber * 100) +
                    " %) is lost, so it feels like roughness " + fmt(map.percept_of(worst->peak_N)) + ", not " +
                    fmt(p.roughness),
                help);
}

std::vector<FeltAtSpeed> felt_at_explain_speeds(const schema::PatchProgram& p, double device_rate_hz) {
  std::vector<double> rates{device_rate_hz};
  if (device_rate_hz != 10000) rates.push_back(10000);
  return felt_at_speed(p, {0.02, 0.05, 0.1, 0.2}, rates);
}

void check_design_speed(double design_speed_m_s) {
  if (!(std::isfinite(design_speed_m_s) && design_speed_m_s >= 0))
    throw std::invalid_argument("a design speed must be a finite hand speed above 0 m/s (0: none), not " +
                                std::to_string(design_speed_m_s));
}

}  // namespace sandpaper::compiler

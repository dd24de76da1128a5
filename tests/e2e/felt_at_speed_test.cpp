// The force a hand really feels at speed (issue 15): explain's prediction (compiler/felt_at_speed.hpp)
// against the simulated joystick. A scan whose half-width is not a whole number of ticks' travel
// starts every stroke at another phase; per stroke, every ridge (period and sign) of the grating
// gets the largest |F| a tick read on it, 0 if none landed; the mean over ridges and strokes is the
// measured mean peak over many phases.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <sstream>
#include <tuple>

#include <gtest/gtest.h>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/felt_at_speed.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "test_support.hpp"

using namespace sandpaper;

namespace {

double measured_mean_peak(const schema::PatchProgram& p, double speed_m_s, double rate_hz, int strokes) {
  const double period = std::get<schema::GratingTerm>(p.terms.at(0)).period_m;
  runtime::HandScript scan;
  scan.speed_m_s = speed_m_s;
  scan.amplitude_m = 0.0300123;  // 60.0246 mm strokes: no whole number of ticks' travel at these speeds
  const double duration = strokes * 2 * scan.amplitude_m / speed_m_s;
  runtime::ServoConfig cfg;
  cfg.rate_hz = rate_hz;
  cfg.duration_s = duration;
  cfg.ramp_s = 0;  // the start ramp would scale the first ridges
  const auto ticks = static_cast<std::size_t>(std::llround(duration * rate_hz)) + 2;
  runtime::SimJoystick sim(runtime::sim_device_limits(), scan, ticks);
  runtime::PatchEvaluator ev(p);
  runtime::VirtualClock clock;
  EXPECT_EQ(runtime::run_servo_loop(sim, ev, clock, cfg).stop_reason, "completed");
  const auto& rec = sim.records();
  // (stroke, period, sign) -> the largest |F| read there.
  std::map<std::tuple<int, long, int>, double> peak;
  int stroke = 0;
  double lo = rec.front().position_m.x, hi = lo;
  std::vector<std::pair<double, double>> ranges;
  for (std::size_t k = 0; k < rec.size(); ++k) {
    const double x = rec[k].position_m.x, f = rec[k].force_N.x;
    if (k >= 2 && (x - rec[k - 1].position_m.x) * (rec[k - 1].position_m.x - rec[k - 2].position_m.x) < 0) {
      ranges.emplace_back(lo, hi);
      ++stroke;
      lo = hi = rec[k - 1].position_m.x;
    }
    lo = std::min(lo, x);
    hi = std::max(hi, x);
    if (f != 0) {
      auto& m = peak[{stroke, static_cast<long>(std::floor(x / period)), f > 0 ? 1 : -1}];
      m = std::max(m, std::abs(f));
    }
  }
  // Every ridge of every period a stroke crossed whole counts, read or not; the first and last
  // strokes (half strokes, or cut by the end) are left out.
  double sum = 0;
  std::size_t count = 0;
  for (int s = 1; s + 1 < static_cast<int>(ranges.size()); ++s) {
    const auto [a, b] = ranges[static_cast<std::size_t>(s)];
    for (long q = static_cast<long>(std::ceil(a / period)); static_cast<double>(q + 1) * period <= b; ++q)
      for (int sign : {1, -1}) {
        const auto it = peak.find({s, q, sign});
        sum += it == peak.end() ? 0.0 : it->second;
        ++count;
      }
  }
  EXPECT_GT(count, 100u);
  return count ? sum / static_cast<double>(count) : 0;
}

}  // namespace

TEST(FeltAtSpeed, PredictionMatchesTheSimulatedJoystick) {
  for (const char* text : {"grating period 0.7 mm; roughness 0.5", "roughness 0.6; grating period 2.5 mm", "a10p25"}) {
    auto r = test::shipped_compiler().compile_text(text);
    ASSERT_TRUE(r.ok()) << text;
    for (double v : {0.02, 0.05, 0.1, 0.2}) {
      const auto predicted = compiler::felt_at_speed(*r.program, {v}, {1000}).at(0);
      const double measured = measured_mean_peak(*r.program, v, 1000, 24);
      EXPECT_NEAR(predicted.peak_N, measured, 0.05 * measured) << text << " at " << v * 1e3 << " mm/s";
      EXPECT_LE(predicted.fraction, 1 + 1e-9);
    }
  }
}

// The measurement that filed the issue: a 0.7 mm grating at 50 mm/s loses a large share of its peak at
// 1 kHz (0.47 N of 1.50 N at the worst phase, the scan that starts on a wall's centre; about 72 % on
// average over phases), and a 10 kHz servo gets it back.
TEST(FeltAtSpeed, FineGratingAtSpeedLosesItsPeakAndAFasterServoRestoresIt) {
  auto r = test::shipped_compiler().compile_text("grating period 0.7 mm; roughness 0.5");
  ASSERT_TRUE(r.ok());
  const auto felt = compiler::felt_at_speed(*r.program, {0.05}, {1000, 10000});
  EXPECT_LT(felt[0].fraction, 0.8);
  EXPECT_GT(felt[1].fraction, 0.9);
  // Slow enough, nothing is lost.
  EXPECT_GT(compiler::felt_at_speed(*r.program, {0.001}, {1000})[0].fraction, 0.98);
}

// A grating far longer than a tick's travel (F40): at 20 mm/s and 1 kHz a 500 m period moves 4e-5 of
// a table sample a tick, and a 1e12 m one (the largest quantity) 2e-14, under half the spacing of
// doubles near the ridge. The prediction walked every tick across each ridge, so the compile ran
// past 30 s, or never ended; it walks the table's samples now. Nothing is lost at such steps:
// the felt peak is the compiled one.
TEST(FeltAtSpeed, AGratingFarLongerThanATicksTravelIsPredictedAndCompiles) {
  for (const char* text : {"grating period 500 m amplitude 1 N", "grating period 1e12 m amplitude 1 N"}) {
    auto r = test::shipped_compiler().compile_text(text);
    ASSERT_TRUE(r.ok()) << text << "\n" << compiler::format_diagnostics(r.diagnostics);
    for (const auto& f : compiler::felt_at_explain_speeds(*r.program, 1000)) {
      EXPECT_GT(f.fraction, 0.999) << text << " at " << f.speed_m_s << " m/s, " << f.rate_hz << " Hz";
      EXPECT_LE(f.fraction, 1 + 1e-9) << text;
    }
  }
}

// The two ways the prediction walks a ridge (every tick's point for a tick of a sample or more; the
// first and last points in each sample's interval under one) agree where they meet.
TEST(FeltAtSpeed, TheWalkJustUnderASampleATickAgreesWithTheWalkJustOver) {
  auto r = test::shipped_compiler().compile_text("grating period 0.7 mm; roughness 0.5");
  ASSERT_TRUE(r.ok());
  const auto& g = std::get<schema::GratingTerm>(r.program->terms.at(0));
  const double per_sample_m_s = g.period_m / static_cast<double>(g.force_N.size()) * 1000;  // a sample a tick at 1 kHz
  const auto under = compiler::felt_at_speed(*r.program, {0.999 * per_sample_m_s}, {1000}).at(0);
  const auto over = compiler::felt_at_speed(*r.program, {1.001 * per_sample_m_s}, {1000}).at(0);
  EXPECT_NEAR(under.peak_N, over.peak_N, 1e-3 * over.peak_N);
}

// W0350 and its remedies, each played: the smoothing it offers keeps the measured felt peak within
// half a force JND at the speed it names, and so does the faster servo it offers.
TEST(FeltAtSpeed, WarningsRemediesHoldOnTheSimulatedJoystick) {
  const auto& c = test::shipped_compiler();
  auto fine = c.compile_text("grating period 0.7 mm; roughness 0.5");
  ASSERT_TRUE(fine.ok());
  EXPECT_EQ(test::codes(fine, compiler::Severity::Warning), std::vector<std::string>{"W0350"});
  const std::string text = compiler::format_diagnostics(fine.diagnostics);
  EXPECT_NE(text.find("run --rate 10000"), std::string::npos) << text;
  EXPECT_NE(text.find("smoothing "), std::string::npos) << text;
  const double weber = c.calibration().knowledge().force_jnd.weber_fraction;
  const auto r = compiler::felt_remedies(*fine.material, *fine.program, 0.1, 1000, 10000, weber);
  ASSERT_GT(r.smoothing_m, 0);
  ASSERT_EQ(r.fast_rate_hz, 10000);
  const double compiled = fine.program->max_lateral_force_N;
  // The faster servo, played.
  EXPECT_GE(measured_mean_peak(*fine.program, 0.1, 10000, 6), (1 - weber / 2) * compiled * 0.98);
  // The wider walls, compiled as the warning writes them and played at the device's rate.
  std::ostringstream smoothed;
  smoothed << "grating period 0.7 mm smoothing " << r.smoothing_m * 1e3 << " mm; roughness 0.5";
  auto wide = c.compile_text(smoothed.str());
  ASSERT_TRUE(wide.ok()) << smoothed.str();
  EXPECT_NEAR(wide.program->max_lateral_force_N, compiled, 1e-9 * compiled);  // the target is kept
  EXPECT_GE(measured_mean_peak(*wide.program, 0.1, 1000, 24), (1 - weber / 2) * compiled * 0.98);
  // At 50 mm/s (slower) it loses less still: no warning for it.
  EXPECT_TRUE(test::codes(wide, compiler::Severity::Warning).empty()) << compiler::format_diagnostics(wide.diagnostics);
  // A wide grating loses nothing worth a JND: no warning.
  EXPECT_TRUE(test::codes(c.compile_text("grating period 10 mm; roughness 0.5"), compiler::Severity::Warning).empty());
}

namespace {

// A grating of amplitude 1 N whose force is zero where |sin| < `flat` (the flat tops and floors of a
// hill below 100 %), else the sine.
double grating_N(double x, double period_m, double flat) {
  const double v = std::sin(2 * M_PI * x / period_m);
  return std::abs(v) < flat ? 0.0 : v;
}

// A hand scanning that grating both ways at `speed_m_s`, read at `rate_hz`, with `damping_N`
// against its motion; each ridge is the half period where the sine has one sign, and its peak the
// largest |F| a tick meets there. Mean over ridges, both directions and 64 first-tick phases:
// explain's device-output measure, counted directly.
double scanned_with_damper(double period_m, double flat, double speed_m_s, double rate_hz, double damping_N) {
  const double step = speed_m_s / rate_hz, half = period_m / 2;
  const int ridges = 40;
  double sum = 0;
  int count = 0;
  for (int phase = 0; phase < 64; ++phase)
    for (int direction : {+1, -1}) {
      std::vector<double> peak(ridges, 0.0);
      for (double x = step * (phase + 0.5) / 64; x < ridges * half; x += step) {
        const double f = grating_N(x, period_m, flat) - direction * damping_N;
        auto& p = peak[static_cast<std::size_t>(x / half)];
        p = std::max(p, std::abs(f));
      }
      for (double p : peak) sum += p, ++count;
    }
  return sum / count;
}

// The same grating scanned both ways with the force on its way to the motor held by clocks of
// their own, counted event by event in time: positions reach the ticks at rates_hz[0], the ticks
// compute the grating's force at the latest position at rates_hz[1], commands carry the latest
// tick's force at rates_hz[2], and the firmware applies the latest command, with the damper against
// the motion, at rates_hz[3]. As the lab measures the firmware (usb-lab/measure.py): a run lasts
// from the first applied force of one sign to the first of the other (zeros do not end it), and
// its peak is the largest |F| applied in it. Each clock starts at a random phase (64 draws); the
// mean over the runs of 40 ridges, the first and last (cut by the scan's ends) left out.
double scanned_through_clocks(double period_m, double flat, double speed_m_s, const std::array<double, 4>& rates_hz,
                              double damping_N) {
  const double span = 20 * period_m, seconds = span / speed_m_s;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0, 1);
  double sum = 0;
  int count = 0;
  for (int draw = 0; draw < 64; ++draw)
    for (int direction : {+1, -1}) {
      std::array<double, 4> at;
      for (std::size_t i = 0; i < 4; ++i) at[i] = unit(random) / rates_hz[i];
      const double start = direction > 0 ? 0.0 : span;
      double position = start, tick_x = start, command_x = start;  // the position each stage holds, m
      std::vector<double> peaks;
      int sign = 0;
      for (;;) {
        const auto i = static_cast<std::size_t>(std::min_element(at.begin(), at.end()) - at.begin());
        const double t = at[i];
        if (t > seconds) break;
        at[i] += 1 / rates_hz[i];
        if (i == 0) position = start + direction * speed_m_s * t;
        else if (i == 1) tick_x = position;
        else if (i == 2) command_x = tick_x;
        else {
          const double f = grating_N(command_x, period_m, flat);
          const int s = f > 0 ? 1 : f < 0 ? -1 : 0;
          if (s != 0 && s != sign) peaks.push_back(0), sign = s;
          if (!peaks.empty()) peaks.back() = std::max(peaks.back(), std::abs(f - direction * damping_N));
        }
      }
      for (std::size_t r = 1; r + 1 < peaks.size(); ++r) sum += peaks[r], ++count;
    }
  return sum / count;
}

}  // namespace

// docs/USB_PID.md "The device's chain": a force reaching the motor through sample-and-holds on
// clocks of their own (positions, ticks, bus, firmware), against the scan counted event by event.
// The slower stages are far from each other and from the grating's ridges, and a ridge's edge,
// where the damper acts alone, reaches the motor only where a value carried through lands on it.
TEST(DeviceOutputAtSpeed, ThroughClocksOfTheirOwnMatchesAScanCountedEventByEvent) {
  schema::PatchProgram p;
  schema::GratingTerm g;
  g.period_m = 2e-3;
  const double flat = 0.3;
  for (int i = 0; i < 1024; ++i) g.force_N.push_back(static_cast<float>(grating_N(g.period_m * i / 1024, g.period_m, flat)));
  p.terms.emplace_back(g);
  calibration::DeviceCalibration d;
  d.axis[0].newtons_per_command_unit = d.axis[1].newtons_per_command_unit = 0.001;
  d.firmware.update_rate_hz = 999;
  for (double v : {0.05, 0.1})
    for (double damping_N : {0.0, 0.8}) {
      d.firmware.damping_command_s_per_m = damping_N / 0.001 / v;
      const compiler::DeviceRates rates{1000, 350, 180};
      const auto out = compiler::device_output_at_speed(p, d, {v}, rates);
      ASSERT_EQ(out.size(), 1u);
      EXPECT_DOUBLE_EQ(out[0].rate_hz, 180);
      EXPECT_DOUBLE_EQ(out[0].command_rate_hz, 180);
      EXPECT_DOUBLE_EQ(out[0].position_rate_hz, 350);
      const double counted = scanned_through_clocks(g.period_m, flat, v, {350, 1000, 180, 999}, damping_N);
      EXPECT_NEAR(out[0].peak_N, counted, 0.02 * counted) << v << " m/s, damper " << damping_N << " N";
      // The bus passes on less than the ticks command.
      if (damping_N == 0) {
        EXPECT_LT(out[0].peak_N, out[0].commanded_peak_N - 0.02) << v << " m/s";
      }
    }
}

// docs/USB_PID.md "The device's chain": the force a device outputs through its firmware, checked
// against the scan counted tick by tick, for a damper below half the grating's amplitude (it
// cancels between the ridges), between half and all of it, and above it, on a grating with flats
// between its ridges (ticks there meet the damper alone) and on a pure sine.
TEST(DeviceOutputAtSpeed, MatchesAScanWithTheFirmwaresDamperCountedTickByTick) {
  for (double flat : {0.3, 0.0}) {
    schema::PatchProgram p;
    schema::GratingTerm g;
    g.period_m = 2e-3;
    for (int i = 0; i < 1024; ++i) g.force_N.push_back(static_cast<float>(grating_N(g.period_m * i / 1024, g.period_m, flat)));
    p.terms.emplace_back(g);
    calibration::DeviceCalibration d;
    d.axis[0].newtons_per_command_unit = d.axis[1].newtons_per_command_unit = 0.001;
    d.firmware.update_rate_hz = 999;
    const double v = 0.05;
    for (double damping_N : {0.3, 0.8, 2.0}) {
      d.firmware.damping_command_s_per_m = damping_N / 0.001 / v;
      const auto out = compiler::device_output_at_speed(p, d, {v}, {1000});
      ASSERT_EQ(out.size(), 1u);
      EXPECT_DOUBLE_EQ(out[0].rate_hz, 999);  // the slower of servo and firmware
      EXPECT_NEAR(out[0].damping_N, damping_N, 1e-9);
      const double counted = scanned_with_damper(g.period_m, flat, v, 999, damping_N);
      EXPECT_NEAR(out[0].peak_N, counted, 0.01 * counted) << "damper " << damping_N << " N";
    }
    // Below half the amplitude the damper adds nothing to the mean; above it, it adds: the ridges
    // against the motion rise to 1 + 2 N, the others' edges meet 2 N (a little less on a pure sine,
    // whose ticks nearest a zero crossing still read some of the grating).
    d.firmware.damping_command_s_per_m = 0.3 / 0.001 / v;
    EXPECT_NEAR(compiler::device_output_at_speed(p, d, {v}, {1000})[0].peak_N, 1.0, 0.01);
    d.firmware.damping_command_s_per_m = 2.0 / 0.001 / v;
    EXPECT_NEAR(compiler::device_output_at_speed(p, d, {v}, {1000})[0].peak_N, 2.5, 0.025);
    // Without [firmware] there is no device output to predict.
    d.firmware = {};
    EXPECT_TRUE(compiler::device_output_at_speed(p, d, {v}, {1000}).empty());
  }
}

// The bus stage's default: one force report per [usb] out_interval, each axis that changes in its
// own (docs/USB_PID.md "The device's chain"). A grating along x changes x alone; at 45 degrees both
// axes change and each gets every other interval. Without an interval the bus is not a stage.
TEST(DeviceOutputAtSpeed, TheBusCarriesOneReportPerIntervalSharedByTheAxesTheGratingDrives) {
  calibration::DeviceCalibration d;
  d.axis[0].newtons_per_command_unit = d.axis[1].newtons_per_command_unit = 0.001;
  d.firmware.update_rate_hz = 999;
  d.min_rate_hz = 900, d.max_rate_hz = 1000;
  for (double angle : {0.0, M_PI / 4}) {
    schema::PatchProgram p;
    schema::GratingTerm g;
    g.period_m = 2e-3;
    g.orientation_rad = angle;
    for (int i = 0; i < 256; ++i) g.force_N.push_back(static_cast<float>(std::sin(2 * M_PI * i / 256)));
    p.terms.emplace_back(g);
    d.usb_out_interval_s = 0;
    EXPECT_DOUBLE_EQ(compiler::device_output_at_speed(p, d, {0.05}, {}).at(0).command_rate_hz, 1000);  // every tick
    d.usb_out_interval_s = 1e-3;
    const auto out = compiler::device_output_at_speed(p, d, {0.05}, {});
    EXPECT_DOUBLE_EQ(out.at(0).command_rate_hz, angle == 0 ? 1000 : 500) << angle;
    EXPECT_DOUBLE_EQ(out.at(0).servo_rate_hz, 1000);
    EXPECT_DOUBLE_EQ(out.at(0).update_rate_hz, 999);
    EXPECT_DOUBLE_EQ(compiler::device_output_at_speed(p, d, {0.05}, {0, 0, 200}).at(0).command_rate_hz, 200);
  }
  // A bus far slower than the ridges (30 reports a second, 1.7 mm apart on a 0.7 mm grating)
  // aliases them: what reaches the motor is still a force, at least the damper on the ridges
  // against the motion, never nothing.
  schema::PatchProgram p;
  schema::GratingTerm g;
  g.period_m = 0.7e-3;
  for (int i = 0; i < 256; ++i) g.force_N.push_back(static_cast<float>(std::sin(2 * M_PI * i / 256)));
  p.terms.emplace_back(g);
  d.firmware.damping_command_s_per_m = 0.5 / 0.001 / 0.05;
  const auto slow = compiler::device_output_at_speed(p, d, {0.05}, {0, 50, 30}).at(0);
  EXPECT_NEAR(slow.damping_N, 0.5, 1e-9);
  EXPECT_GE(slow.peak_N, slow.damping_N);
  EXPECT_LT(slow.peak_N, 1.5 + 1e-9);  // the grating's 1 N and the damper at most
}

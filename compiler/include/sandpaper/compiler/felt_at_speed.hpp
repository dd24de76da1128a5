#pragma once
// The peak lateral force a hand really feels crossing a grating at a given speed and servo rate
// (thesis 3.3.3: "update rates below approximately 1 kHz lead to degradation"). The ticks
// fall every v / f along the hand's path and the runtime interpolates the table between them, so a
// force pulse narrower than one tick's travel is stepped over.
#include <algorithm>
#include <vector>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

struct FeltAtSpeed {
  double speed_m_s = 0;  // hand speed along the grating normal, m/s
  double rate_hz = 0;    // servo rate, Hz
  double peak_N = 0;     // mean over ridges of the largest |F| a tick reads on each ridge, N
  double fraction = 0;   // peak_N / the same mean read continuously (1: nothing is lost)
};

// For the first grating term of `p` (empty without one): every (speed, rate) pair. A ridge is a run
// of force samples of one sign; its felt peak is the largest |F| any tick reads on it, averaged over
// the phase of the first tick (uniform over one tick's travel, 512 phases), with the runtime's linear
// interpolation; a ridge no tick lands on counts as 0. Pure; speeds and rates must be positive.
std::vector<FeltAtSpeed> felt_at_speed(const schema::PatchProgram& p, const std::vector<double>& speeds_m_s,
                                       const std::vector<double>& rates_hz);

// The rates a force passes through between the hand's position and the motor, Hz. Each is a
// sample-and-hold of the one before it, running on its own clock: positions reach the ticks, a tick
// computes the force at the latest position, a command carries the latest tick's force to the device,
// and the firmware applies the latest command at its updates (docs/USB_PID.md "The device's chain").
struct DeviceRates {
  double servo_hz = 0;     // the servo's ticks (0: default_servo_rate_hz)
  double position_hz = 0;  // new positions reaching the ticks (0: a new one every tick)
  double command_hz = 0;   // new commands reaching the firmware, per axis (0: the device's [usb] out_interval
                           // shared by the axes the grating drives; every tick without one)
};

// The force a device with its own firmware chain ([firmware] in its calibration file) outputs as a
// hand scans the first grating of `p` at each speed: the grating read through the chain of
// sample-and-holds of `rates`, plus the firmware's always-on damper against the motion, in the
// same measure as FeltAtSpeed (mean over ridges of each ridge's largest |F|, both scan
// directions, averaged over the stages' phases). Empty without a grating or without [firmware].
struct DeviceOutputAtSpeed {
  double speed_m_s = 0;
  double rate_hz = 0;           // the slowest of the rates below, Hz
  double servo_rate_hz = 0, position_rate_hz = 0, command_rate_hz = 0, update_rate_hz = 0;  // the chain's stages, Hz
  double commanded_peak_N = 0;  // what the ticks command (positions and ticks alone), N
  double damping_N = 0;         // the firmware's damper at this speed, N, against the motion
  double peak_N = 0;            // what the device outputs, N
};
std::vector<DeviceOutputAtSpeed> device_output_at_speed(const schema::PatchProgram& p,
                                                        const calibration::DeviceCalibration& device,
                                                        const std::vector<double>& speeds_m_s, const DeviceRates& rates);

// A design speed is 0 (none) or a finite speed above 0, m/s; anything else (negative, NaN, infinite)
// throws std::invalid_argument saying so. explain_text and explain_json check theirs with it.
void check_design_speed(double design_speed_m_s);

// The speeds explain reports the device output at: 20, 50, 100 and 200 mm/s, and `design_speed_m_s`
// when positive and not one of them, m/s.
inline std::vector<double> device_output_speeds(double design_speed_m_s) {
  std::vector<double> v{0.02, 0.05, 0.1, 0.2};
  if (design_speed_m_s > 0 && std::find(v.begin(), v.end(), design_speed_m_s) == v.end()) v.push_back(design_speed_m_s);
  return v;
}

// What explain reports: hand speeds 20, 50, 100 and 200 mm/s at `device_rate_hz` and at 10 kHz.
std::vector<FeltAtSpeed> felt_at_explain_speeds(const schema::PatchProgram& p, double device_rate_hz);

// Hand speeds a person commonly uses to feel a texture, m/s: 50 and 100 mm/s, about Smith, Gosselin &
// Houde 2002's measured mean exploration speeds (86 and 77 mm/s, bare finger) and inside the 33-110
// mm/s over which Depeault, Meftah & Chapman 2008 scanned textures (docs/TEXTURES.md).
inline const std::vector<double> kCommonHandSpeeds_m_s{0.05, 0.1};

// The servo rate `run` plays `device` at by default: 1000 Hz within the device's range, Hz.
double default_servo_rate_hz(const calibration::DeviceCalibration& device);

// The two remedies for a grating that loses peak force at `speed_m_s` on `rate_hz`, both
// measured by felt_at_speed: a servo at `fast_rate_hz` (offered when above `rate_hz`; the device's
// fastest), or the grating rebuilt with the least `smoothing` (Gaussian sigma, m) that keeps the felt
// peak within half a force JND of its compiled maximum at that speed and rate. The compiled maximum is unchanged by either (the force
// table is rescaled to it), so the roughness predicted from the felt peak returns toward its target.
struct FeltRemedies {
  double speed_m_s = 0, rate_hz = 0;
  FeltAtSpeed now;                 // as compiled
  double fast_rate_hz = 0;         // 0: no faster rate to offer
  FeltAtSpeed fast;                // at fast_rate_hz
  double smoothing_m = 0;          // 0: no smoothing up to a quarter of the period is enough
  FeltAtSpeed smoothed;            // with smoothing_m
};
// For `m`'s grating (nullopt-like empty result, speed_m_s = 0, for other textures).
FeltRemedies felt_remedies(const ResolvedMaterial& m, const schema::PatchProgram& p, double speed_m_s, double rate_hz,
                           double fast_rate_hz, double weber_fraction);

// W0350: at a common hand speed (kCommonHandSpeeds_m_s) on the device's default servo rate, a grating's
// felt peak is more than one force JND below its compiled maximum; says by how much and offers the
// remedies, each with the roughness it would be felt at.
void warn_felt_at_speed(const ResolvedMaterial& m, const schema::PatchProgram& p, const calibration::CalibrationSet& cal,
                        const calibration::DeviceCalibration& device, Diagnostics& diags);

}  // namespace sandpaper::compiler

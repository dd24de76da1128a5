#pragma once
// Calibration data the compiler reads: the psychophysical roughness map, the named roughness
// levels, and device calibrations. All of it lives in calibration/ as TOML with its sources;
// none of these numbers are constants in code.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace sandpaper::calibration {

// Thrown for a calibration file that is missing, malformed or inconsistent; names the file.
struct CalibrationError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A power-law map from maximum lateral force to perceived roughness, log10 R = slope log10 F + b,
// and the ratio scale built on it: r = R / R(F_ref) = (F / F_ref)^slope (the intercept cancels).
// Minsky 1995, 5.3.1, Figure 19.
struct RoughnessMap {
  std::string id;               // "minsky1995-fig19"
  std::string path;             // file it was read from
  double slope = 0, slope_se = 0;
  double intercept = 0, intercept_se = 0;
  double r_squared = 0;
  double reference_force_N = 0;  // F_ref: roughness 1 on the ratio scale
  double domain_force_min_N = 0, domain_force_max_N = 0;    // forces the map was measured on
  double domain_period_min_m = 0, domain_period_max_m = 0;  // grating periods it was measured on
  std::string domain_texture;   // "grating"
  std::string source;           // publication, section, figure

  // Ratio-scale roughness of a patch whose maximum lateral force is `force_N` (>= 0).
  double roughness_of(double force_N) const;
  // Maximum lateral force (N) that the map says gives ratio-scale roughness `r` (>= 0).
  double force_for(double r) const;
  // Roughness at the weakest calibrated stimulus (below it the compiler extrapolates).
  double min_calibrated_roughness() const { return roughness_of(domain_force_min_N); }
};

// A named point on the roughness scale ("coarse"), with why it sits where it does.
struct RoughnessLevel {
  std::string name;
  double roughness = 0;
  std::string rationale;
};

// A device's limits and command scale, SI units (issue 4 grows this).
struct DeviceCalibration {
  std::string name;                  // "sim"
  std::string path;
  double max_force_N = 0;            // maximum continuous lateral force
  double newtons_per_command_unit = 1;
  double min_rate_hz = 0, max_rate_hz = 0;
  double workspace_radius_m = 0;
  std::string calibrated_by;         // how the numbers were obtained
};

class CalibrationSet {
 public:
  // Reads <dir>/roughness/minsky1995-fig19.toml, <dir>/levels/roughness-levels.toml and
  // <dir>/devices/*.toml. Throws CalibrationError.
  static CalibrationSet load(const std::filesystem::path& dir);

  const RoughnessMap& roughness_map() const { return map_; }
  const std::vector<RoughnessLevel>& roughness_levels() const { return levels_; }
  // nullptr if no level has that name.
  const RoughnessLevel* find_level(const std::string& name) const;
  // nullptr if no device calibration has that name.
  const DeviceCalibration* find_device(const std::string& name) const;
  const std::vector<DeviceCalibration>& devices() const { return devices_; }
  const std::filesystem::path& directory() const { return dir_; }

 private:
  std::filesystem::path dir_;
  RoughnessMap map_;
  std::vector<RoughnessLevel> levels_;
  std::vector<DeviceCalibration> devices_;
};

// The calibration directory: $SANDPAPER_CALIBRATION if set, else the source tree's calibration/.
std::filesystem::path default_calibration_dir();

}  // namespace sandpaper::calibration

#pragma once
// Fitting a device's command scale from force-gauge readings: force = gain * command + offset by
// least squares per axis, with linearity (R^2, largest residual as % of full scale) and residuals.
// The device file keeps the gain (newtons_per_command_unit); the offset is reported, not stored,
// because the device model (and the runtime) command force = gain * command. docs/CALIBRATION.md.
#include <filesystem>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "sandpaper/calibration/regression.hpp"

namespace sandpaper::calibration {

// One reading: the command sent and the force the gauge measured, N. `axis` is 'x', 'y', or 0 when
// the CSV has no axis column (one fit for both axes).
struct ForceReading {
  double command = 0;
  double force_N = 0;
  char axis = 0;
  int line = 0;
};

struct DeviceReadings {
  std::string path;
  bool has_axis = false;
  std::vector<ForceReading> readings;
};

// Reads `command,force_N[,axis]` (other columns ignored). Throws FitError file:line for a missing
// column, a non-finite number, an axis other than x or y.
DeviceReadings read_device_readings_csv(const std::filesystem::path& path);
DeviceReadings parse_device_readings_csv(std::string_view text, const std::string& path);

struct AxisFit {
  char axis = 0;                   // 'x', 'y', or 0 for both
  int readings = 0, command_levels = 0;
  RegressionResult regression;     // force_N on command: "constant" (offset, N) and "command" (gain)
  double gain_N_per_unit = 0, gain_se = 0;
  double offset_N = 0, offset_se = 0, offset_p = 1;
  double full_scale_N = 0;         // largest |fitted force| over the measured commands
  double max_abs_residual_N = 0;
  double max_residual_percent = 0; // max |residual| / full scale * 100
  std::vector<ForceReading> points;  // this axis' readings, in file order (residuals in `regression`)
};

struct DeviceFit {
  std::string path;
  std::vector<AxisFit> axes;       // one (axis 0) or x then y
};

// Throws FitError for fewer than 3 readings on an axis, one command level, a gain that is not
// positive (force falls as the command grows: reversed axis or sign).
DeviceFit fit_device(const DeviceReadings& readings);

struct DeviceFileOptions {
  std::string name;        // empty: the base file's name
  std::string base_path;   // for the [calibration] text
  std::string date;        // optional, "YYYY-MM-DD"
};

// A calibrated device file: `base` (a parsed device file) with the fitted newtons_per_command_unit
// per axis, [calibration] status "calibrated" with method, source (the readings CSV) and
// residual_max; the fields readings cannot give (workspace, rates, command range) come from `base`.
// max_continuous is lowered to gain * command_max when the device cannot command the base's value.
// Throws FitError if the readings lack an axis the file needs.
std::string device_file_text(const DeviceFit& fit, const toml::table& base, const DeviceFileOptions& options);

}  // namespace sandpaper::calibration

// A lab's measurement CSVs for `sandpaper calibrate` (calibration/csv.hpp): magnitude estimates
// (`calibrate fit`) and force-gauge readings (`calibrate device`). The same bytes go to both readers;
// what a reader accepts is fitted, and a fit is checked the way the CLI uses it: its JSON view
// serialises, its numbers are finite, and the file it writes (a map; a device file on the shipped
// openffboard-2axis) loads through the loaders the compiler uses. Expected rejections: FitError
// from the readers and the fits. Nothing else is caught: a written file the loader refuses
// (CalibrationError) is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <toml++/toml.h>

#include "fuzz_support.hpp"
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/calibration/device_fit.hpp"
#include "sandpaper/calibration/fit.hpp"
#include "sandpaper/calibration/fit_error.hpp"
#include "sandpaper/calibration/fit_json.hpp"

namespace {

using namespace sandpaper;

void check_finite(const calibration::RegressionResult& r, const std::string& what) {
  for (const auto& c : r.coefficients)
    fuzz::check(std::isfinite(c.value) && std::isfinite(c.se), what + ": coefficient " + c.name + " is not finite");
}

void magnitude_estimates(std::string_view text) {
  calibration::MagnitudeEstimationData data;
  try {
    data = calibration::parse_magnitude_estimation_csv(text, "<fuzz>.csv");
  } catch (const calibration::FitError&) {
    return;
  }
  for (auto normalisation : {calibration::Normalisation::GeometricMean, calibration::Normalisation::None}) {
    calibration::MagnitudeEstimationFit fit;
    try {
      fit = calibration::fit_magnitude_estimation(data, normalisation);
    } catch (const calibration::FitError&) {
      continue;
    }
    check_finite(fit.force, "the force regression");
    fuzz::dump_json(calibration::fit_json(fit));
    // What `calibrate fit -o fitted-x.toml` writes must load, or the calibration folder stops loading.
    const auto path = fuzz::scratch_dir() / "fitted-x.toml";
    std::string map_text;
    try {
      map_text = calibration::map_file_text(fit, calibration::compile_map_options("fitted-x"));
    } catch (const calibration::FitError&) {
      continue;  // a slope of 0: no map is written
    }
    fuzz::write_file(path, map_text);
    try {
      const auto map = calibration::load_map_file(path);
      for (const auto& s : fit.stimuli) (void)map.percept_of(s.x);
    } catch (const calibration::CalibrationError& e) {
      fuzz::fail(std::string("calibrate fit wrote a map the loader refuses: ") + e.what());
    }
  }
}

const toml::table& openffboard_base() {
  static const toml::table base =
      toml::parse_file((fuzz::source_dir() / "calibration/devices/openffboard-2axis.toml").string());
  return base;
}

void gauge_readings(std::string_view text) {
  calibration::DeviceReadings readings;
  try {
    readings = calibration::parse_device_readings_csv(text, "<fuzz>.csv");
  } catch (const calibration::FitError&) {
    return;
  }
  calibration::DeviceFit fit;
  try {
    fit = calibration::fit_device(readings);
  } catch (const calibration::FitError&) {
    return;
  }
  for (const auto& a : fit.axes) {
    check_finite(a.regression, "the gauge regression");
    fuzz::check(a.gain_N_per_unit > 0 && std::isfinite(a.gain_N_per_unit), "a fitted gain that is not positive and finite");
  }
  std::string text_out;
  try {
    text_out = calibration::device_file_text(fit, openffboard_base(), {"", "calibration/devices/openffboard-2axis.toml", ""});
  } catch (const calibration::FitError&) {
    return;  // the readings lack an axis the device needs
  }
  const auto path = fuzz::scratch_dir() / "openffboard-2axis.toml";
  fuzz::write_file(path, text_out);
  try {
    const auto device = calibration::load_device_file(path);
    for (int axis = 0; axis < 2; ++axis) (void)device.command_units(axis, device.max_force_N);
  } catch (const calibration::CalibrationError& e) {
    fuzz::fail(std::string("calibrate device wrote a device file the loader refuses: ") + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  magnitude_estimates(text);
  gauge_readings(text);
  return 0;
}

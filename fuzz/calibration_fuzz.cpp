// Calibration TOML (calibration/: maps, device files, levels, knowledge): the bytes parsed by
// toml++ and validated against every shipped schema (schema/files/*.schema.json), then loaded as a
// device file and as a map file through the loaders the compiler uses (they take a path: one
// scratch file, reused). A loaded device and map are then used the way the compiler uses them.
// Expected rejections: toml::parse_error, calibration::CalibrationError. Nothing else is caught.
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include <toml++/toml.h>

#include "fuzz_support.hpp"
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/schema/file_schema.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const toml::table doc = toml::parse(text, std::string_view("<fuzz>.toml"));
    for (const auto& name : schema::file_schema_names())
      for (const auto& v : schema::validate_file(doc, name))
        fuzz::check(!v.message.empty(), "a schema violation without a message at `" + v.key + "`");
  } catch (const toml::parse_error&) {
  }

  const auto path = fuzz::scratch_dir() / "calibration.toml";
  fuzz::write_file(path, text);
  try {
    const auto device = calibration::load_device_file(path, "<fuzz>.toml");
    for (int a = 0; a < 2; ++a)
      for (double f : {0.0, 0.001, 1.0, device.max_force_N, -device.max_force_N}) {
        (void)device.quantize_N(a, f);
        (void)device.command_units(a, f);
        (void)device.force_step_N(a, f);
      }
    // [firmware]: the schema keeps its numbers non-negative, so the damper is a force against the
    // motion at any speed, as explain's device output takes it.
    if (device.has_firmware())
      for (int a = 0; a < 2; ++a)
        for (double v : {0.0, 0.02, 0.2, -0.2}) {
          const double d = device.firmware_damping_N(a, v);
          fuzz::check(std::isfinite(d) && d >= 0, "a firmware damper that is negative or not finite");
        }
    // [wheel]: the schema keeps its radius and range positive.
    if (device.wheel()) {
      const double deg_per_mm = device.wheel_deg_per_mm();
      fuzz::check(std::isfinite(deg_per_mm) && deg_per_mm > 0, "a wheel whose millimetres are no angle");
    }
  } catch (const calibration::CalibrationError&) {
  }
  try {
    const auto map = calibration::load_map_file(path, "<fuzz>.toml");
    for (double x : {0.0, 1e-6, 0.5, 1.0, 100.0}) {
      (void)map.percept_of(x);
      (void)map.value_for(x);
    }
    (void)map.provenance();
    (void)map.source();
  } catch (const calibration::CalibrationError&) {
  }
  return 0;
}

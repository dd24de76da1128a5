#pragma once
// Calibration data the compiler reads: psychophysical maps, named levels and device calibrations.
// All of it lives in calibration/ as TOML with its sources, validated against schema/files/ on
// load; none of these numbers are constants in code. Formats: docs/CALIBRATION.md.
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sandpaper/calibration/knowledge.hpp"

namespace sandpaper::calibration {

// Thrown for a calibration file that is missing, malformed or inconsistent. what() holds one line
// per problem, each "file:line:col: error: message".
struct CalibrationError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A closed range of a physical quantity, SI units.
struct Range {
  double min = 0, max = 0;
  bool contains(double v, double rel_tol = 1e-9) const { return v >= min * (1 - rel_tol) && v <= max * (1 + rel_tol); }
};

// One term of a log-linear map: coefficient * log10(x / unit).
struct Predictor {
  std::string name;            // "force", "period", "feature", "damping", "stiffness", "friction"
  std::string quantity;        // in words
  std::string unit;            // unit inside the logarithm, e.g. "pu"; "1": dimensionless (friction)
  double unit_si = 1;          // that unit in SI
  double coefficient = 0;
  std::optional<double> se, t, p;
};

// A psychophysical map, log10 P = intercept + sum_i c_i log10(x_i / unit_i) (Minsky 1995 Figures
// 19-20), and the ratio scale built on its ratio predictor: P = (x / x_ref)^c, P = 1 at x_ref.
struct PsychophysicalMap {
  std::string id;              // "minsky1995-fig19"
  std::string file;            // as shown to users: "calibration/maps/minsky1995-fig19.toml"
  std::string percept;         // "roughness"
  bool provisional = false;    // status = "provisional": not measured; every use must warn
  bool for_compile = false;    // use = "compile": the default map of its percept
  bool for_device = false;     // use = "device": compiles only for the device domain.device names
  std::string description;
  std::vector<Predictor> predictors;
  std::optional<double> intercept, intercept_se;
  // Goodness of fit, where the source gives it.
  std::optional<double> r_squared, r_squared_adjusted, residual_sd, f_ratio;
  std::optional<int> degrees_of_freedom, stimuli, subjects, runs;
  std::string normalisation;
  // Ratio scale (compile maps): the predictor's name, its coefficient and reference value (SI).
  std::string ratio_predictor;
  double slope = 0, slope_se = 0;
  double reference_si = 0;
  // Measured domain, SI; absent quantities were not reported. friction: the coefficient (no unit).
  std::optional<Range> force, period, feature, damping, stiffness, friction;
  // [domain] stimuli: the ratio predictor's range the fit saw (SI), when the domain above was widened
  // beyond it to the named levels; between the two the map extrapolates (W0322). nullopt: the same.
  std::optional<Range> stimulus_range;
  std::string domain_texture, domain_device, effector;
  // What the source's subjects touched ([domain] apparatus): "joystick", "manipulandum" (another
  // force-feedback device), "real material" (specimens felt directly: a joystick extrapolates,
  // W0321), "none" (not measured); empty when the file does not say.
  std::string apparatus;
  // Discrimination ([jnd]): the Weber fraction of the predictor (0.23: a 23 % change of stiffness is
  // one JND) and where it was measured; nullopt when the file gives none.
  std::optional<double> weber_fraction;
  std::string jnd_source;
  std::string citation, where;

  // Ratio-scale percept of a patch whose ratio predictor is `x_si` (>= 0); 0 for x <= 0.
  double percept_of(double x_si) const;
  // The ratio predictor's value (SI) that gives ratio-scale percept `p` (>= 0); 0 for p <= 0.
  double value_for(double p) const;
  // "minsky1995-fig19 (calibration/maps/minsky1995-fig19.toml)"
  std::string provenance() const { return id + " (" + file + ")"; }
  // "M. Minsky, ..., section 5.3.1, Figure 19"
  std::string source() const { return citation + ", " + where; }
  const Predictor* predictor(const std::string& name) const;
  // The source's subjects felt real specimens, not a force-feedback device.
  bool real_material() const { return apparatus == "real material"; }
};

// A named point on a percept's ratio scale ("coarse"), with why it sits where it does.
struct Level {
  std::string name;
  double value = 0;
  std::string rationale;
};

// One axis of a device's command scale: newtons at the handle per command unit, or a table of
// force-gauge readings (command, newtons) interpolated linearly and mirrored for negative commands.
struct AxisScale {
  double newtons_per_command_unit = 0;               // when `table` is empty
  std::vector<std::pair<double, double>> table;      // (command >= 0, force N >= 0), ascending
  // +1: a positive command pushes the handle toward the axis's positive end; -1: toward its
  // negative end ([force.x] command_sense). newtons() and command() are magnitudes along the
  // command; a driver multiplies what goes on the wire by the sense.
  int command_sense = 1;
  double newtons(double command) const;
  double command(double newtons) const;
  // Newtons of one command unit near `newtons` (the local slope of the table).
  double step_N(double newtons) const;
};

enum class CalibrationStatus { Calibrated, Uncalibrated, Definition };

// A device's limits and command scale, SI units (docs/CALIBRATION.md; CHAI3D-style limits as data).
struct DeviceCalibration {
  std::string name;                  // "sandpaper-1995": what --device takes
  std::string file;                  // "calibration/devices/sandpaper-1995.toml"
  std::string description;
  std::string command_unit;          // symbol of what a command counts: "ju", "N", "PID magnitude"
  double max_force_N = 0;            // maximum continuous lateral force per axis
  long command_max = 0;              // largest command magnitude; 0: continuous commands (no quantization)
  int resolution_bits = 0;           // 0 if not stated
  // x, y, and z for a three-axis device ([force.z]); z is unused (a default scale) otherwise.
  std::array<AxisScale, 3> axis;
  double position_resolution_m = 0;  // 0 if continuous or not stated
  bool workspace_circle = true;      // round: a circle, or a sphere for a three-axis device
  double workspace_radius_m = 0;     // circle, sphere: radius; rectangle, box: half the smallest side
  // Width (x), height (y) and depth (z) of a rectangle or box; round: the diameter on each. Depth is
  // 0 for a one- or two-axis device's workspace, which is flat.
  double workspace_size_m[3] = {0, 0, 0};
  double min_rate_hz = 0, max_rate_hz = 0;
  // [wheel]: a one-axis device turned at its rim. Its x is metres of rim arc from the centre, its
  // force the force at the rim (N); y is always 0 and takes no force. [force.z]: a three-axis
  // device (a 3-DOF haptic device, felt on shapes/ scenes: x right, y up, z toward the user), with
  // a box or sphere workspace. axes 2 with neither.
  int axes = 2;
  double wheel_rim_radius_m = 0;        // 0: not a wheel
  double wheel_rotation_range_rad = 0;  // lock to lock
  bool wheel() const { return axes == 1; }
  bool three_axis() const { return axes == 3; }
  // Degrees the wheel turns for 1 mm along its rim (0 when not a wheel).
  double wheel_deg_per_mm() const;
  int usb_vendor_id = -1, usb_product_id = -1;  // [usb] table of a USB HID PID device; -1: not a USB device
  // [usb] idle_report_period: how often the device resends an unchanged input report, s (0: it
  // reports every poll); the driver's stale-position watchdog waits at least twice this long.
  double usb_idle_report_period_s = 0;
  // [usb] out_interval: the interrupt OUT endpoint's polling interval (bInterval frames), s (0: not
  // stated). One force report crosses the bus per interval; the driver sends each changed axis in
  // its own, so a force changing on both axes reaches each at half that rate (USB 2.0 5.7.4).
  double usb_out_interval_s = 0;
  // [firmware]: what the device's own firmware does to a command on its way to the motor
  // (docs/USB_PID.md "The device's chain"); update_rate_hz 0 when the file has no [firmware].
  struct Firmware {
    double update_rate_hz = 0;          // a new command reaches the motor drivers this often, Hz
    double fade_in_s = 0;               // the torque ramps up from zero over this long when play starts, s
    double damping_command_s_per_m = 0; // always-on damper: command units against the motion per m/s
  } firmware;
  bool has_firmware() const { return firmware.update_rate_hz > 0; }
  // The firmware's damper on axis `a` at handle speed `speed_m_s`, N, against the motion (0 without one).
  double firmware_damping_N(int a, double speed_m_s) const;
  // [emulation]: a historical device `run` plays on the simulated joystick with its own quantisation
  // (sandpaper-1995: Minsky 1995 Table 2, Appendix B 2.1). `hold_tables`: force tables read by
  // sample-and-hold (nearest sample) instead of interpolation.
  bool emulated = false;
  bool hold_tables = false;
  std::string roughness_map;         // [maps] roughness: the map id this device compiles roughness with; empty: see load()
  CalibrationStatus status = CalibrationStatus::Uncalibrated;
  std::string calibration_method, calibration_source;

  bool quantized() const { return command_max > 0; }
  bool calibrated() const { return status != CalibrationStatus::Uncalibrated; }
  // Newtons of one command unit on axis `a` (0 = x, 1 = y, 2 = z) near `newtons`; 0 for a continuous device.
  double force_step_N(int a, double newtons = 0) const;
  // `newtons` on axis `a` rounded to the nearest force the device can command (unchanged when continuous).
  double quantize_N(int a, double newtons) const;
  // Command units for `newtons` on axis `a` (not rounded).
  double command_units(int a, double newtons) const { return axis_scale(a).command(newtons); }
  const AxisScale& axis_scale(int a) const { return axis[static_cast<std::size_t>(a)]; }
};

namespace detail {
struct Toml;
}

// Calibration files already parsed and validated, each kept with its exact bytes, for a caller that
// loads one folder many times while few of its files change (the calibration_set fuzz target: one
// file a load). A file is still read on every load; only when its bytes, path and schema equal a
// kept file's is its parse and validation skipped, so a changed file can never be served stale.
// Learns the files that validate while learning() is on; once off, a load only looks up. One loader
// at a time: not for use from two threads at once.
class ParsedFileCache {
 public:
  ParsedFileCache();
  ~ParsedFileCache();
  ParsedFileCache(const ParsedFileCache&) = delete;
  ParsedFileCache& operator=(const ParsedFileCache&) = delete;

  void set_learning(bool on) { learning_ = on; }
  bool learning() const { return learning_; }
  std::size_t size() const;
  std::size_t hits() const { return hits_; }  // loads of a file served from the cache, since made

  // For the loader (file_reading.cpp): the kept file for (schema, path, bytes) kept under the path
  // shown as `shown_as` (it is in every message the file's values give later), or null.
  std::shared_ptr<const detail::Toml> find(const std::string& schema, const std::filesystem::path& path,
                                           const std::string& shown_as, const std::string& bytes);
  void keep(const std::string& schema, const std::filesystem::path& path, std::string bytes,
            std::shared_ptr<const detail::Toml> file);

 private:
  struct Entries;
  std::unique_ptr<Entries> entries_;
  bool learning_ = true;
  std::size_t hits_ = 0;
};

class CalibrationSet {
 public:
  // Reads <dir>/maps/*.toml, <dir>/levels/*.toml, <dir>/devices/*.toml and <dir>/knowledge/*.toml,
  // each validated against its schema in schema/files/. Throws CalibrationError listing every
  // problem found (file:line:col), so one run shows them all. With `cache`, a file whose bytes it
  // holds is not parsed again (ParsedFileCache); the result and every message are the same.
  static CalibrationSet load(const std::filesystem::path& dir, ParsedFileCache* cache = nullptr);
  // A set of these devices only (no maps, levels, profiles or knowledge; roughness_map() must not be
  // asked): for opening a device where no calibration folder is needed (runtime::builtin_devices).
  static CalibrationSet of_devices(std::vector<DeviceCalibration> devices);

  const std::vector<PsychophysicalMap>& maps() const { return maps_; }
  // The map the compiler resolves `percept` through: the selected device's own map when it has one
  // (select_device), else the default (use = "compile"); nullptr if none.
  const PsychophysicalMap* compile_map(const std::string& percept) const;
  // The default compile map of `percept`, whatever device is selected; nullptr if none.
  const PsychophysicalMap* default_compile_map(const std::string& percept) const;
  // Compile for device `name` from now on: its [maps] entry, else the use = "device" map whose
  // domain.device names it, replaces the default map of that percept (docs/EXPERIMENTS.md). An empty
  // or unknown name selects no device. Checked by load(): at most one device map per percept and device.
  void select_device(const std::string& name);
  // The roughness compile map for the selected device (default: minsky1995-fig19); always present after load().
  const PsychophysicalMap& roughness_map() const { return *compile_map("roughness"); }
  const PsychophysicalMap* find_map(const std::string& id) const;

  // Named levels of a percept, in file order.
  std::vector<const Level*> levels(const std::string& percept) const;
  const std::vector<Level>& roughness_levels() const { return roughness_levels_; }
  // nullptr if no roughness level has that name.
  const Level* find_level(const std::string& name) const;

  // nullptr if no device calibration has that name.
  // A device file (calibration/devices/) or a profile (calibration/profiles/) by name; nullptr if none.
  const DeviceCalibration* find_device(const std::string& name) const;
  // The devices, without the profiles: what is plugged in is matched, listed and checked against these.
  const std::vector<DeviceCalibration>& devices() const { return devices_; }
  // Profiles: device files of assumptions for a device that has no file of its own, played only
  // when asked (uncalibrated-evdev: `run --device evdev --uncalibrated`, docs/DEVICES.md).
  const std::vector<DeviceCalibration>& profiles() const { return profiles_; }

  const Knowledge& knowledge() const { return knowledge_; }
  const std::filesystem::path& directory() const { return dir_; }

 private:
  std::filesystem::path dir_;
  std::vector<PsychophysicalMap> maps_;
  std::vector<std::pair<std::string, Level>> levels_;  // (percept, level)
  std::vector<Level> roughness_levels_;
  std::vector<DeviceCalibration> devices_;
  std::vector<DeviceCalibration> profiles_;
  Knowledge knowledge_;
  // (device name, percept) -> index into maps_, filled by load(); selected_ picks the device.
  std::vector<std::pair<std::pair<std::string, std::string>, std::size_t>> device_maps_;
  std::string selected_;
};

// One file, validated against its schema; `shown_as` is the path used in messages and provenance
// (default: the path itself). Throw CalibrationError. For tools (`sandpaper calibrate`) and tests.
PsychophysicalMap load_map_file(const std::filesystem::path& path, const std::string& shown_as = {});
DeviceCalibration load_device_file(const std::filesystem::path& path, const std::string& shown_as = {});
// A device file's text (as an embedded copy of one), validated as load_device_file validates a file;
// `shown_as` names it in messages. Throws CalibrationError.
DeviceCalibration parse_device_text(const std::string& text, const std::string& shown_as);

// The calibration directory: $SANDPAPER_CALIBRATION, $SANDPAPER_DATA_DIR/calibration, else the shipped
// calibration/ (the source tree's in a build tree, the installed package's when installed); defined
// with compiler::find_calibration_dir() in compiler/src/library/data_dirs.cpp.
std::filesystem::path default_calibration_dir();

}  // namespace sandpaper::calibration

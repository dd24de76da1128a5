#pragma once
// Sandpaper for applications: a material or a roughness level by name, played on a device.
//
//   sandpaper::Library library;                              // the shipped library and calibration
//   sandpaper::Material corduroy = library.compile("corduroy");
//   sandpaper::Player player = sandpaper::Player::simulated();
//   player.load(corduroy);
//   player.start({.rate_hz = 1000, .duration_s = 0.5});
//   sandpaper::runtime::ServoReport report = player.wait();
//
// A thin layer over sandpaper::compiler::Compiler and the runtime's servo thread; both stay
// usable directly for anything this does not cover. docs/API.md has the whole story.
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/runtime/device.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/schema/patch_program.hpp"

// In an installed package: register where its data lies, found from where its headers lie
// (cmake/package_location.h.in; the source tree has no such header).
#if __has_include(<sandpaper/package_location.h>)
#include <sandpaper/package_location.h>
#endif

namespace sandpaper::compiler {
class Compiler;
}
namespace sandpaper::calibration {
class CalibrationSet;
}

namespace sandpaper {

// Base of everything this API throws for bad input or missing data; what() says how to fix it.
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A material that did not compile. what() is the formatted diagnostics (file:line:col, the source
// line with a caret, help), as `sandpaper compile` prints them; diagnostics() has them as data.
class CompileError : public Error {
 public:
  explicit CompileError(compiler::Diagnostics diagnostics);
  const compiler::Diagnostics& diagnostics() const noexcept { return diagnostics_; }

 private:
  compiler::Diagnostics diagnostics_;
};

// A level name that calibration/levels/ does not define for its percept (or a percept with no
// levels); what() lists the known ones (for a percept with no levels: the percepts that have some).
class UnknownLevel : public Error {
 public:
  // `level_percepts`: the percepts that have levels, named when `percept` has none (percepts_with_levels).
  UnknownLevel(std::string name, std::vector<std::string> known, const std::string& percept = "roughness",
               const std::vector<std::string>& level_percepts = {});
  const std::string& name() const noexcept { return name_; }
  const std::vector<std::string>& known() const noexcept { return known_; }

 private:
  std::string name_;
  std::vector<std::string> known_;
};

// The percepts that have named levels in `calibration` (calibration/levels/), sorted: what an
// UnknownLevel for a percept without levels lists.
std::vector<std::string> percepts_with_levels(const calibration::CalibrationSet& calibration);

// No force-feedback device to play on: none plugged in, none the calibration knows, or one that
// cannot be opened (what() says which, and for a permission problem the udev rule to add).
struct DeviceError : Error {
  using Error::Error;
};

// A compiled material: a patch program (schema/patch_program.hpp, SI units) ready to play.
// Cheap to copy (the program is shared and immutable).
class Material {
 public:
  explicit Material(schema::PatchProgram program);
  const std::string& name() const noexcept { return program_->name; }
  // Texture's maximum lateral force over the patch (N), as compiled for the device; what a run
  // felt is its report's felt_max_lateral_force_N.
  double compiled_max_lateral_force_N() const noexcept { return program_->max_lateral_force_N; }
  // Ratio-scale roughness the roughness map predicts for that force (Minsky 1995, Fig. 19).
  double compiled_roughness() const noexcept { return program_->roughness; }
  // Compiler warnings, one line each: "file:line:col: message [W0330]".
  std::vector<std::string> warnings() const;
  const schema::PatchProgram& program() const noexcept { return *program_; }
  std::shared_ptr<const schema::PatchProgram> shared_program() const noexcept { return program_; }

 private:
  std::shared_ptr<const schema::PatchProgram> program_;
};

struct LibraryOptions {
  // Empty: compiler::find_library_dir() / find_calibration_dir(): $SANDPAPER_LIBRARY /
  // $SANDPAPER_CALIBRATION, $SANDPAPER_DATA_DIR, else the shipped data (docs/API.md, "Data directories").
  std::filesystem::path library_dir;
  std::filesystem::path calibration_dir;
  std::string device = "sim";             // device calibration to compile for (calibration/devices/)
  // A layered library: several library folders, front first (a lab's own on top of the world
  // library; docs/LIBRARY.md, "Layered libraries"). When set, library_dir is not used; when both
  // are empty, $SANDPAPER_LIBRARY_PATH (folders separated by ':') comes before the search above.
  std::vector<std::filesystem::path> library_path;
};

// The world haptics library with its calibration: compiles materials by name or description.
class Library {
 public:
  // The shipped library and calibration (or the environment's, see LibraryOptions), device "sim".
  Library();
  // Another library directory (entries `<name>.hmat`), the shipped calibration, device "sim".
  explicit Library(const std::filesystem::path& library_dir);
  // Throws Error if a data directory is missing (the message names every missing one, what chose
  // it, and the environment variables that override it), if the calibration is malformed, or the
  // device unknown.
  explicit Library(LibraryOptions options);
  ~Library();
  Library(Library&&) noexcept;
  Library& operator=(Library&&) noexcept;

  // A library name or alias ("corduroy"), or material statements separated by ';'
  // ("like corduroy; roughness 0.6", "roughness 0.6"). Throws CompileError on any error: a failed
  // compile never gives a Material. Warnings travel with the Material.
  Material compile(const std::string& name_or_statements) const;
  // A named roughness level ("coarse"; calibration/levels/roughness-levels.toml) on the library's
  // reference texture, as `roughness coarse` in a material file. Throws UnknownLevel, CompileError.
  Material roughness_level(const std::string& level) const;
  // A named level of any percept with levels ("softness", "soft"; calibration/levels/), alone, as
  // `softness soft` in a material file: a spring, a damper, friction, or roughness on the reference
  // texture. Throws UnknownLevel (unknown percept or level), CompileError.
  Material level(const std::string& percept, const std::string& level) const;

  // Entry names, sorted.
  std::vector<std::string> names() const;
  // Roughness level names, weakest first, and a level's ratio-scale value (throws UnknownLevel).
  std::vector<std::string> roughness_levels() const;
  double roughness_level_value(const std::string& level) const;
  // The same for any percept: its level names, weakest first (empty for a percept without levels),
  // and a level's ratio-scale value (throws UnknownLevel).
  std::vector<std::string> levels(const std::string& percept) const;
  double level_value(const std::string& percept, const std::string& level) const;
  // The compiler behind it (its calibration, device and library), for anything this API does not cover.
  const ::sandpaper::compiler::Compiler& compiler() const noexcept;
  // The directories in use (absolute when given so), for reports.
  const std::filesystem::path& library_dir() const noexcept;
  const std::filesystem::path& calibration_dir() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct PlayOptions {
  double rate_hz = 1000.0;  // servo rate, 900 Hz - 10 kHz and within the device's limits
  double duration_s = 0.0;  // how long to play; 0: until stop(), for as long as it takes (fixed memory)
};

// Plays materials on one device on a servo thread of its own (runtime::ServoThread). Loading while
// playing swaps the material without a break (runtime::SwappableSource, 5 ms crossfade).
// How Player::open may take a device.
struct PlayerOpenOptions {
  bool uncalibrated = false;  // an input event node no calibration file names may play (docs/DEVICES.md)
};

class Player {
 public:
  // The simulated joystick (runtime::SimJoystick, limits of calibration/devices/sim.toml): a
  // scripted hand, by default scanning +-30 mm along x at 50 mm/s through the patch centre.
  static Player simulated(runtime::HandScript hand = {});
  // The first USB HID PID force-feedback joystick present whose vendor and product IDs one of
  // `library`'s device calibrations names (calibration/devices/*.toml [usb]; docs/USB_PID.md),
  // opened with its effects created; its forces go out in that calibration's command units.
  // Materials must be compiled for it: Library(LibraryOptions{.device = player.device_calibration()}).
  // Throws DeviceError when USB cannot be searched, no calibrated joystick is plugged in (the
  // message lists the IDs the calibration knows) or it cannot be opened.
  static Player usb(const Library& library);
  // The same, matching against any calibration set (compiler::Compiler::calibration()).
  static Player usb(const calibration::CalibrationSet& set);
  // A calibrated joystick found along the path `device` names (docs/DEVICES.md): "usb" (as usb()),
  // "hidraw" (the first such joystick's hidraw node, the kernel's driver left bound, no root) or
  // "hidraw:PATH" (that node), "evdev" or "evdev:PATH" (its input event node: the kernel's own force
  // feedback, no root). Throws DeviceError as usb() does, and for a device that is not on the bus.
  // options.uncalibrated: an evdev device no calibration file names plays with the uncalibrated-evdev
  // profile (at most a quarter of its strongest force); warning() then says so. Evdev only.
  static Player open(const Library& library, const std::string& device, PlayerOpenOptions options = {});
  static Player open(const calibration::CalibrationSet& set, const std::string& device, PlayerOpenOptions options = {});
  // Any device (a USB HID PID joystick, a replay, your own runtime::Device); the player owns it.
  explicit Player(std::unique_ptr<runtime::Device> device);
  ~Player();  // stops and joins if still playing
  Player(Player&&) noexcept;
  Player& operator=(Player&&) noexcept;

  // Plays `material` from the next start(), or at once if playing. The program is kept alive for
  // as long as the servo thread may use it. Throws DeviceError if the material was compiled for
  // another device than device_calibration() (when that is set).
  void load(const Material& material);
  // Starts the servo thread. Throws Error if nothing is loaded or already playing, and
  // std::invalid_argument for a rate outside the device's limits or a bad duration.
  void start(PlayOptions options = {});
  // Asks the servo thread to stop at its next tick, waits for it and returns its report
  // (stop_cause StopRequested, or what stopped it first). Throws Error if not started.
  runtime::ServoReport stop();
  // Waits for the servo thread to finish on its own (duration, or a fault) and returns its report.
  runtime::ServoReport wait();
  bool playing() const noexcept;
  runtime::Device& device() noexcept;
  // The device calibration materials must be compiled for: the joystick's for usb(); empty for
  // simulated() and a Device given directly (any material plays there).
  const std::string& device_calibration() const noexcept;
  // What a person should be told before the player plays (a device played with a profile's assumed
  // scale: Player::open with uncalibrated); empty otherwise.
  const std::string& warning() const noexcept;

 private:
  void set_device_calibration_nonrt(std::string name);
  void set_warning_nonrt(std::string text);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sandpaper

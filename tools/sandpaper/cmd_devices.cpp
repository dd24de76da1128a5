// `sandpaper devices` and `sandpaper run --device usb`: USB HID PID force-feedback joysticks
// (docs/USB_PID.md). The devices the runtime knows are the calibrations with a [usb] table.
#include <filesystem>
#include <iostream>

#include <fmt/format.h>

#include "cli.hpp"
#include "play.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/usb/hid_pid_joystick.hpp"
#include "sandpaper/runtime/usb/libusb_transport.hpp"

namespace sandpaper::cli {
namespace {

using runtime::usb::UsbStatus;

struct Found {
  runtime::usb::UsbHidDeviceInfo info;
  const calibration::DeviceCalibration* calibration = nullptr;  // nullptr: PID device we have no calibration for
};

std::string ids(int vendor, int product) { return fmt::format("{:04x}:{:04x}", vendor, product); }

std::string udev_rule(int vendor, int product) {
  return fmt::format("SUBSYSTEM==\"usb\", ATTR{{idVendor}}==\"{:04x}\", ATTR{{idProduct}}==\"{:04x}\", MODE=\"0660\", TAG+=\"uaccess\"",
                     vendor, product);
}

void print_udev_help(std::ostream& out, int vendor, int product) {
  out << "  permission to open the device is missing; add this line to /etc/udev/rules.d/70-sandpaper.rules:\n"
      << "    " << udev_rule(vendor, product) << "\n"
      << "  then run `sudo udevadm control --reload` and unplug and replug the device\n";
}

std::string known_list(const calibration::CalibrationSet& set) {
  std::string s;
  for (const auto& d : set.devices())
    if (d.usb_vendor_id >= 0) s += (s.empty() ? "" : ", ") + d.name + " (" + ids(d.usb_vendor_id, d.usb_product_id) + ")";
  return s.empty() ? "none" : s;
}

// Force-feedback devices present: a PID usage in the report descriptor, or a known VID:PID.
// Returns false (after printing why on stderr) when USB cannot be searched or none is present.
bool find_devices(const calibration::CalibrationSet& set, std::vector<Found>& found, const char* command) {
  const auto e = runtime::usb::list_usb_hid_devices();
  if (e.status != UsbStatus::Ok) {
    std::cerr << "sandpaper " << command << ": no USB force-feedback device: " << e.message
              << "\n  known devices: " << known_list(set) << "\n";
    return false;
  }
  for (const auto& info : e.devices) {
    const calibration::DeviceCalibration* cal = nullptr;
    for (const auto& d : set.devices())
      if (d.usb_vendor_id == info.vendor_id && d.usb_product_id == info.product_id) cal = &d;
    if (cal || info.has_pid) found.push_back({info, cal});
  }
  if (found.empty()) {
    std::cerr << "sandpaper " << command << ": no USB force-feedback device found (" << e.devices.size()
              << " USB HID device(s) checked, none with a Physical Interface Device usage or a known ID)"
              << (std::filesystem::exists("/dev/bus/usb") ? "" : "\n  this system shows no USB bus: /dev/bus/usb does not exist (a container or VM without USB passthrough?)")
              << "\n  known devices: " << known_list(set) << "\n";
    return false;
  }
  return true;
}

}  // namespace

int cmd_devices(const CommonOptions& o) {
  CommonOptions base = o;
  base.device = "sim";
  const auto c = make_compiler(base);
  std::vector<Found> found;
  if (!find_devices(c.calibration(), found, "devices")) return kExitUsage;
  bool denied = false;
  for (const auto& f : found) {
    std::cout << fmt::format("{} bus {} address {}{}: {}; {}\n", ids(f.info.vendor_id, f.info.product_id), f.info.bus,
                             f.info.address, f.info.product.empty() ? "" : " \"" + f.info.product + "\"",
                             f.info.descriptor_read ? (f.info.has_pid ? "HID PID force feedback" : "no PID usage in its descriptor")
                                                    : "descriptor not read",
                             f.calibration ? "calibration " + f.calibration->name + " (" + f.calibration->file + ")"
                                           : std::string("no device calibration: cannot be played yet"));
    if (f.info.open_status == UsbStatus::AccessDenied) {
      denied = true;
      print_udev_help(std::cout, f.info.vendor_id, f.info.product_id);
    }
  }
  return denied ? kExitUsage : kExitOk;
}

int cmd_run_usb(const CommonOptions& o, double rate_hz, double duration_s) {
  CommonOptions base = o;
  base.device = "sim";
  const auto probe = make_compiler(base);
  std::vector<Found> found;
  if (!find_devices(probe.calibration(), found, "run --device usb")) return kExitUsage;
  const Found* chosen = nullptr;
  for (const auto& f : found)
    if (f.calibration) {
      chosen = &f;
      break;
    }
  if (!chosen) {
    std::cerr << "sandpaper run --device usb: force-feedback devices are present but none has a device calibration with a [usb] table "
                 "(docs/CALIBRATION.md)\n";
    return kExitUsage;
  }
  CommonOptions co = o;
  co.device = chosen->calibration->name;
  const auto c = make_compiler(co);
  auto in = load_input(co, c, /*allow_patch=*/true);
  if (!in) return kExitBadInput;
  if (in->program.device != co.device) {
    std::cerr << "sandpaper: error: the patch was compiled for device '" << in->program.device << "', not '" << co.device
              << "'; recompile it with --device " << co.device << "\n";
    return kExitUsage;
  }
  runtime::ServoConfig cfg;
  cfg.rate_hz = rate_hz;
  cfg.duration_s = duration_s;

  std::unique_ptr<runtime::usb::LibusbTransport> transport;
  std::string message;
  const UsbStatus s = runtime::usb::LibusbTransport::open(static_cast<std::uint16_t>(chosen->info.vendor_id),
                                                          static_cast<std::uint16_t>(chosen->info.product_id), transport, message);
  if (s != UsbStatus::Ok) {
    std::cerr << "sandpaper run --device usb: cannot open " << ids(chosen->info.vendor_id, chosen->info.product_id) << ": " << message << "\n";
    if (s == UsbStatus::AccessDenied) print_udev_help(std::cerr, chosen->info.vendor_id, chosen->info.product_id);
    return kExitUsage;
  }
  try {
    runtime::usb::HidPidJoystick joystick(*transport, *chosen->calibration);
    runtime::validate_config(cfg, joystick.limits());
    runtime::PatchEvaluator evaluator(in->program);
    std::cout << fmt::format("playing {} on {} ({}): {:g} Hz for {:g} s\n", in->program.name, co.device,
                             ids(chosen->info.vendor_id, chosen->info.product_id), rate_hz, duration_s);
    // Through play(): Ctrl-C / SIGTERM stop the loop with zero force, and the device is given back below.
    const auto rep = play(joystick, evaluator, cfg, /*virtual_clock=*/false, /*live=*/false, 0).report;
    joystick.close();
    const std::string stop = std::string(rep.stop_reason) + " [" + runtime::stop_cause_name(rep.stop_cause) + "]";
    std::cout << fmt::format("  loop     {} ticks, achieved {:.2f} Hz; period p99 {:.1f} us; overruns {}\n", rep.ticks, rep.rate_hz,
                             rep.period_p99_us, rep.overruns)
              << fmt::format("  felt     max force {:.4f} N, clamped ticks {}\n", rep.max_lateral_force_N, rep.clamped_ticks)
              << "  servo    " << (rep.realtime_scheduling ? "SCHED_FIFO, memory locked" : "normal priority (SCHED_FIFO not permitted here)")
              << "; stopped: " << stop << "\n";
    return exit_status_of(rep);
  } catch (const runtime::usb::HidPidError& e) {
    std::cerr << "sandpaper run --device usb: " << e.what() << "\n";
    if (e.status == UsbStatus::AccessDenied) print_udev_help(std::cerr, chosen->info.vendor_id, chosen->info.product_id);
    return kExitUsage;
  }
}

namespace {

// A USB joystick that owns its transport, for callers that keep a Device for their own lifetime (the studio).
class OwnedUsbJoystick final : public runtime::Device {
 public:
  OwnedUsbJoystick(std::unique_ptr<runtime::usb::LibusbTransport> transport, const calibration::DeviceCalibration& cal)
      : transport_(std::move(transport)), joystick_(*transport_, cal) {}
  ~OwnedUsbJoystick() override { joystick_.close(); }
  const runtime::DeviceLimits& limits() const noexcept override { return joystick_.limits(); }
  bool read_position_rt(double t_s, glm::dvec2& position_m) noexcept override {
    return joystick_.read_position_rt(t_s, position_m);
  }
  bool write_force_rt(glm::dvec2 force_N) noexcept override { return joystick_.write_force_rt(force_N); }
  runtime::DeviceFault last_fault_rt() const noexcept override { return joystick_.last_fault_rt(); }

 private:
  std::unique_ptr<runtime::usb::LibusbTransport> transport_;
  runtime::usb::HidPidJoystick joystick_;
};

}  // namespace

std::unique_ptr<runtime::Device> open_usb_joystick(const CommonOptions& o, std::string& device_name, std::string& error) {
  CommonOptions base = o;
  base.device = "sim";
  const auto probe = make_compiler(base);
  std::vector<Found> found;
  if (!find_devices(probe.calibration(), found, "studio --device usb")) {
    error = "no USB force-feedback joystick found";
    return nullptr;
  }
  for (const auto& f : found) {
    if (!f.calibration) continue;
    std::unique_ptr<runtime::usb::LibusbTransport> transport;
    std::string message;
    const UsbStatus st = runtime::usb::LibusbTransport::open(static_cast<std::uint16_t>(f.info.vendor_id),
                                                             static_cast<std::uint16_t>(f.info.product_id), transport, message);
    if (st != UsbStatus::Ok) {
      error = "cannot open " + ids(f.info.vendor_id, f.info.product_id) + ": " + message;
      if (st == UsbStatus::AccessDenied) print_udev_help(std::cerr, f.info.vendor_id, f.info.product_id);
      return nullptr;
    }
    try {
      device_name = f.calibration->name;
      // The calibration lives in `probe`, which goes out of scope: the joystick keeps what it needs
      // of it (limits, command scale) at construction.
      return std::make_unique<OwnedUsbJoystick>(std::move(transport), *f.calibration);
    } catch (const runtime::usb::HidPidError& e) {
      error = e.what();
      return nullptr;
    }
  }
  error = "force-feedback devices are present but none has a device calibration with a [usb] table (docs/CALIBRATION.md)";
  return nullptr;
}

}  // namespace sandpaper::cli

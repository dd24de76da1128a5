// OpenFFBoardFirmware: the firmware compiled for the host (README.md) behind the UsbFunction
// interface. Everything the host sees comes from the firmware: its descriptors and strings through
// its tud_descriptor_*_cb callbacks, control requests and endpoint transfers through TinyUSB's HID
// class driver. This file only translates, and runs each call on the emulated core.
#include "openffboard_firmware.hpp"

#include <array>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "Axis.h"
#include "ClassIDs.h"
#include "CommandHandler.h"
#include "EffectsCalculator.h"
#include "FFBHIDMain.h"
#include "RmdMotorCAN.h"
#include "eeprom_addresses.h"
#include "flash_helpers.h"
#include "hal_timer.hpp"
#include "lab_core.hpp"
#include "lab_usbd.hpp"
#include "stick_link.hpp"
#include "task_hooks.hpp"
#include "startup.hpp"
#include "tusb.h"

extern FFBoardMain* mainclass;  // the firmware's main class (startup.cpp, as cppmain.cpp)

namespace sandpaper::usb_lab {
namespace {

namespace core = usb_lab::core;

// The task that runs the firmware's control steps, woken by TIM_FFB's update (FFBHIDMain.cpp:32, 120).
constexpr std::string_view kControlTask = "FFBMAIN";

// A USB string descriptor (UTF-16LE code units after the 2-byte header) as ASCII.
std::string decode_string_descriptor(const std::uint16_t* desc) {
  if (desc == nullptr) return {};
  const std::size_t length = desc[0] & 0xff;  // bLength, including the header
  std::string out;
  for (std::size_t i = 1; i < length / 2; ++i) out.push_back(static_cast<char>(desc[i] & 0x7f));
  return out;
}

// The HID interface of a configuration descriptor: its interface descriptor and everything up to
// the next interface or interface association, renumbered as interface 0 of the function. Its
// string index stays the firmware's (device-wide; string_descriptor() answers it).
std::vector<std::uint8_t> hid_function_part(const std::uint8_t* config) {
  const std::size_t total = static_cast<std::size_t>(config[2] | (config[3] << 8));
  std::vector<std::uint8_t> out;
  bool in_hid = false;
  for (std::size_t at = config[0]; at + 1 < total && config[at] != 0; at += config[at]) {
    const std::uint8_t* d = config + at;
    const std::uint8_t type = d[1];
    if (type == TUSB_DESC_INTERFACE || type == TUSB_DESC_INTERFACE_ASSOCIATION) {
      in_hid = type == TUSB_DESC_INTERFACE && d[5] == TUSB_CLASS_HID;
      if (in_hid && !out.empty()) break;  // one HID interface
    }
    if (in_hid) out.insert(out.end(), d, d + d[0]);
  }
  if (out.size() < 9) throw std::runtime_error("OpenFFBoard firmware: no HID interface in its configuration descriptor");
  out[2] = 0;  // bInterfaceNumber
  return out;
}

// Reads one of an Axis's settings through the firmware's own command interface ("axis.<cmd>?").
std::int64_t axis_setting(CommandHandler* axis, Axis_commands command) {
  ParsedCommand cmd;
  cmd.cmdId = static_cast<std::uint32_t>(command);
  cmd.type = CMDtype::get;
  std::vector<CommandReply> replies;
  axis->command(cmd, replies);
  if (replies.empty()) throw std::runtime_error("OpenFFBoard firmware: axis setting not readable");
  return replies.front().val;
}

class Firmware final : public OpenFFBoardFirmware {
 public:
  explicit Firmware(MainClass main) : axes_(main == MainClass::Wheel ? 1 : 2) {
    (void)core::epoch();
    // cppmain reads the main class from the flash (ADR_CURRENT_CONFIG), writing DEFAULTMAIN only
    // when none is there: as a board that was switched to another class and restarted.
    Flash_Write(ADR_CURRENT_CONFIG, main == MainClass::Wheel ? CLSID_MAIN_FFBWHEEL : CLSID_MAIN_FFBJOY);
    startup::start_default_task();
    const auto give_up = core::Clock::now() + std::chrono::seconds(10);
    while (!(startup::main_class_ready() && usbd::stack_initialized())) {
      if (core::Clock::now() > give_up) throw std::runtime_error("OpenFFBoard firmware: startup did not finish");
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    core::Hold hold;
    rtos::set_after_notification_take([this](std::string_view task) {
      if (task == kControlTask) control_step_woke();
    });
    const auto* device = reinterpret_cast<const tusb_desc_device_t*>(tud_descriptor_device_cb());
    identity_.vendor_id = device->idVendor;
    identity_.product_id = device->idProduct;
    identity_.bcd_device = device->bcdDevice;
    identity_.bcd_usb = device->bcdUSB;
    identity_.device_class = device->bDeviceClass;
    identity_.device_subclass = device->bDeviceSubClass;
    identity_.device_protocol = device->bDeviceProtocol;
    identity_.manufacturer = decode_string_descriptor(tud_descriptor_string_cb(device->iManufacturer, 0x0409));
    identity_.product = decode_string_descriptor(tud_descriptor_string_cb(device->iProduct, 0x0409));
    identity_.serial_number = decode_string_descriptor(tud_descriptor_string_cb(device->iSerialNumber, 0x0409));
    identity_.max_speed = TUD_OPT_HIGH_SPEED ? "high-speed" : "full-speed";
    descriptors_ = hid_function_part(tud_descriptor_configuration_cb(0));
    for (std::size_t at = 0; at + 2 < descriptors_.size(); at += descriptors_[at]) {
      if (descriptors_[at + 1] != TUSB_DESC_ENDPOINT) continue;
      const std::uint8_t address = descriptors_[at + 2];
      (address & 0x80 ? ep_in_ : ep_out_) = address;
    }
  }

  // The firmware cannot be unloaded: its interrupts stop and its tasks park for good.
  ~Firmware() override {
    {
      core::Hold hold;
      rtos::set_after_notification_take(nullptr);
    }
    hal::stop_timer_interrupts();
    core::halt();
  }

  DeviceIdentity identity() const override { return identity_; }
  int axes() const override { return axes_; }
  std::vector<std::uint8_t> function_descriptors() const override { return descriptors_; }

  // The firmware's string table (USBdevice::getUsbStringDesc through tud_descriptor_string_cb).
  std::string string_descriptor(std::uint8_t index) const override {
    if (index == 0) return {};  // the language list, not a string
    core::Hold hold;
    return decode_string_descriptor(tud_descriptor_string_cb(index, 0x0409));
  }

  void configured() override {
    core::Hold hold;
    usbd::configure(descriptors_);
  }

  void deconfigured() override {
    core::Hold hold;
    usbd::deconfigure();
  }

  void suspended(bool suspended) override {
    core::Hold hold;
    usbd::suspend(suspended);
  }

  ControlReply control(const SetupPacket& setup, std::span<const std::uint8_t> out_data) override {
    core::Hold hold;
    const auto r = usbd::control(setup.bmRequestType, setup.bRequest, setup.wValue, setup.wIndex, setup.wLength, out_data);
    return ControlReply{r.stall, r.data};
  }

  void interrupt_out(std::span<const std::uint8_t> data) override {
    core::Hold hold;
    usbd::out_transfer(ep_out_, data);
  }

  bool next_interrupt_in(std::vector<std::uint8_t>& report, std::chrono::microseconds wait) override {
    return usbd::wait_in_transfer(ep_in_, report, wait);
  }

  void interrupt_in_done(bool delivered) override {
    core::Hold hold;
    usbd::complete_in_transfer(ep_in_, delivered);
  }

  // Encoder counts per fraction of the axis's reported range. Axis.cpp: angle = 360 deg * counts /
  // cpr * gear ratio, negated when inverted; reported fraction = angle / (degrees / 2). The axis's
  // range, inversion and gear ratio are read from the firmware. Call holding the core.
  double counts_per_fraction(int axis) const {
    if (axis < 0 || axis >= axes_)
      throw std::out_of_range("OpenFFBoardFirmware: axis " + std::to_string(axis) + " of " + std::to_string(axes_));
    CommandHandler* handler = CommandHandler::getHandlerFromClassName("axis", static_cast<std::uint8_t>(axis));
    if (handler == nullptr) throw std::runtime_error("OpenFFBoard firmware: no axis " + std::to_string(axis));
    const double degrees = static_cast<double>(axis_setting(handler, Axis_commands::degrees));
    const bool inverted = axis_setting(handler, Axis_commands::invert) != 0;
    ParsedCommand gear_cmd;
    gear_cmd.cmdId = static_cast<std::uint32_t>(Axis_commands::reductionScaler);
    gear_cmd.type = CMDtype::get;
    std::vector<CommandReply> gear;
    handler->command(gear_cmd, gear);
    const double gear_ratio =
        gear.empty() ? 1.0 : static_cast<double>(gear.front().val) / static_cast<double>(gear.front().adr);
    return (degrees / 2.0) / 360.0 / gear_ratio * (inverted ? -1.0 : 1.0) *
           static_cast<double>(RmdMotorCAN::counts_per_rotation);
  }

  void set_position(int axis, double fraction_of_range) override {
    core::Hold hold;
    const double counts = std::round(fraction_of_range * counts_per_fraction(axis));
    stick_link::axis(axis).encoder_counts = static_cast<std::int32_t>(counts);
  }

  void move_stick(StickPath path) override {
    core::Hold hold;
    stick_path_ = std::move(path);
    stick_scale_ = {};
    if (stick_path_)
      for (int a = 0; a < axes_; ++a) stick_scale_[a] = counts_per_fraction(a);
    stick_t_s_ = 0;
  }

  void on_torque(std::function<void(const TorqueUpdate&)> observer) override {
    if (!observer) {
      stick_link::set_observer(nullptr);
      return;
    }
    stick_link::set_observer([observer = std::move(observer)](int axis, std::int16_t torque, core::Clock::time_point time) {
      observer(TorqueUpdate{axis, torque, time});
    });
  }

  FirmwareState state() const override {
    FirmwareState s;
    for (int a = 0; a < 2; ++a) {
      s.torque[a] = stick_link::axis(a).torque.load();
      s.torque_updates[a] = stick_link::axis(a).torque_updates.load();
    }
    s.actuators_enabled = true;
    for (int a = 0; a < axes_; ++a) s.actuators_enabled = s.actuators_enabled && stick_link::axis(a).driver_enabled.load();
    const hal::TimerUpdateCounts ffb_timer = hal::timer_update_counts(TIM_FFB);
    s.ffb_timer_updates = ffb_timer.run;
    s.ffb_timer_updates_dropped = ffb_timer.dropped;
    s.ffb_timer_periods_due = ffb_timer.due;
    s.ffb_control_steps = control_steps_.load(std::memory_order_relaxed);
    core::Hold hold;
    if (auto* main = dynamic_cast<FFBHIDMain*>(mainclass)) s.ffb_active = main->getFfbActive();
    if (auto* fx = dynamic_cast<EffectsCalculator*>(CommandHandler::getHandlerFromClassName("fx"))) {
      for (const FFB_Effect& effect : fx->effects) s.effects_in_use += effect.type != FFB_EFFECT_NONE ? 1 : 0;
    }
    return s;
  }

  // The FFB update rate as the timer that paces it runs: TIM_FFB's clock over (PSC+1)(ARR+1).
  double update_rate_hz() const override {
    core::Hold hold;
    return hal::timer_update_rate_hz(TIM_FFB);
  }

 private:
  // On the control task, holding the core, as each control step wakes (move_stick says why).
  void control_step_woke() {
    control_steps_.fetch_add(1, std::memory_order_relaxed);
    if (!stick_path_) return;
    const std::array<double, 2> f = stick_path_(stick_t_s_);
    for (int a = 0; a < axes_; ++a)
      stick_link::axis(a).encoder_counts = static_cast<std::int32_t>(std::round(f[a] * stick_scale_[a]));
    stick_t_s_ += 1.0 / hal::timer_update_rate_hz(TIM_FFB);
  }

  const int axes_;
  std::atomic<std::uint64_t> control_steps_{0};
  StickPath stick_path_;  // the three stick_ members: read and written holding the core
  std::array<double, 2> stick_scale_{};
  double stick_t_s_ = 0;
  DeviceIdentity identity_;
  std::vector<std::uint8_t> descriptors_;
  std::uint8_t ep_in_ = 0x81;
  std::uint8_t ep_out_ = 0x01;
};

}  // namespace

std::unique_ptr<OpenFFBoardFirmware> OpenFFBoardFirmware::start(MainClass main) {
  static std::atomic<bool> started{false};
  if (started.exchange(true)) throw std::logic_error("OpenFFBoardFirmware::start: the firmware runs once per process");
  return std::make_unique<Firmware>(main);
}

}  // namespace sandpaper::usb_lab

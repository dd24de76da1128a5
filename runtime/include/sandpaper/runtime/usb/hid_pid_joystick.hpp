#pragma once
// A USB HID PID force-feedback joystick or wheel (USB HID PID 1.0) as a servo-loop Device: one
// constant-force effect per axis (a wheel's device file, [wheel], has one: x along the rim),
// streamed with Set Constant Force every tick; position from the input reports.
// The reference device is the OpenFFBoard as a 2-axis joystick (calibration/devices/openffboard-2axis.toml).
// Reports, order, rate and assumptions: docs/USB_PID.md.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <thread>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/runtime/device.hpp"
#include "sandpaper/runtime/usb/hid_descriptor.hpp"
#include "sandpaper/runtime/usb/transport.hpp"

namespace sandpaper::runtime::usb {

// Why the driver stopped playing (runtime/device.hpp): ReadTimedOut when no position report came for
// longer than HidPidOptions::stale_limit_s, ReadFailed for a failed input transfer (not a timeout,
// not an unplug), WriteFailed for a failed Set Constant Force, Unplugged when the transport reports
// no device. The servo loop reads it through last_fault_rt() and names the stop cause.
using sandpaper::runtime::DeviceFault;
const char* to_string(DeviceFault fault) noexcept;

// Where the USB transfers of a running joystick happen.
enum class HidPidIo {
  // Default: on the driver's own I/O thread. The servo tick only exchanges single-slot atomics with
  // it (the latest position in, the latest force out), so _rt calls never reach libusb, which
  // allocates and locks; a transfer that hangs stalls the I/O thread, never the tick.
  IoThread,
  // On the thread that calls read_position_rt / write_force_rt: for tests of the exact report
  // stream, tick by tick. Not real-time safe with a real transport.
  CallingThread,
};

struct HidPidOptions {
  // CallingThread: longest wait for an input report per read (a 1 kHz endpoint reports every 1 ms).
  // The I/O thread takes what has arrived without waiting.
  unsigned read_timeout_ms = 1;
  // Longest time without a position report before the read fails (the watchdog), s. 0: 50 ms, or
  // twice the device calibration's [usb] idle_report_period when that is longer (a handle held
  // still is not a device gone quiet).
  double stale_limit_s = 0;
  unsigned open_read_timeout_ms = 500;  // wait for the first position report while opening
  // How long an output report of the open sequence may keep timing out (the device NAKing it, as a
  // busy firmware does) before the open fails; each try waits the transport's own timeout.
  unsigned open_write_timeout_ms = 2000;
  // How long the whole shutdown sequence may spend resending reports that time out.
  unsigned close_timeout_ms = 500;
  HidPidIo io = HidPidIo::IoThread;
};

// Thrown when the device cannot be opened: the status names the transport's cause (NoDevice,
// AccessDenied, ...; Other for a descriptor without the reports the driver needs). The device has
// been given back (effects freed, interface released, kernel driver reattached) before it is thrown.
struct HidPidError : std::runtime_error {
  HidPidError(UsbStatus s, const std::string& what) : std::runtime_error(what), status(s) {}
  UsbStatus status;
};

class HidPidJoystick final : public HeldDevice {
 public:
  // Opens the device on `transport` (which must outlive this object) and creates the effects
  // (sequence in docs/USB_PID.md). Newtons become command units through `calibration`'s axis
  // scales; position logical ranges map onto its workspace width and height (centre = 0 m).
  // Throws HidPidError.
  HidPidJoystick(UsbTransport& transport, const calibration::DeviceCalibration& calibration,
                 HidPidOptions options = {});
  ~HidPidJoystick() override;
  HidPidJoystick(const HidPidJoystick&) = delete;
  HidPidJoystick& operator=(const HidPidJoystick&) = delete;

  const DeviceLimits& limits() const noexcept override { return limits_; }
  // The latest position (m) the device reported. IoThread: read from the I/O thread's slot, no
  // transfer; CallingThread: reads input reports here (waiting at most read_timeout_ms each).
  // False, with fault() set, when unplugged, on a failed transfer, or when no position report has
  // come for stale_limit_s of servo time (also when the I/O thread is stuck in a transfer).
  bool read_position_rt(double t_s, glm::dvec2& position_m) noexcept override;
  // True when that read found a position report the last one had not (IoThread: the I/O thread
  // received one since; CallingThread: one was read at this call).
  bool position_fresh_rt() const noexcept override { return fresh_; }
  // Set Constant Force for X then Y: magnitude = calibration command units for the force (N), times
  // the axis's command_sense (which way a positive magnitude pushes the handle on this device),
  // rounded and clamped to the Magnitude field's logical range and to +-command_max. IoThread:
  // publishes the pair for the I/O thread to send (false once it has failed); CallingThread: sends.
  bool write_force_rt(glm::dvec2 force_N) noexcept override;

  // IoThread: waits (up to `timeout_s`) until the I/O thread has sent the latest force published
  // and read past every input report queued before this call; true if it did. For tests and shutdown.
  bool flush_nonrt(double timeout_s = 1.0);

  // The shutdown sequence (zero force, stop, free, stop all, disable actuators, release, reattach);
  // best effort, each step tried whatever the previous returned. Idempotent; the destructor calls it.
  void close() noexcept;
  void close_nonrt() noexcept override { close(); }
  // to_string(fault_status()) after a fault, else "".
  std::string fault_detail_nonrt() const override;

  DeviceFault fault() const noexcept { return last_fault_rt(); }
  DeviceFault last_fault_rt() const noexcept override;
  UsbStatus fault_status() const noexcept;
  std::uint8_t effect_block_index(int axis) const noexcept { return block_index_[static_cast<std::size_t>(axis)]; }
  const HidReportDescriptor& descriptor() const noexcept { return descriptor_; }
  // Last magnitudes sent to the device (command units), X and Y.
  std::array<std::int32_t, 2> last_command() const noexcept;

 private:
  static constexpr std::size_t kMaxReport = 64;  // full-speed interrupt packet
  using Buffer = std::array<std::uint8_t, kMaxReport>;

  void open();
  void start_io_thread();
  void stop_io_thread() noexcept;
  void io_thread_body() noexcept;
  std::int32_t command_of(int axis, double force_N) const noexcept;
  void set_fault(DeviceFault fault, UsbStatus status) noexcept;
  void device_control(std::uint32_t command_usage);
  // An output report of the open or shutdown sequence, sent again while it times out (for up to
  // open_write_timeout_ms, or until close_deadline_ns_ once closing).
  UsbStatus write_open(std::span<const std::uint8_t> report) noexcept;
  // Fails the open naming the step, the report (type, ID) and its HID usage, and the transport's cause.
  [[noreturn]] void fail_step(UsbStatus status, const std::string& step, ReportType type, std::uint8_t report_id,
                              std::uint32_t report_usage);
  // The field that carries Device Control's `command_usage` (array or bit form), or nullptr.
  const HidField* device_control_field(std::uint32_t command_usage) const;
  void create_effect(int axis);
  // open() refused every report longer than a Buffer; the bound here only keeps that true.
  std::span<const std::uint8_t> report(const Buffer& b, std::size_t bytes) const { return {b.data(), std::min(bytes, b.size())}; }
  // Set Constant Force on `axis` with the transport's status; no fault set.
  UsbStatus write_constant_force(int axis, std::int32_t magnitude) noexcept;
  bool send_constant_force(int axis, std::int32_t magnitude) noexcept;
  bool decode_position(std::span<const std::uint8_t> report, glm::dvec2& position_m) const noexcept;
  [[noreturn]] void fail_open(UsbStatus status, const std::string& what);

  UsbTransport& transport_;
  calibration::DeviceCalibration calibration_;
  HidPidOptions options_;
  DeviceLimits limits_;
  HidReportDescriptor descriptor_;
  bool ids_ = false;
  int axes_ = 2;  // force axes played: 2, or 1 for a wheel (calibration [wheel]); y is then always 0

  // Fields the driver uses, copied out of the descriptor at open.
  HidField x_, y_;                     // input
  HidField magnitude_, cf_block_;      // Set Constant Force
  std::size_t cf_bytes_ = 0;
  std::array<Buffer, 2> cf_report_{};  // preformatted per axis; only the magnitude changes per tick
  Buffer input_{};

  bool detached_ = false, claimed_ = false, closed_ = false, actuators_enabled_ = false;
  std::int64_t close_deadline_ns_ = 0;  // CLOCK_MONOTONIC
  std::array<std::uint8_t, 2> block_index_{0, 0};  // 0: no effect created
  std::array<bool, 2> started_{false, false};
  std::array<std::atomic<std::int32_t>, 2> last_command_{};
  glm::dvec2 position_m_{0, 0};
  double last_report_t_s_ = 0;
  bool have_time_ = false;
  bool fresh_ = false;  // the servo thread's: what position_fresh_rt() returns
  // The first fault wins; written by whichever thread saw it, read by the tick.
  std::atomic<DeviceFault> fault_{DeviceFault::None};
  std::atomic<UsbStatus> fault_status_{UsbStatus::Ok};
  static_assert(std::atomic<DeviceFault>::is_always_lock_free && std::atomic<std::uint64_t>::is_always_lock_free);

  // The single-slot exchanges between the tick and the I/O thread (HidPidIo::IoThread).
  std::atomic<std::uint64_t> position_raw_{0};       // X, Y logical values (2 x 32 bits) of the latest report
  std::atomic<std::uint64_t> position_reports_{0};   // count of position reports decoded; the tick watches it change
  std::atomic<std::uint64_t> command_raw_{0};        // X, Y command units (2 x 32 bits) the tick wants
  std::atomic<std::uint64_t> command_published_{0};  // count of commands published by the tick
  std::atomic<std::uint64_t> command_sent_{0};       // the publication count the I/O thread last sent
  std::atomic<std::uint64_t> io_cycles_{0};          // I/O thread loop count (flush_nonrt)
  std::atomic<bool> io_running_{false};
  std::uint64_t seen_reports_ = 0;                   // tick side
  std::thread io_thread_;
};

}  // namespace sandpaper::runtime::usb

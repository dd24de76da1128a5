// sandpaper-lab-device: the OpenFFBoard firmware, compiled for the host, as a USB device on a
// FunctionFS mount, with the lab's simulated stick behind it; or (--model sidewinder-ff2) the lab's
// HID PID 1.0 device model with the SideWinder Force Feedback 2's recorded descriptor
// (usb-lab/hid_pid). Runs in the USB lab's guest (docs/USB_PID.md "In the lab"); the lab's scripts
// make the gadget and bind it once this prints its ready line.
#include <signal.h>
#include <time.h>

#include <CLI/CLI.hpp>
#include <array>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iostream>
#include <memory>
#include <thread>
#include <vector>

#include "bus_log.hpp"
#include "faulty_function.hpp"
#include "functionfs_device.hpp"
#include "hid_pid_device.hpp"
#include "logged_function.hpp"
#include "openffboard_firmware.hpp"
#include "scripted_hand.hpp"
#include "sidewinder_ff2.hpp"

using namespace sandpaper::usb_lab;

namespace {

// Moves the handle along the hand's path on the firmware's own update clock (move_stick says why),
// and calls `every_10ms` every 10 ms of the host's clock until `stop`.
void drive_stick(OpenFFBoardFirmware& firmware, const HandPath& path, double half_range_m, const std::atomic<bool>& stop,
                 const std::function<void()>& every_10ms) {
  firmware.move_stick([hand = ScriptedHand(path), half_range_m](double t_s) mutable {
    const HandPosition p = hand.at(t_s);
    return std::array<double, 2>{p.x_m / half_range_m, p.y_m / half_range_m};
  });
  timespec next{};
  clock_gettime(CLOCK_MONOTONIC, &next);
  while (!stop.load()) {
    every_10ms();
    next.tv_nsec += 10'000'000;
    if (next.tv_nsec >= 1'000'000'000) {
      next.tv_nsec -= 1'000'000'000;
      ++next.tv_sec;
    }
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
  }
  firmware.move_stick(nullptr);
}

// The HID PID model has no firmware clock: the hand moves on the steady clock, one position per
// 1 ms step (t is the time since the start, so a late step catches up rather than slowing the
// hand), and `every_10ms` runs every tenth step, until `stop`.
void drive_model_stick(HidPidDevice& model, const HandPath& path, double half_range_m, const std::atomic<bool>& stop,
                       const std::function<void()>& every_10ms) {
  ScriptedHand hand(path);
  timespec start{}, next{};
  clock_gettime(CLOCK_MONOTONIC, &start);
  next = start;
  for (std::uint64_t step = 0; !stop.load(); ++step) {
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    const double t_s = static_cast<double>(now.tv_sec - start.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec - start.tv_nsec);
    const HandPosition p = hand.at(t_s);
    model.set_position(0, p.x_m / half_range_m);
    model.set_position(1, p.y_m / half_range_m);
    if (step % 10 == 0) every_10ms();
    next.tv_nsec += 1'000'000;
    if (next.tv_nsec >= 1'000'000'000) {
      next.tv_nsec -= 1'000'000'000;
      ++next.tv_sec;
    }
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
  }
}

void write_state(const std::string& path, const FirmwareState& s, std::size_t dropped) {
  std::ofstream out(path + ".tmp");
  out << "{\"ffb_active\": " << (s.ffb_active ? "true" : "false")
      << ", \"actuators_enabled\": " << (s.actuators_enabled ? "true" : "false")
      << ", \"effects_in_use\": " << s.effects_in_use << ", \"torque\": [" << s.torque[0] << ", " << s.torque[1]
      << "], \"torque_updates\": [" << s.torque_updates[0] << ", " << s.torque_updates[1]
      << "], \"ffb_timer_updates\": " << s.ffb_timer_updates
      << ", \"ffb_timer_updates_dropped\": " << s.ffb_timer_updates_dropped
      << ", \"ffb_control_steps\": " << s.ffb_control_steps << ", \"log_records_dropped\": " << dropped
      << "}\n";
  out.close();
  std::filesystem::rename(path + ".tmp", path);
}

// The HID PID model's state under the firmware's keys where they mean the same (ffb_active:
// actuators enabled and not paused, the model's one force switch). The firmware's timer figures
// (ffb_timer_updates, ffb_timer_updates_dropped, ffb_control_steps) are null: the model has no
// FFB timer or control task, and a 0 would read as a starved guest. effects_playing is the model's own.
void write_state(const std::string& path, const HidPidDeviceState& s, std::size_t dropped) {
  std::ofstream out(path + ".tmp");
  out << "{\"ffb_active\": " << (s.actuators_enabled && !s.paused ? "true" : "false")
      << ", \"actuators_enabled\": " << (s.actuators_enabled ? "true" : "false")
      << ", \"effects_in_use\": " << s.effects_in_use << ", \"effects_playing\": " << s.effects_playing
      << ", \"torque\": [" << s.torque[0] << ", " << s.torque[1] << "], \"torque_updates\": [" << s.torque_updates[0]
      << ", " << s.torque_updates[1]
      << "], \"ffb_timer_updates\": null, \"ffb_timer_updates_dropped\": null, \"ffb_control_steps\": null"
      << ", \"log_records_dropped\": " << dropped << "}\n";
  out.close();
  std::filesystem::rename(path + ".tmp", path);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The OpenFFBoard firmware (or the lab's HID PID model of a SideWinder Force Feedback 2) as a USB device "
               "on a FunctionFS mount (the USB lab's joystick)"};
  std::string ffs, log_dir;
  HandPath path;
  double speed_mm_s = 100, extent_mm = 40, half_range_mm = 50;
  bool identity = false;
  app.add_flag("--identity", identity, "print the device's identity (key=value lines) for the gadget's configfs and exit");
  app.add_option("--ffs", ffs, "the FunctionFS mount (holds ep0)");
  app.add_option("--hand", path.kind, "the hand's path: still, scan (along x), circle")->capture_default_str();
  app.add_option("--speed", speed_mm_s, "the hand's speed along its path, mm/s")->capture_default_str();
  app.add_option("--extent", extent_mm, "scan stroke length or circle diameter, mm")->capture_default_str();
  std::vector<double> centre_mm{0, 0};
  app.add_option("--at", centre_mm, "where a still hand holds the handle, or the centre of a scan or circle: X Y in mm")
      ->expected(2)->capture_default_str();
  app.add_option("--half-range", half_range_mm,
                 "the handle travel from centre to the end the firmware reports as full scale, mm "
                 "(the device calibration's workspace half-width)")->capture_default_str();
  app.add_option("--log", log_dir, "write reports.csv, torque.csv and state.json here at exit");
  std::string model = "openffboard";
  app.add_option("--model", model,
                 "the device: openffboard (the firmware compiled for the host) or sidewinder-ff2 (the lab's HID PID 1.0 "
                 "model with the SideWinder Force Feedback 2's recorded descriptor, usb-lab/hid_pid)")
      ->check(CLI::IsMember({"openffboard", "sidewinder-ff2"}))
      ->capture_default_str();
  std::string main_class = "joystick";
  app.add_option("--main-class", main_class,
                 "the firmware's main class, as the board's flash chooses it: joystick (2 axes) or wheel (1 axis, "
                 "FFBWheel with its 1-axis descriptor; the hand's y is not read)")
      ->check(CLI::IsMember({"joystick", "wheel"}))
      ->capture_default_str();
  int stall_feature = -1;
  app.add_option("--stall-feature", stall_feature,
                 "refuse (STALL) every GET_REPORT and SET_REPORT of this Feature report ID, as a broken device does")
      ->check(CLI::Range(1, 255));
  int late_feature = -1;
  app.add_option("--late-feature", late_feature,
                 "answer every GET_REPORT of this Feature report ID late (--late-ms), as a device busy elsewhere does")
      ->check(CLI::Range(1, 255));
  int late_ms = 2000;
  app.add_option("--late-ms", late_ms, "how late --late-feature's answers are, ms")->check(CLI::Range(0, 60000))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  const bool ff2 = model == "sidewinder-ff2";
  if (ff2 && app.count("--main-class") > 0) {
    std::cerr << "sandpaper-lab-device: --main-class chooses the OpenFFBoard firmware's main class; not with --model " << model
              << "\n";
    return 2;
  }
  if (!identity && ffs.empty()) {
    std::cerr << "sandpaper-lab-device: --ffs is required (or --identity)\n";
    return 2;
  }
  path.speed_m_s = speed_mm_s * 1e-3;
  path.extent_m = extent_mm * 1e-3;
  path.centre_x_m = centre_mm[0] * 1e-3;
  path.centre_y_m = centre_mm[1] * 1e-3;
  try {
    (void)hand_position(path, 0);
  } catch (const std::exception& e) {
    std::cerr << "sandpaper-lab-device: " << e.what() << "\n";
    return 2;
  }

  // SIGINT and SIGTERM end the program and SIGUSR2 silences the input reports (the lab's
  // stale-position fault), all through sigwait below; blocked before any thread starts so that
  // every thread (the firmware's too) inherits the mask.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGUSR2);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  AppendLog<ReportRecord> reports(1 << 18);
  AppendLog<TorqueRecord> torques(1 << 19);
  try {
    // One of the two: the firmware (one per process, started as on the board) or the model.
    std::unique_ptr<OpenFFBoardFirmware> firmware;
    std::unique_ptr<HidPidDevice> hid_pid;
    if (ff2) hid_pid = sidewinder_ff2();
    else firmware = OpenFFBoardFirmware::start(main_class == "wheel" ? MainClass::Wheel : MainClass::Joystick);
    UsbFunction& function = firmware ? static_cast<UsbFunction&>(*firmware) : *hid_pid;
    if (identity) {
      const DeviceIdentity id = function.identity();
      std::printf("vendor_id=0x%04x\nproduct_id=0x%04x\nbcd_device=0x%04x\nbcd_usb=0x%04x\ndevice_class=0x%02x\n"
                  "device_subclass=0x%02x\ndevice_protocol=0x%02x\nmanufacturer=%s\nproduct=%s\nserial_number=%s\n"
                  "max_speed=%s\n",
                  id.vendor_id, id.product_id, id.bcd_device, id.bcd_usb, id.device_class, id.device_subclass,
                  id.device_protocol, id.manufacturer.c_str(), id.product.c_str(), id.serial_number.c_str(),
                  id.max_speed.c_str());
      std::fflush(stdout);
      std::_Exit(0);
    }
    const auto log_torque = [&](const TorqueUpdate& u) {
      const auto t = std::chrono::duration_cast<std::chrono::nanoseconds>(u.time.time_since_epoch()).count();
      torques.append(TorqueRecord{t, u.axis, u.torque});
    };
    if (firmware) firmware->on_torque(log_torque);
    else hid_pid->on_torque(log_torque);
    FaultyFunction faulty(function);
    if (stall_feature > 0) faulty.stall(ClassReport{3, static_cast<std::uint8_t>(stall_feature)});
    if (late_feature > 0)
      faulty.answer_late(ClassReport{3, static_cast<std::uint8_t>(late_feature)}, std::chrono::milliseconds(late_ms));
    LoggedFunction logged(faulty, reports);
    FunctionFsDevice device(ffs, logged);
    device.start();
    std::atomic<bool> stop{false};
    // "playing" once the host has started an effect per axis (two on the joystick, one on the wheel)
    // with force feedback on, then "streaming" once it has sent 200 more output reports (a hundred
    // servo ticks of Set Constant Force on two axes): the lab's scripts wait for that line before
    // they inject a fault into a running play.
    bool playing = false, streaming = false;
    std::uint64_t outputs_at_play = 0;
    const auto announce = [&] {
      if (streaming) return;
      if (!playing) {
        int effects = 0;
        if (firmware) {
          const FirmwareState s = firmware->state();
          if (!(s.ffb_active && s.effects_in_use >= firmware->axes())) return;
          effects = s.effects_in_use;
        } else {
          // The model: its actuators on and at least one effect playing.
          const HidPidDeviceState s = hid_pid->state();
          if (!(s.actuators_enabled && s.effects_playing >= 1)) return;
          effects = s.effects_playing;
        }
        std::printf("sandpaper-lab-device: playing (%d effects, force feedback on)\n", effects);
        playing = true;
        outputs_at_play = device.interrupt_out_transfers();
      } else if (device.interrupt_out_transfers() >= outputs_at_play + 200) {
        std::printf("sandpaper-lab-device: streaming (%llu output reports since playing)\n",
                    static_cast<unsigned long long>(device.interrupt_out_transfers() - outputs_at_play));
        streaming = true;
      }
      std::fflush(stdout);
    };
    std::thread stick([&] {
      if (firmware) drive_stick(*firmware, path, half_range_mm * 1e-3, stop, announce);
      else drive_model_stick(*hid_pid, path, half_range_mm * 1e-3, stop, announce);
    });
    if (firmware)
      std::printf("sandpaper-lab-device: ready on %s (firmware update rate %.0f Hz)\n", ffs.c_str(),
                  firmware->update_rate_hz());
    else
      std::printf("sandpaper-lab-device: ready on %s (HID PID model %s, hand at 1000 Hz)\n", ffs.c_str(), model.c_str());
    std::fflush(stdout);

    int signal = 0;
    while (sigwait(&stop_signals, &signal) == 0 && signal == SIGUSR2) {
      faulty.silence_input();
      std::printf("sandpaper-lab-device: input reports silenced\n");
      std::fflush(stdout);
    }
    stop.store(true);
    stick.join();
    device.stop();
    // The logs and the device's state (the firmware's or the model's) at exit, for the lab's checks.
    const auto write_logs = [&](const auto& state) {
      if (log_dir.empty()) return;
      write_report_log(log_dir + "/reports.csv", reports.records());
      write_torque_log(log_dir + "/torque.csv", torques.records());
      write_state(log_dir + "/state.json", state, reports.dropped() + torques.dropped());
    };
    if (hid_pid) {
      const HidPidDeviceState s = hid_pid->state();
      std::printf("sandpaper-lab-device: stopped (%s); HID PID model: actuators_enabled %d, effects %d (%d playing), "
                  "torque %d %d, interrupt OUT %llu, IN %llu\n",
                  signal == SIGINT ? "SIGINT" : "SIGTERM", s.actuators_enabled, s.effects_in_use, s.effects_playing,
                  s.torque[0], s.torque[1], static_cast<unsigned long long>(device.interrupt_out_transfers()),
                  static_cast<unsigned long long>(device.interrupt_in_transfers()));
      write_logs(s);
      std::fflush(stdout);
      std::_Exit(0);
    }
    const FirmwareState s = firmware->state();
    std::printf("sandpaper-lab-device: stopped (%s); firmware: ffb_active %d, actuators_enabled %d, effects %d, torque %d %d, "
                "interrupt OUT %llu, IN %llu; timer updates %llu run, %llu dropped late; control steps %llu\n",
                signal == SIGINT ? "SIGINT" : "SIGTERM", s.ffb_active, s.actuators_enabled, s.effects_in_use, s.torque[0],
                s.torque[1], static_cast<unsigned long long>(device.interrupt_out_transfers()),
                static_cast<unsigned long long>(device.interrupt_in_transfers()),
                static_cast<unsigned long long>(s.ffb_timer_updates),
                static_cast<unsigned long long>(s.ffb_timer_updates_dropped),
                static_cast<unsigned long long>(s.ffb_control_steps));
    write_logs(s);
    std::fflush(stdout);
    // The firmware's threads run forever, as on the board: leave without destroying it.
    std::_Exit(0);
  } catch (const std::exception& e) {
    std::cerr << "sandpaper-lab-device: " << e.what() << "\n";
    return 1;
  }
}

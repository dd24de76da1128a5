#pragma once
// Where the simulated motor drivers (firmware side, RmdMotorCAN.h) meet the lab's simulated stick
// (OpenFFBoardFirmware): per axis, the encoder position the stick sets and the torque the
// firmware commands. Lock-free for the position and the torque; the observer is set rarely.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>

namespace sandpaper::usb_lab::stick_link {

// One torque command as the driver received it: axis, MotorDriver::turn units, steady-clock time.
using TorqueObserver = std::function<void(int axis, std::int16_t torque, std::chrono::steady_clock::time_point)>;

struct Axis {
  std::atomic<std::int32_t> encoder_counts{0};  // the stick's position, counts_per_rotation per turn
  std::atomic<std::int16_t> torque{0};          // last torque the driver was commanded
  std::atomic<std::uint64_t> torque_updates{0};
  std::atomic<bool> driver_enabled{false};      // between startMotor() and stopMotor()
  std::atomic<bool> driver_exists{false};       // the firmware created this axis's driver
};

Axis& axis(int index);  // 0 = X, 1 = Y

void set_observer(TorqueObserver observer);
void publish_torque(int axis, std::int16_t torque);  // records the torque and calls the observer

}  // namespace sandpaper::usb_lab::stick_link

#pragma once
// A UsbFunction served through Linux FunctionFS (Documentation/usb/functionfs.rst): descriptors and
// strings written to ep0, every control request the kernel forwards answered by the function, its
// interrupt IN and OUT endpoints pumped by one thread each. The gadget (configfs, the UDC binding)
// is the lab script's; this only serves an ffs mount.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

#include "usb_function.hpp"

namespace sandpaper::usb_lab {

// What the front end saw on the bus, for the lab's measurements.
struct BusEvent {
  enum class Kind : std::uint8_t { Bind, Unbind, Enable, Disable, Setup, Suspend, Resume, Stalled };
  Kind kind;
  SetupPacket setup;  // for Setup and Stalled
};

class FunctionFsDevice {
 public:
  // `ffs_dir`: the mounted FunctionFS instance (holds ep0). Throws std::runtime_error naming the
  // file and errno when ep0 cannot be opened or the kernel refuses the descriptors.
  FunctionFsDevice(std::string ffs_dir, UsbFunction& function);
  ~FunctionFsDevice();
  FunctionFsDevice(const FunctionFsDevice&) = delete;
  FunctionFsDevice& operator=(const FunctionFsDevice&) = delete;

  // Writes descriptors and strings; once this returns the gadget can be bound to a UDC.
  void start(std::function<void(const BusEvent&)> on_event = {});
  // Stops the threads and closes the endpoint files (the kernel then sees the function go away).
  void stop();

  std::uint64_t interrupt_out_transfers() const { return out_transfers_.load(std::memory_order_relaxed); }
  std::uint64_t interrupt_in_transfers() const { return in_transfers_.load(std::memory_order_relaxed); }

 private:
  void ep0_loop();
  void handle_setup(const SetupPacket& setup);
  void open_endpoints();
  void close_endpoints();
  void out_loop();
  void in_loop();

  std::string dir_;
  UsbFunction& function_;
  std::function<void(const BusEvent&)> on_event_;
  int ep0_ = -1;
  std::atomic<int> ep_in_{-1}, ep_out_{-1};
  std::atomic<bool> stopping_{false}, enabled_{false};
  std::atomic<std::uint64_t> out_transfers_{0}, in_transfers_{0};
  std::thread ep0_thread_, out_thread_, in_thread_;
  std::atomic<bool> exited_[3] = {false, false, false};
};

}  // namespace sandpaper::usb_lab

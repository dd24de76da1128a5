#include "stick_link.hpp"

#include <array>

namespace sandpaper::usb_lab::stick_link {
namespace {

std::array<Axis, 2>& axes() {
  static auto* a = new std::array<Axis, 2>();  // never destroyed: firmware threads outlive statics
  return *a;
}

struct ObserverSlot {
  std::mutex mutex;
  TorqueObserver observer;
};

ObserverSlot& slot() {
  static auto* s = new ObserverSlot();
  return *s;
}

}  // namespace

Axis& axis(int index) { return axes().at(static_cast<std::size_t>(index)); }

void set_observer(TorqueObserver observer) {
  std::lock_guard lock(slot().mutex);
  slot().observer = std::move(observer);
}

void publish_torque(int index, std::int16_t torque) {
  const auto now = std::chrono::steady_clock::now();
  Axis& a = axis(index);
  a.torque = torque;
  a.torque_updates.fetch_add(1);
  std::lock_guard lock(slot().mutex);
  if (slot().observer) slot().observer(index, torque, now);
}

}  // namespace sandpaper::usb_lab::stick_link

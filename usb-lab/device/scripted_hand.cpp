#include "scripted_hand.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace sandpaper::usb_lab {

namespace {

// Turn point k (k >= 1) of a scan, relative to the centre: odd ones at the +x end, even ones at -x.
double turn_point(const HandPath& path, std::size_t k) {
  if (k == 0) return -path.extent_m / 2;
  const double golden = std::numbers::phi - 1;
  const double kg = static_cast<double>(k) * golden;
  const double beyond = path.extent_m / 2 + path.turn_spread_m * (kg - std::floor(kg));
  return k % 2 == 1 ? beyond : -beyond;
}

}  // namespace

ScriptedHand::ScriptedHand(HandPath path) : path_(std::move(path)), turn_at_m_{0.0} {
  if (path_.kind == "still") return;
  if (path_.kind != "scan" && path_.kind != "circle")
    throw std::invalid_argument("unknown hand path '" + path_.kind + "' (still, scan, circle)");
  if (!(path_.speed_m_s > 0) || !(path_.extent_m > 0))
    throw std::invalid_argument("the hand's speed and extent must be positive");
  if (!(path_.turn_spread_m >= 0)) throw std::invalid_argument("the hand's turn spread must not be negative");
}

HandPosition ScriptedHand::at(double t_s) {
  HandPosition p;
  const double travelled = path_.speed_m_s * std::max(0.0, t_s);
  if (path_.kind == "scan") {
    // Passed turn points are kept, so rising times extend the list by a stroke now and then.
    while (turn_at_m_.back() <= travelled) {
      const std::size_t k = turn_at_m_.size();
      turn_at_m_.push_back(turn_at_m_.back() + std::abs(turn_point(path_, k) - turn_point(path_, k - 1)));
    }
    const auto next = std::upper_bound(turn_at_m_.begin(), turn_at_m_.end(), travelled);
    const std::size_t stroke = static_cast<std::size_t>(next - turn_at_m_.begin()) - 1;
    const double from = turn_point(path_, stroke), along = travelled - turn_at_m_[stroke];
    p.x_m = stroke % 2 == 0 ? from + along : from - along;
  } else if (path_.kind == "circle") {
    const double r = path_.extent_m / 2;
    const double angle = travelled / r;
    p = {r * std::cos(angle), r * std::sin(angle)};
  }
  return {p.x_m + path_.centre_x_m, p.y_m + path_.centre_y_m};
}

HandPosition hand_position(const HandPath& path, double t_s) { return ScriptedHand(path).at(t_s); }

}  // namespace sandpaper::usb_lab

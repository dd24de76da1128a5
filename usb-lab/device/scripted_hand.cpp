#include "scripted_hand.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace sandpaper::usb_lab {

namespace {

HandPosition relative_position(const HandPath& path, double t_s) {
  if (path.kind == "still") return {};
  if (!(path.speed_m_s > 0) || !(path.extent_m > 0))
    throw std::invalid_argument("the hand's speed and extent must be positive");
  const double travelled = path.speed_m_s * t_s;
  if (path.kind == "scan") {
    const double stroke = path.extent_m;
    const double phase = std::fmod(travelled, 2 * stroke);
    const double along = phase < stroke ? phase : 2 * stroke - phase;
    return {along - stroke / 2, 0};
  }
  if (path.kind == "circle") {
    const double r = path.extent_m / 2;
    const double angle = travelled / r;
    return {r * std::cos(angle), r * std::sin(angle)};
  }
  throw std::invalid_argument("unknown hand path '" + path.kind + "' (still, scan, circle)");
}

}  // namespace

HandPosition hand_position(const HandPath& path, double t_s) {
  const HandPosition p = relative_position(path, t_s);
  return {p.x_m + path.centre_x_m, p.y_m + path.centre_y_m};
}

}  // namespace sandpaper::usb_lab

#pragma once
// The hand on the lab's simulated stick: a scripted path the handle follows exactly (the hand is
// stiff against the firmware's torque), as `sandpaper run --hand scan|circle --speed` moves the
// simulated hand. Positions in metres, handle centre = 0.
#include <string>

namespace sandpaper::usb_lab {

struct HandPath {
  std::string kind = "still";   // still, scan (back and forth along x), circle
  double speed_m_s = 0.1;       // along the path
  double extent_m = 0.04;       // scan: the stroke's length; circle: its diameter
  double centre_x_m = 0, centre_y_m = 0;  // still: where the hand holds the handle; scan, circle: their centre
};

struct HandPosition {
  double x_m = 0, y_m = 0;
};

// Where the hand is `t_s` seconds after it started, relative to the centre. Scan: starts at
// -extent/2 moving +x, turns
// at each end (a triangle wave); circle: counter-clockwise from (+extent/2, 0). Throws
// std::invalid_argument for an unknown kind or a non-positive speed or extent.
HandPosition hand_position(const HandPath& path, double t_s);

}  // namespace sandpaper::usb_lab

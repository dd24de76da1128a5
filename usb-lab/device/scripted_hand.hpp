#pragma once
// The hand on the lab's simulated stick: a scripted path the handle follows exactly (the hand is
// stiff against the firmware's torque), as `sandpaper run --hand scan|circle --speed` moves the
// simulated hand. Positions in metres, handle centre = 0.
#include <string>
#include <vector>

namespace sandpaper::usb_lab {

struct HandPath {
  std::string kind = "still";   // still, scan (back and forth along x), circle
  double speed_m_s = 0.1;       // along the path
  double extent_m = 0.04;       // scan: the stroke's length (before turn_spread_m); circle: its diameter
  double centre_x_m = 0, centre_y_m = 0;  // still: where the hand holds the handle; scan, circle: their centre
  // scan: each turn point lies up to this much beyond the stroke's end, by the golden-ratio sequence
  // frac(k phi). The firmware moves the hand once a control step, speed / rate apart; strokes of one
  // length that is a whole number of those steps (40 mm at 100 mm/s and 1 kHz: 400) put every
  // stroke's samples at the same places on a grating, and with a period a whole number of steps
  // (corduroy's 3.2 mm: 32) every ridge at one phase, so a run measured one phase, not the mean
  // over phases explain predicts (docs/DEVICES.md "A wheel").
  double turn_spread_m = 1e-3;
};

struct HandPosition {
  double x_m = 0, y_m = 0;
};

// The hand's position `t_s` seconds after it started, relative to the path's centre plus the
// centre. Scan: starts at -extent/2 moving +x and turns at the moving turn points above (a
// triangle wave of varying stroke); circle: counter-clockwise from (+extent/2, 0). Keeps the turn
// points it has passed, so a caller asking for rising times (the firmware's steps) does O(1) work
// per call. Throws std::invalid_argument for an unknown kind, a non-positive speed or extent, or a
// negative turn spread.
class ScriptedHand {
 public:
  explicit ScriptedHand(HandPath path);
  HandPosition at(double t_s);

 private:
  HandPath path_;
  std::vector<double> turn_at_m_;  // distance travelled at each turn point passed so far (0: the start)
};

// ScriptedHand(path).at(t_s), for a single look.
HandPosition hand_position(const HandPath& path, double t_s);

}  // namespace sandpaper::usb_lab

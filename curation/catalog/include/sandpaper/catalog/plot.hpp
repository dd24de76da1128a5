#pragma once
// The catalog's force plot: the lateral force a hand feels moving along a scan line through the patch
// centre (along x at y = 0, or along the normal of the program's first grating), computed by the
// runtime's evaluator (runtime/patch_evaluator.hpp, the code the servo loop plays), drawn as SVG with
// axes in mm and N.
#include <cmath>
#include <string>
#include <vector>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::catalog {

// The drawn curve leaves out samples that lie within this many pixels (of the 640 x 296 viewBox)
// of the line through the samples kept (Ramer-Douglas-Peucker): the same picture, far fewer bytes.
inline constexpr double kPlotTolerancePx = 0.2;

struct ForceScan {
  double direction[2] = {1, 0};  // unit vector of the scan
  std::string axis;              // "x" (along x at y = 0) or "u" (along the grating normal)
  std::string description;       // "along x at y = 0", "along the grating normal (45 deg)"
  double speed_m_s = 0;          // the hand's speed along the scan
  std::vector<double> s_m;       // position along the scan, m (0 at the patch centre)
  std::vector<double> along_N;   // force component along the scan direction, N
  std::vector<double> across_N;  // component 90 deg anticlockwise from it, N
  bool has_across() const;       // any |across| above 0.1 % of the largest |along| (or nonzero if along is 0)
};

// Scans from -half_length_m to +half_length_m along the direction at speed_m_s, `points` samples
// equally spaced: a fresh evaluator, reset with the hand at the start, then one force_rt per sample,
// dt = spacing / speed, so dampers, nap and stateful terms act as they would under a moving hand.
// Throws std::invalid_argument for points < 2, half_length_m <= 0 or speed_m_s <= 0.
ForceScan scan_force(const schema::PatchProgram& program, double half_length_m, double speed_m_s = 0.05,
                     int points = 2001);
// The scan's direction: the first grating's normal, else +x.
void scan_direction(const schema::PatchProgram& program, double out[2], std::string& axis, std::string& description);
// Longest half-length through the centre along the direction that stays inside a w x h rectangle (m).
double half_length_inside(const double direction[2], double width_m, double height_m);

// Plot geometry: data ranges and the SVG's pixel box, and the tick values (mm, N).
struct PlotAxes {
  double x_min_mm = 0, x_max_mm = 0, y_min_N = 0, y_max_N = 0;
  double left = 66, right = 626, top = 26, bottom = 244;  // plot box in SVG pixels (viewBox 640 x 296)
  std::vector<double> x_ticks_mm, y_ticks_N;
  double x_px(double mm) const;
  double y_px(double newtons) const;
};
// Ranges and ticks (1, 2 or 5 times a power of ten; 4 to 10 ticks) for a scan.
PlotAxes plot_axes(const ForceScan& scan);
// "1, 2, 5 x 10^k" steps that divide [lo, hi] into about `target` intervals.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);
// Which of the points (x[i], y[i]) a line drawn through only them keeps within `tolerance` of every
// point (Ramer-Douglas-Peucker; same units as x and y): 1 to keep. The first and last are kept.
std::vector<char> kept_points(const std::vector<double>& x, const std::vector<double>& y, double tolerance);
// Inline SVG (role="img"), with the along-scan force as a polyline of class "force-along" (one
// point per sample, in order) and, if any, the across force as "force-across"; axis labels
// "<axis> (mm)" and "lateral force (N)" in elements of class "axis-label".
std::string force_plot_svg(const ForceScan& scan, const std::string& title);

}  // namespace sandpaper::catalog

// Lateral force along a scan line, and its SVG plot (plot.hpp).
#include "sandpaper/catalog/plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "sandpaper/catalog/html.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"

namespace sandpaper::catalog {

bool ForceScan::has_across() const {
  double a = 0, c = 0;
  for (double v : along_N) a = std::max(a, std::abs(v));
  for (double v : across_N) c = std::max(c, std::abs(v));
  return a > 0 ? c > 1e-3 * a : c > 0;
}

void scan_direction(const schema::PatchProgram& program, double out[2], std::string& axis, std::string& description) {
  for (const auto& t : program.terms)
    if (const auto* g = std::get_if<schema::GratingTerm>(&t)) {
      out[0] = std::cos(g->orientation_rad);
      out[1] = std::sin(g->orientation_rad);
      axis = "u";
      description = "along the grating normal (" + format_number(g->orientation_rad * 180 / std::numbers::pi, 3) +
                    "\xC2\xB0 from x), through the patch centre";
      return;
    }
  out[0] = 1;
  out[1] = 0;
  axis = "x";
  description = "along x at y = 0";
}

double half_length_inside(const double direction[2], double width_m, double height_m) {
  double h = std::numeric_limits<double>::infinity();
  if (std::abs(direction[0]) > 1e-12) h = std::min(h, 0.5 * width_m / std::abs(direction[0]));
  if (std::abs(direction[1]) > 1e-12) h = std::min(h, 0.5 * height_m / std::abs(direction[1]));
  return h;
}

ForceScan scan_force(const schema::PatchProgram& program, double half_length_m, double speed_m_s, int points) {
  if (points < 2 || !(half_length_m > 0) || !(speed_m_s > 0))
    throw std::invalid_argument("scan_force: needs 2 or more points, a positive half-length and a positive speed");
  ForceScan scan;
  scan_direction(program, scan.direction, scan.axis, scan.description);
  scan.speed_m_s = speed_m_s;
  const glm::dvec2 d{scan.direction[0], scan.direction[1]};
  const glm::dvec2 across{-d.y, d.x};
  const double step = 2 * half_length_m / (points - 1);
  const double dt = step / speed_m_s;
  runtime::PatchEvaluator eval(program);
  runtime::HandState hand;
  hand.velocity_m_s = d * speed_m_s;
  for (int i = 0; i < points; ++i) {
    // The last sample is placed exactly, not accumulated, so the scan ends where it says.
    const double s = i + 1 == points ? half_length_m : -half_length_m + i * step;
    hand.position_m = d * s;
    if (i == 0) eval.reset_rt(hand);
    const glm::dvec2 f = eval.force_rt(hand, i == 0 ? 0.0 : dt);
    scan.s_m.push_back(s);
    scan.along_N.push_back(f.x * d.x + f.y * d.y);
    scan.across_N.push_back(f.x * across.x + f.y * across.y);
  }
  return scan;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo)) return {lo};
  const double raw = (hi - lo) / target;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * p;
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) {
      step = m * p;
      break;
    }
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step)
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  return ticks;
}

double PlotAxes::x_px(double v) const { return left + (v - x_min_mm) / (x_max_mm - x_min_mm) * (right - left); }
double PlotAxes::y_px(double v) const { return bottom - (v - y_min_N) / (y_max_N - y_min_N) * (bottom - top); }

PlotAxes plot_axes(const ForceScan& scan) {
  PlotAxes a;
  a.x_min_mm = scan.s_m.front() * 1e3;
  a.x_max_mm = scan.s_m.back() * 1e3;
  double peak = 0;
  for (double v : scan.along_N) peak = std::max(peak, std::abs(v));
  if (scan.has_across())
    for (double v : scan.across_N) peak = std::max(peak, std::abs(v));
  if (!(peak > 0)) peak = 1;  // no force anywhere: still draw a +-1 N frame
  // Symmetric about zero, with a margin, rounded out to a tick.
  const auto yt = nice_ticks(-peak * 1.05, peak * 1.05, 6);
  const double ystep = yt.size() > 1 ? yt[1] - yt[0] : peak;
  a.y_max_N = std::ceil(peak * 1.05 / ystep - 1e-9) * ystep;
  a.y_min_N = -a.y_max_N;
  a.y_ticks_N = nice_ticks(a.y_min_N, a.y_max_N, 6);
  a.x_ticks_mm = nice_ticks(a.x_min_mm, a.x_max_mm, 8);
  return a;
}

namespace {

std::string px(double v) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(2);
  os << v;
  return os.str();
}

// Ramer-Douglas-Peucker: marks the points to keep so that no dropped point is further than `tol`
// from the line drawn. A 2001-sample scan in a 560-pixel plot is most of a page's bytes; kept
// within kPlotTolerancePx it draws the same picture.
void simplify(const std::vector<double>& x, const std::vector<double>& y, std::size_t i, std::size_t j, double tol,
              std::vector<char>& keep) {
  // Iterative, so that a long noisy scan cannot exhaust the stack.
  std::vector<std::pair<std::size_t, std::size_t>> todo{{i, j}};
  while (!todo.empty()) {
    const auto [a, b] = todo.back();
    todo.pop_back();
    if (b <= a + 1) continue;
    const double dx = x[b] - x[a], dy = y[b] - y[a], len = std::hypot(dx, dy);
    double worst = -1;
    std::size_t at = a;
    for (std::size_t k = a + 1; k < b; ++k) {
      const double d = len > 0 ? std::abs(dy * (x[k] - x[a]) - dx * (y[k] - y[a])) / len : std::hypot(x[k] - x[a], y[k] - y[a]);
      if (d > worst) worst = d, at = k;
    }
    if (worst > tol) {
      keep[at] = 1;
      todo.push_back({a, at});
      todo.push_back({at, b});
    }
  }
}

std::string polyline(const PlotAxes& a, const ForceScan& scan, const std::vector<double>& f, const char* cls) {
  std::vector<double> x(f.size()), y(f.size());
  for (std::size_t i = 0; i < f.size(); ++i) x[i] = a.x_px(scan.s_m[i] * 1e3), y[i] = a.y_px(f[i]);
  const auto keep = kept_points(x, y, kPlotTolerancePx);
  std::string s = "<polyline class=\"" + std::string(cls) + "\" fill=\"none\" points=\"";
  bool first = true;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!keep[i]) continue;
    if (!first) s += ' ';
    first = false;
    s += px(x[i]) + "," + px(y[i]);
  }
  return s + "\"/>\n";
}

}  // namespace

std::vector<char> kept_points(const std::vector<double>& x, const std::vector<double>& y, double tolerance) {
  std::vector<char> keep(x.size(), 0);
  if (!x.empty()) keep.front() = keep.back() = 1;
  if (x.size() > 2) simplify(x, y, 0, x.size() - 1, tolerance, keep);
  return keep;
}

std::string force_plot_svg(const ForceScan& scan, const std::string& title) {
  const PlotAxes a = plot_axes(scan);
  std::ostringstream o;
  o << "<svg class=\"force-plot\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 640 296\" role=\"img\" "
       "aria-labelledby=\"plot-title\">\n<title id=\"plot-title\">"
    << html_escape(title) << "</title>\n";
  o << "<rect class=\"frame\" x=\"" << px(a.left) << "\" y=\"" << px(a.top) << "\" width=\"" << px(a.right - a.left)
    << "\" height=\"" << px(a.bottom - a.top) << "\" fill=\"none\"/>\n";
  o << "<g class=\"ticks x\">\n";
  for (double t : a.x_ticks_mm) {
    const double x = a.x_px(t);
    o << "<line class=\"grid\" x1=\"" << px(x) << "\" y1=\"" << px(a.top) << "\" x2=\"" << px(x) << "\" y2=\"" << px(a.bottom)
      << "\"/><line x1=\"" << px(x) << "\" y1=\"" << px(a.bottom) << "\" x2=\"" << px(x) << "\" y2=\"" << px(a.bottom + 5)
      << "\"/><text x=\"" << px(x) << "\" y=\"" << px(a.bottom + 18) << "\" text-anchor=\"middle\">" << format_number(t, 4)
      << "</text>\n";
  }
  o << "</g>\n<g class=\"ticks y\">\n";
  for (double t : a.y_ticks_N) {
    const double y = a.y_px(t);
    o << "<line class=\"grid" << (t == 0 ? " zero" : "") << "\" x1=\"" << px(a.left) << "\" y1=\"" << px(y) << "\" x2=\""
      << px(a.right) << "\" y2=\"" << px(y) << "\"/><line x1=\"" << px(a.left - 5) << "\" y1=\"" << px(y) << "\" x2=\""
      << px(a.left) << "\" y2=\"" << px(y) << "\"/><text x=\"" << px(a.left - 8) << "\" y=\"" << px(y + 4)
      << "\" text-anchor=\"end\">" << format_number(t, 4) << "</text>\n";
  }
  o << "</g>\n";
  if (scan.has_across()) o << polyline(a, scan, scan.across_N, "force-across");
  o << polyline(a, scan, scan.along_N, "force-along");
  const std::string xlabel = scan.axis == "u" ? "position along the grating normal, u (mm)" : "position along the scan, x (mm)";
  o << "<text class=\"axis-label x\" x=\"" << px(0.5 * (a.left + a.right)) << "\" y=\"288\" text-anchor=\"middle\">"
    << html_escape(xlabel) << "</text>\n";
  o << "<text class=\"axis-label y\" transform=\"translate(15 " << px(0.5 * (a.top + a.bottom))
    << ") rotate(-90)\" text-anchor=\"middle\">lateral force (N)</text>\n";
  if (scan.has_across())
    o << "<g class=\"legend\"><line class=\"force-along\" x1=\"" << px(a.right - 250) << "\" y1=\"13\" x2=\""
      << px(a.right - 230) << "\" y2=\"13\"/><text x=\"" << px(a.right - 225) << "\" y=\"17\">along the scan</text>"
      << "<line class=\"force-across\" x1=\"" << px(a.right - 90) << "\" y1=\"13\" x2=\"" << px(a.right - 70)
      << "\" y2=\"13\"/><text x=\"" << px(a.right - 65) << "\" y=\"17\">across it</text></g>\n";
  o << "</svg>\n";
  return o.str();
}

}  // namespace sandpaper::catalog

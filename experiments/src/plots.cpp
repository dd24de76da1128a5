#include "sandpaper/experiment/plots.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace sandpaper::experiment {
namespace {

// Steps of 1, 2 or 5 x 10^k dividing [lo, hi] into about `target` intervals.
std::vector<double> ticks(double lo, double hi, int target = 6) {
  if (!(hi > lo)) hi = lo + 1;
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * mag) {
      step = m * mag;
      break;
    }
  std::vector<double> out;
  for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) out.push_back(std::abs(v) < step * 1e-9 ? 0 : v);
  return out;
}

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

// A plot box with linear axes over [x0, x1] x [y0, y1], in a 640 x 400 SVG.
struct Frame {
  double x0, x1, y0, y1;
  double left = 70, right = 620, top = 40, bottom = 340;
  double px(double x) const { return left + (x - x0) / (x1 - x0) * (right - left); }
  double py(double y) const { return bottom - (y - y0) / (y1 - y0) * (bottom - top); }
};

std::string open_svg(const std::string& title, int width = 640, int height = 400) {
  return fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {0} {1}\" width=\"{0}\" height=\"{1}\" role=\"img\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n<title>{2}</title>\n<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n"
      "<text x=\"{3}\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">{2}</text>\n",
      width, height, escape(title), width / 2);
}

std::string axes(const Frame& f, const std::string& xlabel, const std::string& ylabel) {
  std::string out = fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#444\"/>\n", f.left,
                                f.top, f.right - f.left, f.bottom - f.top);
  for (double t : ticks(f.x0, f.x1))
    out += fmt::format("<line x1=\"{0:.1f}\" x2=\"{0:.1f}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#444\"/>"
                       "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4:g}</text>\n",
                       f.px(t), f.bottom, f.bottom + 5, f.bottom + 19, t);
  for (double t : ticks(f.y0, f.y1))
    out += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2:.1f}\" y2=\"{2:.1f}\" stroke=\"#444\"/>"
                       "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:g}</text>\n",
                       f.left - 5, f.left, f.py(t), f.left - 8, f.py(t) + 4, t);
  out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", (f.left + f.right) / 2, f.bottom + 40,
                     escape(xlabel));
  out += fmt::format("<text transform=\"translate(18 {}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                     (f.top + f.bottom) / 2, escape(ylabel));
  return out;
}

}  // namespace

std::string magnitude_plot_svg(const calibration::MagnitudeEstimationFit& fit, const std::vector<EstimatePoint>& trials,
                               const std::string& title) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  auto extend = [&](double x, double y) {
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  };
  for (const auto& p : trials) extend(std::log10(p.x), std::log10(p.estimate));
  for (const auto& s : fit.stimuli) extend(std::log10(s.x), std::log10(s.mean_response));
  const auto& xp = fit.predictor;
  const std::string unit = xp.unit == "1" ? "" : " " + xp.unit;
  const double mx = (x1 - x0) * 0.05 + 1e-3, my = (y1 - y0) * 0.05 + 1e-3;
  Frame f{x0 - mx, x1 + mx, y0 - my, y1 + my};
  std::string out = open_svg(title);
  out += axes(f, "log10 " + xp.quantity + (xp.unit == "1" ? "" : " (" + xp.unit + ")"), "log10 normalised estimate");
  for (const auto& p : trials)
    out += fmt::format("<circle class=\"trial\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"2\" fill=\"#2a6fdb\" fill-opacity=\"0.7\"/>\n",
                       f.px(std::log10(p.x)), f.py(std::log10(p.estimate)));
  for (const auto& s : fit.stimuli)
    out += fmt::format("<circle class=\"mean\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4.5\" fill=\"#c33\"><title>{}: {:.4g}{}, "
                       "mean {:.4g}</title></circle>\n",
                       f.px(std::log10(s.x)), f.py(std::log10(s.mean_response)), escape(s.stimulus), s.x, escape(unit),
                       s.mean_response);
  const double a = fit.intercept(), b = fit.slope();
  out += fmt::format("<line class=\"fit\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#222\" stroke-width=\"2\"/>\n",
                     f.px(x0), f.py(a + b * x0), f.px(x1), f.py(a + b * x1));
  const auto& r = fit.force;
  out += fmt::format("<text x=\"{}\" y=\"{}\">log P = {:.3f} log {} {} {:.3f}; slope s.e. {:.3f}, R^2 {:.3f}, s {:.3g}, "
                     "df {}, F {:.0f}</text>\n",
                     f.left + 8, f.top + 16, b, escape(xp.name), a < 0 ? "-" : "+", std::abs(a), fit.slope_se(), r.r_squared, r.s,
                     r.df_residual, r.f_ratio);
  out += fmt::format("<text x=\"{}\" y=\"{}\" fill=\"#555\">{} stimuli (red: geometric mean per stimulus), {} subjects, "
                     "{} answered trials (blue)</text>\n",
                     f.left + 8, f.top + 32, fit.stimuli.size(), fit.subjects.size(), fit.answered);
  return out + "</svg>\n";
}

std::string dendrogram_svg(const std::vector<std::string>& labels, const std::vector<Merge>& merges,
                           const std::string& title, const std::string& height_label) {
  const std::size_t n = labels.size();
  const auto order = leaf_order(merges, n);
  double hmax = 0;
  for (const auto& m : merges) hmax = std::max(hmax, m.height);
  Frame f{0, static_cast<double>(n), 0, hmax > 0 ? hmax * 1.05 : 1};
  f.bottom = 300;
  std::string out = open_svg(title);
  // Vertical axis only: leaves are categories.
  for (double t : ticks(f.y0, f.y1))
    out += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2:.1f}\" y2=\"{2:.1f}\" stroke=\"#ccc\"/>"
                       "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:g}</text>\n",
                       f.left, f.right, f.py(t), f.left - 8, f.py(t) + 4, t);
  out += fmt::format("<text transform=\"translate(18 {}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                     (f.top + f.bottom) / 2, escape(height_label));
  std::vector<double> x(2 * n, 0), y(2 * n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const auto leaf = static_cast<std::size_t>(order[k]);
    x[leaf] = f.px(static_cast<double>(k) + 0.5);
    y[leaf] = f.py(0);
    out += fmt::format("<text class=\"leaf\" transform=\"translate({:.1f} {:.1f}) rotate(60)\">{}</text>\n", x[leaf] - 3,
                       f.bottom + 10, escape(labels[leaf]));
  }
  for (std::size_t m = 0; m < merges.size(); ++m) {
    const auto a = static_cast<std::size_t>(merges[m].a), b = static_cast<std::size_t>(merges[m].b);
    const double h = f.py(merges[m].height);
    out += fmt::format("<path class=\"link\" d=\"M{:.1f} {:.1f}V{:.1f}H{:.1f}V{:.1f}\" fill=\"none\" stroke=\"#246\" stroke-width=\"1.5\"/>\n",
                       x[a], y[a], h, x[b], y[b]);
    x[n + m] = (x[a] + x[b]) / 2;
    y[n + m] = h;
  }
  return out + "</svg>\n";
}

std::string psychometric_svg(const PsychometricFit& fit, const std::vector<ProportionPoint>& points, const std::string& title) {
  double x1 = 0;
  for (const auto& p : points) x1 = std::max(x1, p.increment);
  Frame f{0, x1 * 1.1, 0.4, 1.06};
  std::string out = open_svg(title);
  out += axes(f, "force increment of the comparison (fraction of the standard)", "proportion correct");
  std::string path;
  for (int i = 0; i <= 100; ++i) {
    const double d = f.x1 * i / 100.0;
    path += fmt::format("{}{:.1f} {:.1f}", i == 0 ? "M" : "L", f.px(d), f.py(d > 0 ? fit.p_correct(d) : 0.5));
  }
  out += "<path class=\"fit\" d=\"" + path + "\" fill=\"none\" stroke=\"#222\" stroke-width=\"2\"/>\n";
  for (const auto& p : points)
    out += fmt::format("<circle class=\"point\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{:.1f}\" fill=\"#c33\"><title>{:g}: {:.3f} "
                       "of {}</title></circle>\n",
                       f.px(p.increment), f.py(p.proportion), 2.5 + std::sqrt(p.trials) * 0.4, p.increment, p.proportion,
                       p.trials);
  out += fmt::format("<line x1=\"{0:.1f}\" x2=\"{0:.1f}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#c33\" stroke-dasharray=\"4 3\"/>\n",
                     f.px(std::min(fit.weber_fraction, f.x1)), f.top, f.bottom);
  out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">Weber fraction (75 % correct) {:.3f}, 95 % interval {:.3f} "
                     "to {:.3f}; {} trials</text>\n",
                     f.right - 8, f.bottom - 12, fit.weber_fraction, fit.weber_low, fit.weber_high, fit.trials);
  return out + "</svg>\n";
}

}  // namespace sandpaper::experiment

// Writes a fitted map in the format of docs/CALIBRATION.md (schema/files/map.schema.json).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include <fmt/format.h>

#include "sandpaper/calibration/fit.hpp"
#include "sandpaper/calibration/fit_error.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "toml_text.hpp"

namespace sandpaper::calibration {
namespace {

using detail::toml_float;
using detail::toml_string;

// `value` written with 6 significant digits, rounded outward (down for a range's low end, up for
// its high end) so that the written domain still contains every stimulus.
// A dimensionless quantity (unit "1", the friction coefficient) is written as a bare number.
std::string bound_text(double value, const std::string& unit, bool upper) {
  const std::string suffix = unit == "1" ? "" : " " + unit;
  double v = value;
  for (int i = 0; i < 4; ++i) {
    const std::string s = fmt::format("{:.6g}", v);
    const double back = std::strtod(s.c_str(), nullptr);  // stod throws on a subnormal (F31)
    if (upper ? back >= value : back <= value) return s + suffix;
    v = upper ? v * (1 + 1e-6) : v * (1 - 1e-6);
  }
  return fmt::format("{:.17g}{}", value, suffix);
}

void coefficient_lines(std::string& out, const Coefficient& c) {
  out += fmt::format("se = {}\nt = {}\np = {}\n", toml_float(c.se), toml_float(c.t, 4), toml_float(c.p, 3));
}

}  // namespace

std::string quantity_text(double value, const char* unit) {
  return std::string(unit) == "1" ? fmt::format("{:.6g}", value) : fmt::format("{:.6g} {}", value, unit);
}

std::string map_file_text(const MagnitudeEstimationFit& fit, const MapFileOptions& o) {
  const auto& r = fit.force;
  const auto& slope = r.coefficient(fit.slope_name());
  const auto& constant = r.coefficient("constant");
  const FitPredictor& x = fit.predictor;
  const char* unit = x.unit.c_str();
  // The compiler turns a roughness into a force by the inverse power, 1 / slope: a map with slope 0
  // is refused by its loader, so it is not written (a balanced design whose means
  // do not move with force).
  if (slope.value == 0)
    throw FitError(fit.path, 0,
                   "the fitted slope is 0: in these data the estimates do not change with " + x.name + ", and a map needs a "
                   "slope to turn a " + o.percept + " into a " + x.name + "; nothing is written");
  double fmin = fit.stimuli.front().x, fmax = fmin, pmin = fit.stimuli.front().period_m, pmax = pmin;
  for (const auto& s : fit.stimuli) {
    fmin = std::min(fmin, s.x);
    fmax = std::max(fmax, s.x);
    pmin = std::min(pmin, s.period_m);
    pmax = std::max(pmax, s.period_m);
  }
  const std::string id = o.id.empty() ? "fitted-" + o.percept : o.id;
  const std::string description =
      o.description.empty() ? "perceived " + o.percept + " against " + x.quantity + ", fitted by sandpaper calibrate fit"
                            : o.description;
  const bool normalised = fit.normalisation == Normalisation::GeometricMean;
  const std::string normalisation =
      normalised ? "free-modulus magnitude estimation; each subject's estimates divided by their geometric mean and "
                   "multiplied by the grand geometric mean (Lane, Catania & Stevens 1961); geometric mean per stimulus "
                   "over subjects and runs"
                 : "none: raw estimates; geometric mean per stimulus over subjects and runs";

  std::string out;
  if (!o.provenance.empty()) out += "# " + o.provenance + "\n";
  out += fmt::format("# Fitted by `sandpaper {}` from the magnitude estimates in {}:\n",
                     o.provenance.empty() ? "calibrate fit" : "experiment analyse", fit.path);
  out += fmt::format("# {} trials ({} answered), {} subjects, {} stimuli, {} runs. log10 mean estimate regressed on\n",
                     fit.trials, fit.answered, fit.subjects.size(), fit.stimuli.size(), fit.runs);
  out += fmt::format("# log10({} / 1 {}) with a constant, the form of Minsky 1995 Figure 19 (docs/CALIBRATION.md, \"Fitting\").\n",
                     x.name, x.unit);
  out += fmt::format("# Sums of squares: regression {:.6g} (df {}), residual {:.6g} (df {}); F-ratio p = {:.3g}.\n",
                     r.ss_regression, r.df_regression, r.ss_residual, r.df_residual, r.f_p);
  if (fit.force_period) {
    const auto& c = fit.force_period->coefficient("log period");
    out += fmt::format("# Log period beside log {} (Figure 20 form, with a constant): coefficient {:.4g}, s.e. {:.3g},\n"
                       "# t {:.3g}, p {:.3g}: {}.\n",
                       x.name, c.value, c.se, c.t, c.p,
                       c.p < 0.05 ? "period is significant at the 5 % level; this one-predictor map leaves it out"
                                  : "period adds nothing significant at the 5 % level");
  } else {
    out += "# Log period: " + fit.period_note + ".\n";
  }
  if (fit.between.subjects >= 2)
    out += fmt::format("# Subjects' own slopes: mean {:.4g}, sd {:.3g}, s.e. of the mean {:.3g} ({} subjects).\n",
                       fit.between.slope_mean, fit.between.slope_sd, fit.between.slope_se, fit.between.subjects);
  out += "schema = \"sandpaper-map/1\"\n";
  out += "id = " + toml_string(id) + "\n";
  out += "percept = " + toml_string(o.percept) + "\n";
  out += "status = \"measured\"\n";
  out += o.device.empty() ? "use = \"compile\"\n" : "use = \"device\"\n";
  out += "law = \"log-linear\"\n";
  out += "description = " + toml_string(description) + "\n\n";
  out += "[[predictor]]\nname = " + toml_string(x.name) + "\nquantity = " + toml_string(x.quantity) +
         "\nunit = " + toml_string(x.unit) + "\n";
  out += "coefficient = " + toml_float(slope.value) + "\n";
  coefficient_lines(out, slope);
  out += "\n[intercept]                  # log10 estimate at 1 " + x.unit + ", on the normalised estimates' scale\n";
  out += "value = " + toml_float(constant.value) + "\n";
  coefficient_lines(out, constant);
  out += "\n[fit]\n";
  out += fmt::format("r_squared = {}\nr_squared_adjusted = {}\nresidual_sd = {}         # s, log10 units\n",
                     toml_float(r.r_squared), toml_float(r.r_squared_adjusted), toml_float(r.s));
  out += fmt::format("degrees_of_freedom = {}\nf_ratio = {}\nstimuli = {}\nsubjects = {}\nruns = {}\n", r.df_residual,
                     toml_float(r.f_ratio), fit.stimuli.size(), fit.subjects.size(), fit.runs);
  out += "normalisation = " + toml_string(normalisation) + "\n";
  if (o.reference_N > 0) {
    out += "\n[ratio_scale]                # ratio-scale percept 1 at the default map's reference\n";
    out += "predictor = " + toml_string(x.name) + "\nreference = " + toml_string(quantity_text(o.reference_N, unit)) + "\n";
  } else {
    // A percept that falls as x grows (softness on stiffness) is 1 at the smallest stimulus.
    out += "\n[ratio_scale]                # ratio-scale percept 1 at the most intense stimulus\n";
    out += "predictor = " + toml_string(x.name) + "\nreference = " +
           toml_string(slope.value > 0 ? bound_text(fmax, x.unit, true) : bound_text(fmin, x.unit, false)) + "\n";
  }
  double dmin = fmin, dmax = fmax;
  for (double v : o.widen_domain_to)
    if (v > 0 && std::isfinite(v)) {
      dmin = std::min(dmin, v);
      dmax = std::max(dmax, v);
    }
  const auto range = [&](double lo, double hi) {
    return "[" + toml_string(bound_text(lo, x.unit, false)) + ", " + toml_string(bound_text(hi, x.unit, true)) + "]";
  };
  if (dmin < fmin || dmax > fmax) {
    out += "\n[domain]                     # the stimuli the fit saw, widened to the named levels' values\n";
    out += x.name + " = " + range(dmin, dmax) + "\n";
    out += "stimuli = " + range(fmin, fmax) + "     # the fit's stimuli; beyond them the map extrapolates (W0322)\n";
  } else {
    out += "\n[domain]                     # the stimuli the fit saw\n";
    out += x.name + " = " + range(fmin, fmax) + "\n";
  }
  if (pmin > 0)
    out += "period = [" + toml_string(bound_text(pmin * 1e3, "mm", false)) + ", " +
           toml_string(bound_text(pmax * 1e3, "mm", true)) + "]\n";
  if (!o.device.empty()) out += "device = " + toml_string(o.device) + "\n";
  if (!o.apparatus.empty()) out += "apparatus = " + toml_string(o.apparatus) + "\n";
  if (o.weber_fraction > 0) {
    out += "\n[jnd]\n";
    out += "weber_fraction = " + toml_float(o.weber_fraction) + "\n";
    out += "source = " + toml_string(o.jnd_source) + "\n";
  }
  out += "\n[source]\n";
  out += "citation = " + toml_string(o.citation.empty() ? "magnitude-estimation data in " + fit.path : o.citation) + "\n";
  out += "where = " + toml_string(o.provenance.empty()
                                      ? fmt::format("fitted by sandpaper calibrate fit: {} stimuli, {} subjects, {} runs",
                                                    fit.stimuli.size(), fit.subjects.size(), fit.runs)
                                      : o.provenance) +
         "\n";
  // Names given on the command line (the CSV's path, the output's stem) are bytes on Linux; the file
  // must stay UTF-8 or the whole calibration folder stops loading (F26).
  return schema::replace_invalid_utf8(out);
}

}  // namespace sandpaper::calibration

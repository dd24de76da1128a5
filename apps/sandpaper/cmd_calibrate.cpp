// `sandpaper calibrate fit <responses.csv>` and `sandpaper calibrate device <readings.csv>`:
// psychophysical maps and device calibrations fitted from measurements, reported as Minsky 1995
// Figures 19 and 20 reported theirs (docs/CALIBRATION.md, "Fitting").
#include <cmath>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "cli.hpp"
#include "sandpaper/calibration/device_fit.hpp"
#include "sandpaper/calibration/fit.hpp"
#include "sandpaper/calibration/fit_error.hpp"
#include "sandpaper/calibration/fit_json.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/json_text.hpp"

namespace sandpaper::cli {
namespace {

using calibration::Coefficient;
using calibration::RegressionResult;
using nlohmann::json;

using calibration::period_verdict;
constexpr double kAlpha = calibration::kSignificanceLevel;

// JSON has no infinity: a non-finite statistic becomes null.
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string p_text(double p) { return calibration::p_value_text(p); }

// The regression table in the layout of Minsky 1995 Figures 19-20 (Data Desk's).
std::string regression_table(const RegressionResult& r, const std::string& dependent) {
  std::string out;
  out += fmt::format("Dependent variable is: {}\n", dependent);
  if (r.has_constant)
    out += fmt::format("R squared = {:.1f}%   R squared (adjusted) = {:.1f}%\n", 100 * r.r_squared, 100 * r.r_squared_adjusted);
  else
    out += fmt::format("R squared (uncentred) = {:.1f}%   R squared (adjusted) = {:.1f}%\n", 100 * r.r_squared,
                       100 * r.r_squared_adjusted);
  const int k = static_cast<int>(r.coefficients.size());
  out += fmt::format("s = {:.4g} with {} - {} = {} degrees of freedom\n\n", r.s, r.n, k, r.df_residual);
  out += fmt::format("{:<12}{:>16}{:>5}{:>14}{:>10}{:>10}\n", "Source", "Sum of Squares", "df", "Mean Square", "F-ratio", "prob");
  out += fmt::format("{:<12}{:>16.6g}{:>5}{:>14.6g}{:>10.4g}{:>10}\n", "Regression", r.ss_regression, r.df_regression,
                     r.ss_regression / r.df_regression, r.f_ratio, p_text(r.f_p));
  out += fmt::format("{:<12}{:>16.6g}{:>5}{:>14.6g}\n", "Residual", r.ss_residual, r.df_residual, r.ss_residual / r.df_residual);
  out += fmt::format("{:<12}{:>16.6g}{:>5}\n\n", r.has_constant ? "Total" : "Total (unc.)", r.ss_total,
                     r.df_regression + r.df_residual);
  out += fmt::format("{:<12}{:>14}{:>16}{:>10}{:>10}\n", "Variable", "Coefficient", "s.e. of Coeff", "t-ratio", "prob");
  for (const auto& c : r.coefficients)
    out += fmt::format("{:<12}{:>14.6g}{:>16.4g}{:>10.2f}{:>10}\n", c.name == "constant" ? "Constant" : c.name, c.value, c.se,
                       c.t, p_text(c.p));
  return out;
}

void write_output(const std::string& path, const std::string& text) {
  try {
    schema::write_file_atomically(path, text);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(e.what());  // environment: exit 2 in main
  }
}

int run_fit(const CalibrateOptions& o) {
  const auto data = calibration::read_magnitude_estimation_csv(o.input);
  const auto fit = calibration::fit_magnitude_estimation(data);
  const auto& r = fit.force;
  const auto& slope = r.coefficient("log force");
  const auto& constant = r.coefficient("constant");
  if (!o.output.empty()) {
    calibration::MapFileOptions mo;
    mo.percept = o.percept;
    mo.id = o.id.empty() ? std::filesystem::path(o.output).stem().string() : o.id;
    write_output(o.output, calibration::map_file_text(fit, mo));
  }
  if (o.json) {
    json j = {{"ok", true}, {"source", fit.path}, {"percept", o.percept}};
    j.update(calibration::fit_json(fit));
    if (!o.output.empty()) j["output"] = o.output;
    std::cout << schema::json_text(j, 2) << "\n";
    return kExitOk;
  }
  std::cout << fmt::format("{}: {} trials ({} answered), {} subjects, {} stimuli, {} runs\n", fit.path, fit.trials,
                           fit.answered, fit.subjects.size(), fit.stimuli.size(), fit.runs);
  std::cout << fmt::format("normalisation: each subject's estimates / their geometric mean x the grand geometric mean {:.4g};\n"
                           "  geometric mean per stimulus over subjects and runs\n\n",
                           fit.grand_geometric_mean);
  std::cout << "Regression of log mean " << o.percept << " on log force (force in N)   [as Minsky 1995, Figure 19]\n";
  std::cout << regression_table(r, "log mean " + o.percept);
  std::cout << fmt::format("\nlog R = {:.4g} log F {} {:.4g}   (F in N; slope {:.4g} +- {:.2g} s.e.)\n", slope.value,
                           constant.value < 0 ? "-" : "+", std::abs(constant.value), slope.value, slope.se);
  if (fit.force_period) {
    std::cout << "\nMultiple regression on log force (N) and log period (mm), with a constant   [as Figure 20]\n";
    std::cout << regression_table(*fit.force_period, "log mean " + o.percept);
    std::cout << "\n" << period_verdict(fit.force_period->coefficient("log period")) << ".\n";
    if (fit.force_period_origin) {
      const auto& c = fit.force_period_origin->coefficient("log period");
      std::cout << fmt::format("(Through the origin, as the thesis fitted Figure 20: log period {:.4g}, s.e. {:.3g}, t {:.3g}, p {};\n"
                               " not a test of period: without a constant the coefficients depend on the units, here N and mm.)\n",
                               c.value, c.se, c.t, p_text(c.p));
    }
  } else {
    std::cout << "\nlog period: " << fit.period_note << "\n";
  }
  if (fit.between.subjects >= 2)
    std::cout << fmt::format("\nSubjects' own slopes: mean {:.4g}, sd {:.3g}, s.e. of the mean {:.3g} ({} subjects). The\n"
                             "regression's s.e. is for these subjects; for people in general, mind this one too.\n",
                             fit.between.slope_mean, fit.between.slope_sd, fit.between.slope_se, fit.between.subjects);
  if (!o.output.empty()) std::cout << "\nwrote " << o.output << "\n";
  return kExitOk;
}

int run_device(const CalibrateOptions& o) {
  std::optional<toml::table> base;
  if (!o.base.empty()) {
    if (!std::filesystem::is_regular_file(o.base)) {
      std::cerr << o.base << ": error: cannot read the base device file (does it exist?)\n";
      return kExitBadInput;
    }
    try {
      base = toml::parse_file(o.base);
    } catch (const toml::parse_error& e) {
      std::cerr << fmt::format("{}:{}: error: {}\n", o.base, e.source().begin.line, e.description());
      return kExitBadInput;
    }
  }
  const auto readings = calibration::read_device_readings_csv(o.input);
  const auto fit = calibration::fit_device(readings);
  if (!o.output.empty()) {
    calibration::DeviceFileOptions d;
    d.name = o.name;
    d.base_path = o.base;
    d.date = o.date;
    write_output(o.output, calibration::device_file_text(fit, *base, d));
  }
  if (o.json) {
    json axes = json::array();
    for (const auto& a : fit.axes) {
      json residuals = json::array();
      for (std::size_t i = 0; i < a.points.size(); ++i)
        residuals.push_back({{"command", a.points[i].command}, {"force_N", a.points[i].force_N},
                             {"fitted_N", a.regression.fitted[i]}, {"residual_N", a.regression.residuals[i]}});
      axes.push_back({{"axis", a.axis ? std::string(1, a.axis) : std::string("both")},
                      {"readings", a.readings},
                      {"command_levels", a.command_levels},
                      {"newtons_per_command_unit", a.gain_N_per_unit},
                      {"gain_se", a.gain_se},
                      {"offset_N", a.offset_N},
                      {"offset_se", a.offset_se},
                      {"offset_p", num(a.offset_p)},
                      {"r2", a.regression.r_squared},
                      {"s_N", a.regression.s},
                      {"df", a.regression.df_residual},
                      {"full_scale_N", a.full_scale_N},
                      {"max_abs_residual_N", a.max_abs_residual_N},
                      {"max_residual_percent_fs", a.max_residual_percent},
                      {"residuals", residuals}});
    }
    json j = {{"ok", true}, {"source", fit.path}, {"axes", axes}};
    if (!o.output.empty()) j["output"] = o.output;
    std::cout << schema::json_text(j, 2) << "\n";
    return kExitOk;
  }
  std::cout << fit.path << ": force = gain x command + offset, least squares\n";
  for (const auto& a : fit.axes) {
    std::cout << fmt::format("\n{}: {} readings at {} command levels\n", a.axis ? std::string("axis ") + a.axis : "both axes",
                             a.readings, a.command_levels);
    std::cout << fmt::format("  gain   {:.6g} N per command unit (s.e. {:.2g})\n", a.gain_N_per_unit, a.gain_se);
    std::cout << fmt::format("  offset {:.4g} N (s.e. {:.2g}, p {}){}\n", a.offset_N, a.offset_se, p_text(a.offset_p),
                             a.offset_p < kAlpha ? ": significant; not stored (the device model has no offset)" : "");
    std::cout << fmt::format("  linearity: R^2 = {:.6f}, s = {:.3g} N, largest residual {:.3g} N = {:.2f} % of full scale {:.4g} N\n",
                             a.regression.r_squared, a.regression.s, a.max_abs_residual_N, a.max_residual_percent,
                             a.full_scale_N);
    std::cout << fmt::format("  {:>10}{:>12}{:>12}{:>12}\n", "command", "force N", "fitted N", "residual N");
    for (std::size_t i = 0; i < a.points.size(); ++i)
      std::cout << fmt::format("  {:>10g}{:>12.4g}{:>12.4g}{:>12.3g}\n", a.points[i].command, a.points[i].force_N,
                               a.regression.fitted[i], a.regression.residuals[i]);
  }
  if (!o.output.empty()) std::cout << "\nwrote " << o.output << "\n";
  return kExitOk;
}

}  // namespace

void add_calibrate_command(CLI::App& app, CalibrateOptions& o) {
  auto* cal = app.add_subcommand("calibrate", "fit psychophysical maps and device calibrations from measurements");
  cal->require_subcommand(1);
  o.fit = cal->add_subcommand("fit", "fit a map (log R = slope log F + b) from magnitude estimates: subject,stimulus,force_N,period_mm,response");
  o.fit->add_option("responses", o.input, "magnitude-estimation CSV, one row per trial")->required();
  o.fit->add_option("-o,--output", o.output, "map file to write (calibration/maps/*.toml format)");
  o.fit->add_option("--percept", o.percept, "the percept estimated")->capture_default_str();
  o.fit->add_option("--id", o.id, "map id (default: the output file's name)");
  o.fit->add_flag("--json", o.json, "print one JSON object instead of text");
  o.device = cal->add_subcommand("device", "fit newtons per command unit from force-gauge readings: command,force_N[,axis]");
  o.device->add_option("readings", o.input, "force-gauge CSV, one row per reading")->required();
  o.device->add_option("-o,--output", o.output, "device file to write (needs --base)");
  o.device->add_option("--base", o.base, "device file the readings calibrate: gives workspace, servo rates, command range");
  o.device->add_option("--name", o.name, "device name to write (default: the base's)");
  o.device->add_option("--date", o.date, "date of the measurement to record, YYYY-MM-DD");
  o.device->add_flag("--json", o.json, "print one JSON object instead of text");
}

int cmd_calibrate(const CalibrateOptions& o) {
  const bool fit = o.fit && o.fit->parsed(), device = o.device && o.device->parsed();
  if (!fit && !device) return -1;
  if (device && !o.output.empty() && o.base.empty()) {
    std::cerr << "sandpaper calibrate device: -o needs --base <device file>: the readings give the force scale only, "
                 "the base gives the workspace, servo rates and command range (e.g. --base calibration/devices/openffboard-2axis.toml)\n";
    return kExitUsage;
  }
  try {
    return fit ? run_fit(o) : run_device(o);
  } catch (const calibration::FitError& e) {
    std::cerr << e.what() << "\n";
    if (o.json) {
      json d = {{"severity", "error"}, {"file", e.file}, {"message", e.message}};
      if (e.line > 0) d["line"] = e.line;
      std::cout << schema::json_text(json{{"ok", false}, {"diagnostics", json::array({d})}}, 2) << "\n";
    }
    return kExitBadInput;
  }
}

}  // namespace sandpaper::cli

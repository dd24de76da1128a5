// Force-gauge readings -> newtons per command unit, per axis. A line with an offset is fitted: a
// gauge's zero error, friction or a motor's cogging shift every reading alike, and forcing the line
// through zero would bend the gain to absorb them. The offset is reported (with its s.e. and p) so a
// large one is seen, but not stored: the device model commands force = gain * command.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "sandpaper/calibration/csv.hpp"
#include "sandpaper/calibration/device_fit.hpp"
#include "sandpaper/calibration/fit_error.hpp"

namespace sandpaper::calibration {
namespace {

DeviceReadings from_table(const CsvTable& t) {
  require_columns(t, {"command", "force_N"});
  const auto c_command = *t.column("command"), c_force = *t.column("force_N");
  const auto c_axis = t.column("axis");
  DeviceReadings d;
  d.path = t.path;
  d.has_axis = c_axis.has_value();
  for (const auto& row : t.rows) {
    ForceReading r;
    r.line = row.line;
    r.command = number_field(t, row, c_command);
    r.force_N = number_field(t, row, c_force);
    if (c_axis) {
      std::string a = row.fields[*c_axis];
      std::transform(a.begin(), a.end(), a.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      if (a != "x" && a != "y")
        throw FitError(t.path, row.line, "axis is `" + row.fields[*c_axis] + "`; it must be x or y");
      r.axis = a[0];
    }
    d.readings.push_back(r);
  }
  if (d.readings.empty()) throw FitError(t.path, t.header_line, "no readings: the header is followed by no data rows");
  return d;
}

std::string axis_label(char axis) { return axis ? std::string("axis ") + axis : std::string("the readings"); }

AxisFit fit_axis(const std::string& file, char axis, const std::vector<ForceReading>& pts) {
  AxisFit a;
  a.axis = axis;
  a.points = pts;
  a.readings = static_cast<int>(pts.size());
  std::set<double> levels;
  for (const auto& p : pts) levels.insert(p.command);
  a.command_levels = static_cast<int>(levels.size());
  if (pts.size() < 3)
    throw FitError(file, 0,
                   fmt::format("too few readings for {}: {}; a line with gain and offset needs at least 3 (one residual "
                               "degree of freedom), better a dozen across the command range",
                               axis_label(axis), pts.size()));
  if (levels.size() < 2)
    throw FitError(file, pts.front().line,
                   fmt::format("{} has one command level ({:g}) only: the gain needs readings at two or more commands",
                               axis_label(axis), pts.front().command));
  std::vector<double> x, y;
  for (const auto& p : pts) {
    x.push_back(p.command);
    y.push_back(p.force_N);
  }
  if (varies_too_little(y))
    throw FitError(file, pts.front().line,
                   fmt::format("{} reads the same force ({:g} N) at every command: the gain needs a force that changes "
                               "with the command (is the gauge attached?)",
                               axis_label(axis), y.front()));
  a.regression = least_squares({"command"}, {x}, y, Constant::Fitted);
  for (const auto& k : a.regression.coefficients)
    if (!std::isfinite(k.value) || !std::isfinite(k.se))
      throw FitError(file, 0, fmt::format("{} gives no finite fit ({} is {:g}, s.e. {:g})", axis_label(axis), k.name,
                                          k.value, k.se));
  const auto& g = a.regression.coefficient("command");
  const auto& c = a.regression.coefficient("constant");
  a.gain_N_per_unit = g.value;
  a.gain_se = g.se;
  a.offset_N = c.value;
  a.offset_se = c.se;
  a.offset_p = c.p;
  if (!(a.gain_N_per_unit > 0))
    throw FitError(file, 0,
                   fmt::format("the fitted gain of {} is {:.4g} N per command unit: force does not grow with the command "
                               "(is the axis reversed, or force_N signed the other way?)",
                               axis_label(axis), a.gain_N_per_unit));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    a.full_scale_N = std::max(a.full_scale_N, std::abs(a.regression.fitted[i]));
    a.max_abs_residual_N = std::max(a.max_abs_residual_N, std::abs(a.regression.residuals[i]));
  }
  a.max_residual_percent = a.full_scale_N > 0 ? 100.0 * a.max_abs_residual_N / a.full_scale_N : 0.0;
  return a;
}

}  // namespace

DeviceReadings parse_device_readings_csv(std::string_view text, const std::string& path) {
  return from_table(parse_csv(text, path));
}

DeviceReadings read_device_readings_csv(const std::filesystem::path& path) { return from_table(read_csv(path)); }

DeviceFit fit_device(const DeviceReadings& d) {
  DeviceFit f;
  f.path = d.path;
  if (!d.has_axis) {
    f.axes.push_back(fit_axis(d.path, 0, d.readings));
    return f;
  }
  for (char axis : {'x', 'y'}) {
    std::vector<ForceReading> pts;
    for (const auto& r : d.readings)
      if (r.axis == axis) pts.push_back(r);
    if (!pts.empty()) f.axes.push_back(fit_axis(d.path, axis, pts));
  }
  return f;
}

}  // namespace sandpaper::calibration

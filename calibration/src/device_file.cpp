// Writes a calibrated device file (schema/files/device.schema.json) from a fit and a base file.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "sandpaper/calibration/device_fit.hpp"
#include "sandpaper/calibration/fit_error.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/schema/units.hpp"
#include "toml_text.hpp"

namespace sandpaper::calibration {
namespace {

using detail::toml_float;
using detail::toml_string;

// "10 N", "382 gf" -> newtons; nullopt if not a force quantity.
std::optional<double> force_of(std::string_view text) {
  const auto q = schema::parse_quantity(text);
  if (!q || q->unit.dimension != schema::Dimension::Force) return std::nullopt;
  return q->si();
}

// A TOML value as text; tables are written by the caller.
std::string value_text(const toml::node& n) {
  if (auto s = n.as_string()) return toml_string(s->get());
  if (auto i = n.as_integer()) return fmt::format("{}", i->get());
  if (auto f = n.as_floating_point()) {
    std::string t = fmt::format("{}", f->get());
    if (t.find_first_of(".eEn") == std::string::npos) t += ".0";
    return t;
  }
  if (auto b = n.as_boolean()) return b->get() ? "true" : "false";
  if (auto a = n.as_array()) {
    std::string out = "[";
    for (std::size_t i = 0; i < a->size(); ++i) out += (i ? ", " : "") + value_text(*a->get(i));
    return out + "]";
  }
  return toml_string("?");
}

// The base table `name` copied key by key (values only; nested tables are not used by device files).
void copy_table(std::string& out, const toml::table& base, const char* name) {
  const auto* t = base[name].as_table();
  if (!t) return;
  out += fmt::format("\n[{}]\n", name);
  // In the base's order (toml++ keeps keys sorted; the source lines say where each was written).
  std::vector<std::pair<std::string, const toml::node*>> keys;
  for (const auto& [k, v] : *t)
    if (!v.is_table()) keys.emplace_back(std::string(k.str()), &v);
  std::stable_sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) {
    return a.second->source().begin.line < b.second->source().begin.line;
  });
  for (const auto& [k, v] : keys) out += fmt::format("{} = {}\n", k, value_text(*v));
}

std::string axis_summary(const AxisFit& a) {
  return fmt::format("{}: {} readings at {} commands, gain {:.6g} N/unit (s.e. {:.2g}), offset {:.3g} N (s.e. {:.2g}, p {:.2g}), "
                     "R^2 {:.6f}, largest residual {:.3g} N = {:.2f} % of {:.4g} N",
                     a.axis ? std::string("axis ") + a.axis : std::string("both axes"), a.readings, a.command_levels,
                     a.gain_N_per_unit, a.gain_se, a.offset_N, a.offset_se, a.offset_p, a.regression.r_squared,
                     a.max_abs_residual_N, a.max_residual_percent, a.full_scale_N);
}

}  // namespace

std::string device_file_text(const DeviceFit& fit, const toml::table& base, const DeviceFileOptions& o) {
  const AxisFit* ax = nullptr;
  const AxisFit* ay = nullptr;
  for (const auto& a : fit.axes) {
    if (a.axis == 0) ax = ay = &a;
    if (a.axis == 'x') ax = &a;
    if (a.axis == 'y') ay = &a;
  }
  // A wheel ([wheel]) has one force axis, x along its rim: its readings need no y.
  if (base["wheel"].is_table() && ay == nullptr) ay = ax;
  // A three-axis device ([force.z]): the readings name x and y only, so one fit for every axis
  // (no axis column) is the only one that covers z.
  const bool three_axis = base["force"]["z"].is_table();
  if (three_axis && !(ax != nullptr && ax == ay && ax->axis == 0))
    throw FitError(fit.path, 0,
                   "the base device file has three force axes ([force.z]) and the readings name axes x and y only: "
                   "drop the axis column to fit one scale for all three axes");
  for (auto [a, name] : {std::pair{ax, 'x'}, std::pair{ay, 'y'}})
    if (!a)
      throw FitError(fit.path, 0,
                     fmt::format("the readings have no rows for axis {}; a device file needs both axes: measure {} too, "
                                 "or drop the axis column to use one fit for both",
                                 name, name));

  const std::string name = o.name.empty() ? base["name"].value_or(std::string("device")) : o.name;
  std::string description = base["description"].value_or(std::string(name));
  if (auto p = description.find(" (uncalibrated)"); p != std::string::npos) description.erase(p, 15);
  const auto base_max = force_of(base["force"]["max_continuous"].value_or(std::string()));
  const auto command_max = base["force"]["command_max"].value<std::int64_t>();
  std::optional<double> max_continuous = base_max;
  bool max_rounded_down = false;
  std::string max_note;
  if (command_max) {
    const double reach = std::min(ax->gain_N_per_unit, ay->gain_N_per_unit) * static_cast<double>(*command_max);
    if (!max_continuous || reach < *max_continuous) {
      max_note = fmt::format("   # lowered from the base's {}: command_max gives {:.4g} N at the weaker axis",
                             base["force"]["max_continuous"].value_or(std::string("(none)")), reach);
      max_continuous = reach;
      max_rounded_down = true;
    }
  }
  if (!max_continuous)
    throw FitError(o.base_path, 0, "the base device file gives neither force.max_continuous nor force.command_max");
  const double residual_max = std::max(ax->max_abs_residual_N, ay->max_abs_residual_N);

  std::string out;
  out += fmt::format("# Calibrated by `sandpaper calibrate device` from the force-gauge readings in {}\n", fit.path);
  out += fmt::format("# on the base device file {}: force = gain x command + offset, least squares per axis.\n",
                     o.base_path.empty() ? "(none)" : o.base_path);
  for (const auto& a : fit.axes) out += "# " + axis_summary(a) + ".\n";
  out += "# The offset is reported, not stored: the device model commands force = newtons_per_command_unit x command.\n";
  out += "schema = \"sandpaper-device/1\"\n";
  out += "name = " + toml_string(name) + "\n";
  out += "description = " + toml_string(description) + "\n";
  out += "command_unit = " + toml_string(base["command_unit"].value_or(std::string("command unit"))) + "\n";
  out += "\n[force]\n";
  std::string max_text = fmt::format("{:.4g}", *max_continuous);
  // Never claim more than command_max gives: a value that rounded up comes down one unit in its
  // fourth significant digit (8.3527 N is written 8.352 N, not 8.353).
  if (max_rounded_down && std::stod(max_text) > *max_continuous) {
    const double unit = std::pow(10.0, std::floor(std::log10(*max_continuous)) - 3);
    max_text = fmt::format("{:.4g}", std::stod(max_text) - unit);
  }
  out += "max_continuous = " + toml_string(max_text + " N") + max_note + "\n";
  if (command_max) out += fmt::format("command_max = {}\n", *command_max);
  if (auto bits = base["force"]["resolution_bits"].value<std::int64_t>()) out += fmt::format("resolution_bits = {}\n", *bits);
  // The readings measure how hard a command pushes, not which way: the sense is the base's.
  const bool wheel = base["wheel"].is_table();
  for (auto [a, axis] : {std::pair{ax, "x"}, std::pair{ay, "y"}, std::pair{ax, "z"}}) {
    if (wheel && axis[0] == 'y') continue;  // ay is ax there
    if (!three_axis && axis[0] == 'z') continue;  // ax is the one fit of all axes there
    out += fmt::format("[force.{}]\nnewtons_per_command_unit = {}\n", axis, toml_float(a->gain_N_per_unit, 9));
    if (auto sense = base["force"][axis]["command_sense"].value<std::int64_t>()) out += fmt::format("command_sense = {}\n", *sense);
  }
  copy_table(out, base, "wheel");
  copy_table(out, base, "position");
  copy_table(out, base, "workspace");
  copy_table(out, base, "usb");
  // What the firmware does to a command is in command units, which a gauge fit does not change.
  copy_table(out, base, "firmware");
  copy_table(out, base, "emulation");
  copy_table(out, base, "maps");
  copy_table(out, base, "servo_rate_hz");
  out += "\n[calibration]\nstatus = \"calibrated\"\n";
  std::string method = "least-squares line force = gain x command + offset fitted to force-gauge readings, per axis";
  if (!fit.axes.empty() && fit.axes.front().axis == 0) method = "least-squares line force = gain x command + offset fitted to force-gauge readings, one fit for both axes";
  for (const auto& a : fit.axes) method += "; " + axis_summary(a);
  method += "; the offset is not part of the device model";
  out += "method = " + toml_string(method) + "\n";
  out += "source = " + toml_string("force-gauge readings in " + fit.path) + "\n";
  if (!o.date.empty()) out += "date = " + toml_string(o.date) + "\n";
  out += "residual_max = " + toml_string(fmt::format("{:.3g} N", residual_max)) + "\n";
  // Names given on the command line (the CSV's path, the output's stem) are bytes on Linux; the file
  // must stay UTF-8 or the whole calibration folder stops loading (F26).
  return schema::replace_invalid_utf8(out);
}

}  // namespace sandpaper::calibration

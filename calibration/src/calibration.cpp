#include "sandpaper/calibration/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <set>

#include "file_reading.hpp"
#include "sandpaper/schema/units.hpp"

namespace sandpaper::calibration {
namespace {

using detail::Problems;
using detail::Toml;

Range range_of(const toml::node_view<const toml::node>& v) {
  const auto* a = v.as_array();
  return {detail::quantity_si(*a->get(0)), detail::quantity_si(*a->get(1))};
}

// A dimensionless value written as a bare number string ("0.43"); NaN when it is not one.
double bare_number(const toml::node& n) {
  const std::string text = n.value<std::string>().value_or("");
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return !text.empty() && end != text.c_str() && *end == '\0' && std::isfinite(v) ? v : std::nan("");
}

std::optional<Range> optional_range(const toml::table& doc, const char* key) {
  auto v = doc["domain"][key];
  if (!v.as_array()) return std::nullopt;
  return range_of(v);
}

template <typename T>
std::optional<T> optional_value(const toml::node_view<const toml::node>& v) {
  if (auto x = v.value<T>()) return *x;
  return std::nullopt;
}

// The domain's range of a predictor; nullptr when the map has none.
const std::optional<Range>* domain_of(const PsychophysicalMap& m, const std::string& name) {
  if (name == "force") return &m.force;
  if (name == "period") return &m.period;
  if (name == "feature") return &m.feature;
  if (name == "damping") return &m.damping;
  if (name == "stiffness") return &m.stiffness;
  if (name == "friction") return &m.friction;
  return nullptr;
}

// [domain] stimuli: the ratio predictor's range the fit saw, inside its (wider) domain range.
void read_stimulus_range(const Toml& f, const Predictor& rp, PsychophysicalMap& m, Problems& problems) {
  const auto* a = f.doc["domain"]["stimuli"].as_array();
  if (!a) return;
  Range r;
  if (rp.unit == "1") r = Range{bare_number(*a->get(0)), bare_number(*a->get(1))};
  else {
    const auto lo = schema::parse_quantity(a->get(0)->value<std::string>().value_or(""));
    const auto hi = schema::parse_quantity(a->get(1)->value<std::string>().value_or(""));
    const auto u = schema::find_unit(rp.unit);
    if (!lo || !hi || !u || lo->unit.dimension != u->dimension || hi->unit.dimension != u->dimension) {
      problems.add(f, *a, "[domain] stimuli is a range of the ratio predictor `" + rp.name + "`, in a unit of `" + rp.unit + "`",
                   "e.g. stimuli = [\"0.4 " + rp.unit + "\", \"6.4 " + rp.unit + "\"]");
      return;
    }
    r = Range{lo->si(), hi->si()};
  }
  const auto* d = domain_of(m, rp.name);
  if (!(r.min > 0 && r.min <= r.max && std::isfinite(r.max)) || !d || !*d ||
      r.min < (*d)->min * (1 - 1e-9) || r.max > (*d)->max * (1 + 1e-9)) {
    problems.add(f, *a, "[domain] stimuli must be a positive range [low, high] inside the domain's " + rp.name + " range",
                 "the domain's range is what compiles; stimuli is the part of it the fit saw");
    return;
  }
  m.stimulus_range = r;
}

PsychophysicalMap read_map(const Toml& f, Problems& problems) {
  const toml::table& c = f.doc;
  PsychophysicalMap m;
  m.file = f.shown_as;
  m.id = *c["id"].value<std::string>();
  m.percept = *c["percept"].value<std::string>();
  m.provisional = *c["status"].value<std::string>() == "provisional";
  m.for_compile = *c["use"].value<std::string>() == "compile";
  m.for_device = *c["use"].value<std::string>() == "device";
  m.description = *c["description"].value<std::string>();
  for (const auto& node : *c["predictor"].as_array()) {
    const toml::table& p = *node.as_table();
    Predictor pr;
    pr.name = *p["name"].value<std::string>();
    pr.quantity = *p["quantity"].value<std::string>();
    pr.unit = *p["unit"].value<std::string>();
    pr.coefficient = *p["coefficient"].value<double>();
    pr.se = optional_value<double>(p["se"]);
    pr.t = optional_value<double>(p["t"]);
    pr.p = optional_value<double>(p["p"]);
    if (pr.unit == "1") pr.unit_si = 1;  // dimensionless: the friction coefficient
    else if (auto u = schema::find_unit(pr.unit)) pr.unit_si = u->to_si;
    else problems.add(f, *p["unit"].node(), "unknown unit `" + pr.unit + "` for predictor " + pr.name,
                      "use a unit of schema/LANGUAGE.md, e.g. N, gf, pu, mm");
    m.predictors.push_back(std::move(pr));
  }
  m.intercept = optional_value<double>(c["intercept"]["value"]);
  m.intercept_se = optional_value<double>(c["intercept"]["se"]);
  m.r_squared = optional_value<double>(c["fit"]["r_squared"]);
  m.r_squared_adjusted = optional_value<double>(c["fit"]["r_squared_adjusted"]);
  m.residual_sd = optional_value<double>(c["fit"]["residual_sd"]);
  m.f_ratio = optional_value<double>(c["fit"]["f_ratio"]);
  m.degrees_of_freedom = optional_value<int>(c["fit"]["degrees_of_freedom"]);
  m.stimuli = optional_value<int>(c["fit"]["stimuli"]);
  m.subjects = optional_value<int>(c["fit"]["subjects"]);
  m.runs = optional_value<int>(c["fit"]["runs"]);
  m.normalisation = c["fit"]["normalisation"].value_or(std::string());
  m.force = optional_range(c, "force");
  m.period = optional_range(c, "period");
  m.feature = optional_range(c, "feature");
  m.damping = optional_range(c, "damping");
  m.stiffness = optional_range(c, "stiffness");
  if (const auto* a = c["domain"]["friction"].as_array()) {
    m.friction = Range{bare_number(*a->get(0)), bare_number(*a->get(1))};
    if (std::isnan(m.friction->min) || std::isnan(m.friction->max))
      problems.add(f, *a, "[domain] friction is a range of friction coefficients, bare numbers such as [\"0.43\", \"2.79\"]", "");
  }
  m.apparatus = c["domain"]["apparatus"].value_or(std::string());
  m.weber_fraction = optional_value<double>(c["jnd"]["weber_fraction"]);
  m.jnd_source = c["jnd"]["source"].value_or(std::string());
  m.domain_texture = c["domain"]["texture"].value_or(std::string());
  m.domain_device = c["domain"]["device"].value_or(std::string());
  m.effector = c["domain"]["effector"].value_or(std::string());
  m.citation = *c["source"]["citation"].value<std::string>();
  m.where = *c["source"]["where"].value<std::string>();

  for (const auto* r : {&m.force, &m.period, &m.feature, &m.damping, &m.stiffness, &m.friction})
    // low == high is a domain of one value: a map fitted on stimuli of one period (F34).
    if (*r && !((*r)->min > 0 && (*r)->min <= (*r)->max && std::isfinite((*r)->max)))
      problems.add(f, *c["domain"].node(), "a domain range must be positive and finite, [low, high] with low <= high", "");

  if (m.for_device && m.domain_device.empty())
    problems.add(f, *c["use"].node(), "a map with use = \"device\" names its device in [domain] device",
                 "add [domain] device = \"<name in calibration/devices/>\"");
  if (m.for_compile || m.for_device) {
    if (!c["ratio_scale"].as_table()) {
      problems.add(f, c, "a map used to compile (use = \"compile\" or \"device\") needs a [ratio_scale] (predictor and reference)",
                   "add [ratio_scale] with predictor = \"force\" and reference = \"382 gf\"");
      return m;
    }
    m.ratio_predictor = *c["ratio_scale"]["predictor"].value<std::string>();
    const Predictor* rp = m.predictor(m.ratio_predictor);
    const auto& ref_node = *c["ratio_scale"]["reference"].node();
    if (!rp) {
      problems.add(f, *c["ratio_scale"]["predictor"].node(),
                   "ratio_scale.predictor `" + m.ratio_predictor + "` is not one of the map's predictors", "");
      return m;
    }
    if (m.predictors.size() != 1)
      problems.add(f, *c["predictor"].node(), "a compile map has exactly one predictor (its ratio scale is a power of it)",
                   "move multiple-regression maps to use = \"comparison\"");
    m.slope = rp->coefficient;
    m.slope_se = rp->se.value_or(0);
    auto q = schema::parse_quantity(*ref_node.value<std::string>());
    if (rp->unit == "1") {
      // A dimensionless predictor's reference is a bare number ("0.43").
      const double v = bare_number(ref_node);
      if (!(v > 0))
        problems.add(f, ref_node, "ratio_scale.reference of a dimensionless predictor must be a positive number, e.g. \"0.43\"", "");
      else m.reference_si = v;
    } else if (!q || q->unit.to_si <= 0 || !(q->si() > 0))
      problems.add(f, ref_node, "ratio_scale.reference must be a positive quantity with a unit, e.g. \"382 gf\"", "");
    else if (auto u = schema::find_unit(rp->unit); u && u->dimension != q->unit.dimension)
      problems.add(f, ref_node, "ratio_scale.reference's unit does not measure the same thing as the predictor's `" +
                                    rp->unit + "`", "");
    else m.reference_si = q->si();
    if (m.slope == 0) problems.add(f, *c["predictor"].node(), "a compile map's slope must not be zero", "");
    read_stimulus_range(f, *rp, m, problems);
  }
  return m;
}

std::vector<Level> read_levels(const Toml& f, std::string& percept, std::string& map) {
  const toml::table& c = f.doc;
  percept = *c["percept"].value<std::string>();
  map = *c["map"].value<std::string>();
  std::vector<Level> out;
  for (const auto& node : *c["level"].as_array()) {
    const toml::table& l = *node.as_table();
    out.push_back({*l["name"].value<std::string>(), *l["value"].value<double>(), *l["rationale"].value<std::string>()});
  }
  return out;
}

AxisScale read_axis(const toml::node_view<const toml::node>& v) {
  AxisScale a;
  a.newtons_per_command_unit = v["newtons_per_command_unit"].value_or(0.0);
  a.command_sense = static_cast<int>(v["command_sense"].value_or(std::int64_t{1}));
  if (const auto* t = v["table"].as_array())
    for (const auto& row : *t) {
      const toml::table& r = *row.as_table();
      a.table.emplace_back(*r["command"].value<double>(), detail::quantity_si(*r["force"].node()));
    }
  return a;
}

// [workspace]: a circle or rectangle for a one- or two-axis device, a sphere or box for a
// three-axis one (axes already read from [force]); a solid for a flat device, or the reverse, is a
// unit of design slipped, and is named as such.
void read_workspace(const Toml& f, DeviceCalibration& d, Problems& problems) {
  const toml::table& c = f.doc;
  const auto ws = c["workspace"];
  const std::string shape = *ws["shape"].value<std::string>();
  const bool solid = shape == "box" || shape == "sphere";
  d.workspace_circle = shape == "circle" || shape == "sphere";
  if (d.three_axis() && !solid)
    problems.add(f, *ws["shape"].node(),
                 "a three-axis device ([force.z]) moves in a volume: its workspace is a box or a sphere, not a " + shape,
                 "shape = \"box\" with width, height and depth, or shape = \"sphere\" with diameter");
  if (!d.three_axis() && solid)
    problems.add(f, *ws["shape"].node(),
                 "a " + shape + " workspace is for a three-axis device, and this file gives no [force.z]",
                 "add [force.z] for a 3-DOF device, or use shape = \"circle\" or \"rectangle\"");
  if (shape != "box" && ws["depth"].node())
    problems.add(f, *ws["depth"].node(), "`depth` is for a box workspace (width x height x depth); a " + shape + " has none",
                 "remove depth, or use shape = \"box\"");
  if (d.workspace_circle) {
    if (auto dia = ws["diameter"].node()) {
      double diameter = detail::quantity_si(*dia);
      d.workspace_radius_m = diameter / 2;
      d.workspace_size_m[0] = d.workspace_size_m[1] = diameter;
      if (shape == "sphere") d.workspace_size_m[2] = diameter;
    } else if (shape == "sphere") {
      problems.add(f, *ws.node(), "a spherical workspace needs `diameter`", "add diameter = \"100 mm\"");
    } else {
      problems.add(f, *ws.node(), "a circular workspace needs `diameter`", "add diameter = \"9 in\"");
    }
  } else if (shape == "box") {
    auto w = ws["width"].node(), h = ws["height"].node(), z = ws["depth"].node();
    if (w && h && z) {
      d.workspace_size_m[0] = detail::quantity_si(*w);
      d.workspace_size_m[1] = detail::quantity_si(*h);
      d.workspace_size_m[2] = detail::quantity_si(*z);
      d.workspace_radius_m = std::min({d.workspace_size_m[0], d.workspace_size_m[1], d.workspace_size_m[2]}) / 2;
    } else {
      problems.add(f, *ws.node(), "a box workspace needs `width`, `height` and `depth` (along x, y and z)",
                   "add the missing one(s), e.g. depth = \"100 mm\"");
    }
  } else {
    auto w = ws["width"].node(), h = ws["height"].node();
    if (w && h) {
      d.workspace_size_m[0] = detail::quantity_si(*w);
      d.workspace_size_m[1] = detail::quantity_si(*h);
      d.workspace_radius_m = std::min(d.workspace_size_m[0], d.workspace_size_m[1]) / 2;
    } else problems.add(f, *ws.node(), "a rectangular workspace needs `width` and `height`", "");
  }
}

DeviceCalibration read_device(const Toml& f, Problems& problems) {
  const toml::table& c = f.doc;
  DeviceCalibration d;
  d.file = f.shown_as;
  d.name = *c["name"].value<std::string>();
  d.description = *c["description"].value<std::string>();
  d.command_unit = *c["command_unit"].value<std::string>();
  d.max_force_N = detail::quantity_si(*c["force"]["max_continuous"].node());
  d.command_max = c["force"]["command_max"].value_or(std::int64_t{0});
  d.resolution_bits = static_cast<int>(c["force"]["resolution_bits"].value_or(std::int64_t{0}));
  d.axis[0] = read_axis(c["force"]["x"]);
  d.axis[1] = read_axis(c["force"]["y"]);
  if (c["wheel"].is_table()) {
    d.axes = 1;
    d.wheel_rim_radius_m = detail::quantity_si(*c["wheel"]["rim_radius"].node());
    d.wheel_rotation_range_rad = detail::quantity_si(*c["wheel"]["rotation_range"].node());
    // One axis: y takes no force, so its scale is x's (a force on y is never sent).
    if (c["force"]["y"].is_table())
      problems.add(f, *c["force"]["y"].node(), "a wheel ([wheel]) has one force axis: [force.x], at the rim",
                   "remove [force.y]");
    d.axis[1] = d.axis[0];
  } else if (!c["force"]["y"].is_table()) {
    if (c["force"]["z"].is_table())
      problems.add(f, *c["force"].node(), "a three-axis device needs [force.y] as well as [force.x] and [force.z]", "add [force.y]");
    else
      problems.add(f, *c["force"].node(), "a two-axis device needs [force.y] as well as [force.x]",
                   "add [force.y], or a [wheel] table for a one-axis device turned at its rim");
  }
  if (c["force"]["z"].is_table()) {
    if (d.wheel())
      problems.add(f, *c["force"]["z"].node(), "a wheel ([wheel]) has one force axis: [force.x], at the rim", "remove [force.z]");
    else {
      d.axes = 3;
      d.axis[2] = read_axis(c["force"]["z"]);
    }
  }
  for (int a = 0; a < (d.three_axis() ? 3 : 2); ++a) {
    const auto& t = d.axis_scale(a).table;
    const char* name = a == 0 ? "x" : a == 1 ? "y" : "z";
    for (std::size_t i = 1; i < t.size(); ++i)
      if (!(t[i].first > t[i - 1].first && t[i].second > t[i - 1].second)) {
        problems.add(f, *c["force"][name]["table"].node(),
                     std::string("force.") + name + ".table must rise: commands and forces both ascending", "");
        break;
      }
  }
  if (auto r = c["position"]["resolution"].node()) d.position_resolution_m = detail::quantity_si(*r);
  read_workspace(f, d, problems);
  if (d.wheel()) {
    // From a haptic knob to a large steering wheel; outside it, a unit slipped.
    if (!(d.wheel_rim_radius_m >= 0.005 && d.wheel_rim_radius_m <= 1.0))
      problems.add(f, *c["wheel"]["rim_radius"].node(), "a wheel's rim radius is between 5 mm and 1 m", "");
    if (!(d.wheel_rotation_range_rad <= 20 * std::numbers::pi))
      problems.add(f, *c["wheel"]["rotation_range"].node(), "a wheel's rotation range is at most 3600 deg (ten turns)", "");
    // The rim's arc over the rotation range is the wheel's travel: the width says the same in mm.
    const double arc_m = d.wheel_rim_radius_m * d.wheel_rotation_range_rad;
    if (d.workspace_circle || !(std::abs(d.workspace_size_m[0] - arc_m) <= 1e-3 * arc_m)) {
      char want[64];
      std::snprintf(want, sizeof want, "%.1f mm", arc_m * 1e3);
      problems.add(f, *c["workspace"].node(),
                   std::string("a wheel's workspace is a rectangle whose width is its rim's arc over the rotation range, ") +
                       want,
                   std::string("shape = \"rectangle\", width = \"") + want + "\"");
    }
  }
  d.usb_vendor_id = static_cast<int>(c["usb"]["vendor_id"].value_or(std::int64_t{-1}));
  if (const auto* idle = c["usb"]["idle_report_period"].node()) d.usb_idle_report_period_s = detail::quantity_si(*idle);
  if (const auto* out = c["usb"]["out_interval"].node()) d.usb_out_interval_s = detail::quantity_si(*out);
  d.usb_product_id = static_cast<int>(c["usb"]["product_id"].value_or(std::int64_t{-1}));
  if (c["firmware"].is_table()) {
    d.firmware.update_rate_hz = c["firmware"]["update_rate_hz"].value_or(0.0);
    if (const auto* fade = c["firmware"]["fade_in"].node()) d.firmware.fade_in_s = detail::quantity_si(*fade);
    d.firmware.damping_command_s_per_m = c["firmware"]["damping_command_s_per_m"].value_or(0.0);
  }
  d.roughness_map = c["maps"]["roughness"].value_or(std::string());
  if (c["emulation"].is_table()) {
    d.emulated = true;
    d.hold_tables = c["emulation"]["tables"].value_or(std::string()) == "sample-and-hold";
  }
  d.min_rate_hz = *c["servo_rate_hz"]["min"].value<double>();
  d.max_rate_hz = *c["servo_rate_hz"]["max"].value<double>();
  if (d.min_rate_hz > d.max_rate_hz)
    problems.add(f, *c["servo_rate_hz"].node(), "servo_rate_hz.min is above servo_rate_hz.max", "");
  const std::string status = *c["calibration"]["status"].value<std::string>();
  d.status = status == "calibrated"  ? CalibrationStatus::Calibrated
             : status == "definition" ? CalibrationStatus::Definition
                                      : CalibrationStatus::Uncalibrated;
  d.calibration_method = *c["calibration"]["method"].value<std::string>();
  d.calibration_source = *c["calibration"]["source"].value<std::string>();
  return d;
}

std::vector<std::filesystem::path> toml_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().extension() == ".toml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

double DeviceCalibration::wheel_deg_per_mm() const {
  if (!wheel() || !(wheel_rim_radius_m > 0)) return 0;
  return 1e-3 / wheel_rim_radius_m * 180.0 / std::numbers::pi;
}

double PsychophysicalMap::percept_of(double x_si) const {
  if (!(x_si > 0) || !(reference_si > 0)) return 0;
  return std::pow(x_si / reference_si, slope);
}

double PsychophysicalMap::value_for(double p) const {
  if (!(p > 0) || slope == 0) return 0;
  return reference_si * std::pow(p, 1.0 / slope);
}

const Predictor* PsychophysicalMap::predictor(const std::string& name) const {
  for (const auto& p : predictors)
    if (p.name == name) return &p;
  return nullptr;
}

double AxisScale::newtons(double command) const {
  if (table.empty()) return command * newtons_per_command_unit;
  const double c = std::abs(command);
  std::size_t i = 1;
  while (i + 1 < table.size() && c > table[i].first) ++i;
  const auto& [c0, f0] = table[i - 1];
  const auto& [c1, f1] = table[i];
  const double f = f0 + (c - c0) * (f1 - f0) / (c1 - c0);
  return std::copysign(f, command);
}

double AxisScale::command(double newtons_) const {
  if (table.empty()) return newtons_ / newtons_per_command_unit;
  const double n = std::abs(newtons_);
  std::size_t i = 1;
  while (i + 1 < table.size() && n > table[i].second) ++i;
  const auto& [c0, f0] = table[i - 1];
  const auto& [c1, f1] = table[i];
  const double c = c0 + (n - f0) * (c1 - c0) / (f1 - f0);
  return std::copysign(c, newtons_);
}

double AxisScale::step_N(double newtons_) const {
  if (table.empty()) return newtons_per_command_unit;
  const double c = command(newtons_);
  return std::abs(newtons(c + 0.5) - newtons(c - 0.5));
}

double DeviceCalibration::force_step_N(int a, double newtons) const {
  return quantized() ? axis_scale(a).step_N(newtons) : 0.0;
}

double DeviceCalibration::quantize_N(int a, double newtons) const {
  if (!quantized()) return newtons;
  const auto& s = axis_scale(a);
  return s.newtons(std::round(s.command(newtons)));
}

double DeviceCalibration::firmware_damping_N(int a, double speed_m_s) const {
  return axis_scale(a).newtons(firmware.damping_command_s_per_m * std::abs(speed_m_s));
}

double ForceJndData::steps_between(double f1_N, double f2_N) const {
  if (!(f1_N > 0) || !(f2_N > 0) || !(weber_fraction > 0)) return 0;
  return std::log(f2_N / f1_N) / std::log1p(weber_fraction);
}

PsychophysicalMap load_map_file(const std::filesystem::path& path, const std::string& shown_as) {
  Problems problems;
  auto f = detail::read_validated(path, shown_as.empty() ? path.string() : shown_as, "map", problems);
  PsychophysicalMap m;
  if (f) m = read_map(*f, problems);
  problems.throw_if_any();
  return m;
}

DeviceCalibration load_device_file(const std::filesystem::path& path, const std::string& shown_as) {
  Problems problems;
  auto f = detail::read_validated(path, shown_as.empty() ? path.string() : shown_as, "device", problems);
  DeviceCalibration d;
  if (f) d = read_device(*f, problems);
  problems.throw_if_any();
  return d;
}

DeviceCalibration parse_device_text(const std::string& text, const std::string& shown_as) {
  Problems problems;
  auto f = detail::parse_validated(text, shown_as, "device", problems);
  DeviceCalibration d;
  if (f) d = read_device(*f, problems);
  problems.throw_if_any();
  return d;
}

CalibrationSet CalibrationSet::of_devices(std::vector<DeviceCalibration> devices) {
  CalibrationSet set;
  set.devices_ = std::move(devices);
  return set;
}

CalibrationSet CalibrationSet::load(const std::filesystem::path& dir, ParsedFileCache* cache) {
  CalibrationSet s;
  s.dir_ = dir;
  Problems problems;
  // Paths as users see them: relative to the calibration directory's parent ("calibration/maps/x.toml")
  // when that names the file from the current folder too, else absolute: a path shown must open.
  std::error_code cwd_error;
  const auto cwd = std::filesystem::current_path(cwd_error);
  const auto shown = [&](const std::filesystem::path& p) {
    auto parent = dir.lexically_normal().parent_path();
    auto rel = p.lexically_normal().lexically_relative(parent.empty() ? "." : parent);
    if (rel.empty()) return p.string();
    std::error_code ec;
    if (!cwd_error && std::filesystem::equivalent(cwd / rel, p, ec)) return rel.string();
    const auto abs = std::filesystem::absolute(p, ec);
    return ec ? rel.string() : abs.lexically_normal().string();
  };
  std::map<std::string, std::string> map_ids;  // id -> file
  for (const auto& p : toml_files(dir / "maps")) {
    auto f = detail::read_validated(p, shown(p), "map", problems, cache);
    if (!f) continue;
    auto m = read_map(*f, problems);
    if (auto [it, fresh] = map_ids.emplace(m.id, m.file); !fresh)
      problems.add(*f, *f->doc["id"].node(), "map id `" + m.id + "` is also used by " + it->second, "give each map its own id");
    s.maps_.push_back(std::move(m));
  }
  std::map<std::string, int> compile_maps;
  for (const auto& m : s.maps_)
    if (m.for_compile) ++compile_maps[m.percept];
  for (const auto& [percept, n] : compile_maps)
    if (n > 1) problems.add_plain(shown(dir / "maps") + ": " + std::to_string(n) + " maps have percept = \"" + percept +
                                  "\" and use = \"compile\"; the compiler needs exactly one (mark the others use = \"comparison\")");
  if (!compile_maps.count("roughness"))
    problems.add_plain(shown(dir / "maps") + ": no map with percept = \"roughness\" and use = \"compile\"");

  for (const auto& p : toml_files(dir / "levels")) {
    auto f = detail::read_validated(p, shown(p), "levels", problems, cache);
    if (!f) continue;
    std::string percept, map;
    auto levels = read_levels(*f, percept, map);
    const PsychophysicalMap* m = nullptr;
    for (const auto& x : s.maps_)
      if (x.id == map) m = &x;
    if (!m) problems.add(*f, *f->doc["map"].node(), "levels refer to map `" + map + "`, which calibration/maps/ lacks", "");
    else if (m->percept != percept)
      problems.add(*f, *f->doc["percept"].node(), "levels are for percept `" + percept + "` but map `" + map + "` is for `" +
                                                      m->percept + "`", "");
    std::set<std::string> names;
    for (const auto& l : levels) {
      if (!names.insert(l.name).second)
        problems.add(*f, *f->doc["level"].node(), "level `" + l.name + "` is named twice", "");
      s.levels_.emplace_back(percept, l);
      if (percept == "roughness") s.roughness_levels_.push_back(l);
    }
  }

  // Devices, then profiles (what a device with no file of its own is played with when the user
  // accepts that): one schema, and one name space, since both are found by name.
  std::set<std::string> device_names;
  const auto read_devices = [&](const char* folder, std::vector<DeviceCalibration>& into, const std::string& taken) {
    for (const auto& p : toml_files(dir / folder)) {
      auto f = detail::read_validated(p, shown(p), "device", problems, cache);
      if (!f) continue;
      auto d = read_device(*f, problems);
      if (!device_names.insert(d.name).second) problems.add(*f, *f->doc["name"].node(), "`" + d.name + "` " + taken, "");
      into.push_back(std::move(d));
    }
  };
  read_devices("devices", s.devices_, "is a device name used by two files");
  if (s.devices_.empty() && !problems.any()) problems.add_plain(shown(dir / "devices") + ": no device calibrations");
  read_devices("profiles", s.profiles_, "is a profile name that is also a device's or another profile's");

  // Device maps: the device file's [maps] entry, else the one use = "device" map naming the device.
  for (std::size_t i = 0; i < s.maps_.size(); ++i) {
    const auto& m = s.maps_[i];
    if (!m.for_device) continue;
    if (!s.find_device(m.domain_device)) {
      problems.add_plain(m.file + ": error: this use = \"device\" map is for device `" + m.domain_device +
                         "`, which calibration/devices/ lacks");
      continue;
    }
    const auto& d = *s.find_device(m.domain_device);
    if (!d.roughness_map.empty() && m.percept == "roughness") continue;  // the device file chooses
    for (const auto& [key, j] : s.device_maps_)
      if (key.first == m.domain_device && key.second == m.percept)
        problems.add_plain(m.file + ": error: device `" + m.domain_device + "` already has a " + m.percept + " map, " +
                           s.maps_[j].file + "; name the one to use in " + d.file + " ([maps] " + m.percept + " = \"<id>\")");
    s.device_maps_.push_back({{m.domain_device, m.percept}, i});
  }
  for (const auto& d : s.devices_) {
    if (d.roughness_map.empty()) continue;
    std::size_t found = s.maps_.size();
    for (std::size_t i = 0; i < s.maps_.size(); ++i)
      if (s.maps_[i].id == d.roughness_map) found = i;
    if (found == s.maps_.size())
      problems.add_plain(d.file + ": error: [maps] roughness names map `" + d.roughness_map + "`, which calibration/maps/ lacks");
    else if (s.maps_[found].percept != "roughness" || !(s.maps_[found].for_compile || s.maps_[found].for_device))
      problems.add_plain(d.file + ": error: [maps] roughness names map `" + d.roughness_map +
                         "`, which is not a roughness map with use = \"device\" or \"compile\"");
    else s.device_maps_.push_back({{d.name, "roughness"}, found});
  }

  detail::load_knowledge(dir / "knowledge", shown, s.knowledge_, problems, cache);
  problems.throw_if_any();
  return s;
}

void CalibrationSet::select_device(const std::string& name) { selected_ = name; }

const PsychophysicalMap* CalibrationSet::default_compile_map(const std::string& percept) const {
  for (const auto& m : maps_)
    if (m.for_compile && m.percept == percept) return &m;
  return nullptr;
}

const PsychophysicalMap* CalibrationSet::compile_map(const std::string& percept) const {
  if (!selected_.empty())
    for (const auto& [key, i] : device_maps_)
      if (key.first == selected_ && key.second == percept) return &maps_[i];
  return default_compile_map(percept);
}

const PsychophysicalMap* CalibrationSet::find_map(const std::string& id) const {
  for (const auto& m : maps_)
    if (m.id == id) return &m;
  return nullptr;
}

std::vector<const Level*> CalibrationSet::levels(const std::string& percept) const {
  std::vector<const Level*> out;
  for (const auto& [p, l] : levels_)
    if (p == percept) out.push_back(&l);
  return out;
}

const Level* CalibrationSet::find_level(const std::string& name) const {
  for (const auto& l : roughness_levels_)
    if (l.name == name) return &l;
  return nullptr;
}

const DeviceCalibration* CalibrationSet::find_device(const std::string& name) const {
  for (const auto& d : devices_)
    if (d.name == name) return &d;
  for (const auto& d : profiles_)
    if (d.name == name) return &d;
  return nullptr;
}

}  // namespace sandpaper::calibration

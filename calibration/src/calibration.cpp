#include "sandpaper/calibration/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <toml++/toml.h>

namespace sandpaper::calibration {
namespace {

constexpr double kGramForce = 9.80665e-3;  // N, standard gravity (ISO 80000-4)

toml::table parse_file(const std::filesystem::path& p) {
  if (!std::filesystem::exists(p)) throw CalibrationError("calibration file missing: " + p.string());
  try {
    return toml::parse_file(p.string());
  } catch (const toml::parse_error& e) {
    throw CalibrationError(p.string() + ":" + std::to_string(e.source().begin.line) + ": " + std::string(e.description()));
  }
}

double need_number(const toml::node_view<const toml::node>& v, const std::filesystem::path& p, const char* key) {
  auto x = v.value<double>();
  if (!x || !std::isfinite(*x)) throw CalibrationError(p.string() + ": missing or non-numeric `" + key + "`");
  return *x;
}

std::string need_string(const toml::node_view<const toml::node>& v, const std::filesystem::path& p, const char* key) {
  auto x = v.value<std::string>();
  if (!x || x->empty()) throw CalibrationError(p.string() + ": missing `" + key + "`");
  return *x;
}

RoughnessMap load_map(const std::filesystem::path& p) {
  auto t = parse_file(p);
  const toml::table& c = t;
  RoughnessMap m;
  m.path = p.string();
  m.id = need_string(c["id"], p, "id");
  if (need_string(c["law"], p, "law") != "power")
    throw CalibrationError(p.string() + ": only `law = \"power\"` maps are understood");
  m.slope = need_number(c["fit"]["slope"], p, "fit.slope");
  m.slope_se = need_number(c["fit"]["slope_se"], p, "fit.slope_se");
  m.intercept = need_number(c["fit"]["intercept"], p, "fit.intercept");
  m.intercept_se = need_number(c["fit"]["intercept_se"], p, "fit.intercept_se");
  m.r_squared = need_number(c["fit"]["r_squared"], p, "fit.r_squared");
  m.reference_force_N = need_number(c["ratio_scale"]["reference_force_gf"], p, "ratio_scale.reference_force_gf") * kGramForce;
  m.domain_force_min_N = need_number(c["domain"]["force_min_gf"], p, "domain.force_min_gf") * kGramForce;
  m.domain_force_max_N = need_number(c["domain"]["force_max_gf"], p, "domain.force_max_gf") * kGramForce;
  m.domain_period_min_m = need_number(c["domain"]["period_min_mm"], p, "domain.period_min_mm") * 1e-3;
  m.domain_period_max_m = need_number(c["domain"]["period_max_mm"], p, "domain.period_max_mm") * 1e-3;
  m.domain_texture = need_string(c["domain"]["texture"], p, "domain.texture");
  m.source = need_string(c["source"]["citation"], p, "source.citation") + ", " +
             need_string(c["source"]["where"], p, "source.where");
  if (!(m.slope > 0) || !(m.reference_force_N > 0) || !(m.domain_force_min_N < m.domain_force_max_N))
    throw CalibrationError(p.string() + ": slope, reference force and force domain must be positive and ordered");
  return m;
}

std::vector<RoughnessLevel> load_levels(const std::filesystem::path& p) {
  auto t = parse_file(p);
  std::vector<RoughnessLevel> out;
  auto* arr = t["level"].as_array();
  if (!arr || arr->empty()) throw CalibrationError(p.string() + ": no [[level]] entries");
  for (const auto& node : *arr) {
    auto* lt = node.as_table();
    if (!lt) throw CalibrationError(p.string() + ": [[level]] must be a table");
    const toml::table& l = *lt;
    RoughnessLevel lv;
    lv.name = need_string(l["name"], p, "level.name");
    lv.roughness = need_number(l["roughness"], p, "level.roughness");
    lv.rationale = need_string(l["rationale"], p, "level.rationale");
    out.push_back(std::move(lv));
  }
  return out;
}

DeviceCalibration load_device(const std::filesystem::path& p) {
  auto t = parse_file(p);
  const toml::table& c = t;
  DeviceCalibration d;
  d.path = p.string();
  d.name = need_string(c["name"], p, "name");
  d.max_force_N = need_number(c["max_force_N"], p, "max_force_N");
  d.newtons_per_command_unit = need_number(c["newtons_per_command_unit"], p, "newtons_per_command_unit");
  d.min_rate_hz = need_number(c["servo_rate_hz"]["min"], p, "servo_rate_hz.min");
  d.max_rate_hz = need_number(c["servo_rate_hz"]["max"], p, "servo_rate_hz.max");
  d.workspace_radius_m = need_number(c["workspace"]["radius_mm"], p, "workspace.radius_mm") * 1e-3;
  d.calibrated_by = need_string(c["calibrated_by"], p, "calibrated_by");
  if (!(d.max_force_N > 0) || !(d.min_rate_hz > 0) || !(d.min_rate_hz <= d.max_rate_hz))
    throw CalibrationError(p.string() + ": max force and servo rates must be positive and ordered");
  return d;
}

}  // namespace

double RoughnessMap::roughness_of(double force_N) const {
  if (!(force_N > 0)) return 0;
  return std::pow(force_N / reference_force_N, slope);
}

double RoughnessMap::force_for(double r) const {
  if (!(r > 0)) return 0;
  return reference_force_N * std::pow(r, 1.0 / slope);
}

CalibrationSet CalibrationSet::load(const std::filesystem::path& dir) {
  CalibrationSet s;
  s.dir_ = dir;
  s.map_ = load_map(dir / "roughness" / "minsky1995-fig19.toml");
  s.levels_ = load_levels(dir / "levels" / "roughness-levels.toml");
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir / "devices", ec))
    if (e.path().extension() == ".toml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) s.devices_.push_back(load_device(f));
  if (s.devices_.empty()) throw CalibrationError((dir / "devices").string() + ": no device calibrations");
  return s;
}

const RoughnessLevel* CalibrationSet::find_level(const std::string& name) const {
  for (const auto& l : levels_)
    if (l.name == name) return &l;
  return nullptr;
}

const DeviceCalibration* CalibrationSet::find_device(const std::string& name) const {
  for (const auto& d : devices_)
    if (d.name == name) return &d;
  return nullptr;
}

std::filesystem::path default_calibration_dir() {
  if (const char* env = std::getenv("SANDPAPER_CALIBRATION"); env && *env) return env;
  return SANDPAPER_DEFAULT_CALIBRATION_DIR;
}

}  // namespace sandpaper::calibration

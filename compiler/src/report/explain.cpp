#include "sandpaper/compiler/explain.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <iomanip>
#include <sstream>

#include "sandpaper/compiler/felt_at_speed.hpp"
#include "sandpaper/compiler/force_levels.hpp"
#include "sandpaper/compiler/knowledge_report.hpp"
#include "sandpaper/compiler/percepts.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::compiler {
namespace {

std::string num_text(double v) {
  std::ostringstream os;
  os << std::setprecision(4) << v;
  return os.str();
}

std::string pad(const std::string& s, std::size_t w) { return s.size() >= w ? s + " " : s + std::string(w - s.size(), ' '); }

}  // namespace

std::string explain_text(const ResolvedMaterial& m, const schema::PatchProgram& p,
                         const calibration::CalibrationSet& cal, const calibration::DeviceCalibration& device,
                         double design_speed_m_s, const DeviceRates& rates) {
  check_design_speed(design_speed_m_s);
  const auto& map = cal.roughness_map();
  std::ostringstream os;
  os << std::setprecision(4);
  os << "material  " << p.name << "\n";
  if (!p.describes.empty()) os << "describes \"" << p.describes << "\"\n";
  os << "device    " << device.name << " (" << device.file << "): maximum force " << device.max_force_N << " N, "
     << (device.command_unit == "N" ? std::string("commanded in newtons")
                                    : num_text(device.axis_scale(0).step_N(0)) + " N per " + device.command_unit)
     << (device.quantized() ? ", commands up to " + std::to_string(device.command_max) : std::string(", continuous")) << ", "
     << (device.status == calibration::CalibrationStatus::Calibrated ? "calibrated"
         : device.status == calibration::CalibrationStatus::Definition ? "exact by definition"
                                                                    : "UNCALIBRATED (scale assumed)")
     << "\n";
  if (device.wheel())
    os << "wheel     one axis along the rim: 1 mm of rim turns the wheel " << device.wheel_deg_per_mm() << " deg (rim radius "
       << device.wheel_rim_radius_m * 1e3 << " mm, " << device.wheel_rotation_range_rad * 180 / std::numbers::pi
       << " deg lock to lock); 1 N at the rim is " << device.wheel_rim_radius_m
       << " N*m; the patch's x lies along the rim, and forces across it (y) are not played\n";
  os << "\n";

  os << "layers (resolved in this order; what a file says beats what it inherits)\n";
  os << "  representative  ";
  if (m.like_chain.empty()) os << "none\n";
  else {
    for (std::size_t i = 0; i < m.like_chain.size(); ++i) os << (i ? " -> like " : "like ") << m.like_chain[i];
    os << "  (" << (m.like_origins.empty() ? "library/" + m.like_chain.front() + ".hmat" : m.like_origins.front())
       << ")\n";
  }
  os << "  perceptual      ";
  if (m.roughness)
    os << m.roughness->stated << " [" << layer_name(m.roughness->layer) << ", " << m.roughness->source << "]\n"
       << "                  -> maximum lateral force F = " << map.reference_si << " N * r^(1/" << map.slope
       << ") = " << m.max_lateral_force->si << " N  (" << map.provenance() << ")\n";
  else if (m.percepts.empty()) os << "none\n";
  os << explain_percepts(m, cal, /*inline_first=*/!m.roughness);
  os << "  physical        ";
  if (const auto* g = std::get_if<ResolvedGrating>(&m.texture))
    os << "grating, period " << g->period.stated << " [" << g->period.source << "]\n";
  else if (const auto* h = std::get_if<ResolvedHeightmap>(&m.texture))
    os << "height map \"" << h->stated_path << "\" [" << h->source << "]\n";
  else if (const auto* pt = std::get_if<ResolvedPattern>(&m.texture))
    os << "pattern " << pattern_kind_name(pt->kind) << " [" << pt->location.str() << "]\n";
  else os << "no texture\n";
  if (m.spring) os << "                  spring " << m.spring->stated << " [" << m.spring->source << "]\n";
  if (m.damper) os << "                  damper " << m.damper->stated << " [" << m.damper->source << "]\n";

  os << "\nparameters\n";
  // As wide as the longest name, so that a long law parameter (physics.NapFriction.against_kinetic)
  // does not push its row's columns out of line.
  std::size_t name_width = 28;
  for (const auto& pv : p.provenance) name_width = std::max(name_width, pv.parameter.size() + 1);
  os << "  " << pad("parameter", name_width) << pad("value", 14) << pad("layer", 16) << "source (as stated)\n";
  for (const auto& pv : p.provenance) {
    std::string value = pv.si_unit.empty() ? "" : schema::display_value(pv.value_si, pv.si_unit);
    os << "  " << pad(pv.parameter, name_width) << pad(value, 14) << pad(pv.layer, 16) << pv.source;
    if (!pv.stated.empty()) os << "  (" << pv.stated << ")";
    os << "\n";
  }

  os << "\nresult\n";
  if (p.max_lateral_force_N > 0) {
    os << "  compiled maximum lateral force " << p.max_lateral_force_N << " N (" << p.max_lateral_force_N / 9.80665e-3
       << " gf) over the patch less its rim\n";
    os << "  compiled roughness    " << schema::roughness_text(p.roughness) << " on the ratio scale (1 = " << map.reference_si
       << " N; " << map.id << ", R^2 = " << map.r_squared.value_or(0) << ")\n";
  } else {
    os << "  no texture: no lateral-force roughness\n";
  }
  if (auto levels = count_force_levels(p); levels.tables > 0)
    os << "  force levels          " << levels.magnitudes << " distinct magnitudes |F| (zero excluded), "
       << levels.signed_values << " distinct signed values; " << levels.samples << " samples in " << levels.tables
       << " force table" << (levels.tables == 1 ? "" : "s") << "\n";
  os << "  patch                 " << p.size_m[0] * 1e3 << " mm x " << p.size_m[1] * 1e3 << " mm, " << p.terms.size()
     << " force term" << (p.terms.size() == 1 ? "" : "s") << "\n";
  // The servo rate `run` plays this device at: 1000 Hz within the device's range.
  const double rate = default_servo_rate_hz(device);
  if (const auto felt = felt_at_explain_speeds(p, rate); !felt.empty()) {
    os << "\nfelt at speed (grating: the mean peak a tick reads per ridge, over every phase; docs/TEXTURES.md)\n";
    for (const auto& f : felt)
      os << "  " << f.speed_m_s * 1e3 << " mm/s at " << std::lround(f.rate_hz) << " Hz  " << f.peak_N << " N  ("
         << f.fraction * 100 << " % of the compiled peak), felt roughness " << schema::roughness_text(map.percept_of(f.peak_N)) << "\n";
    // The remedies, measured: at the designer's stated speed, else at the common hand speed that
    // loses the most (W0350's), if one loses more than a JND.
    const double weber = cal.knowledge().force_jnd.weber_fraction;
    double worst_speed = 0, worst = 1;
    for (const auto& f : felt_at_speed(p, kCommonHandSpeeds_m_s, {rate}))
      if (f.fraction < 1 - weber && f.fraction < worst) worst = f.fraction, worst_speed = f.speed_m_s;
    const double at = design_speed_m_s > 0 ? design_speed_m_s : worst_speed;
    if (at > 0) {
      const auto r = felt_remedies(m, p, at, rate, std::max(rate, device.max_rate_hz), weber);
      os << "  remedies at " << at * 1e3 << " mm/s (" << (design_speed_m_s > 0 ? "the design speed" : "more than one force JND lost")
         << " at " << std::lround(rate) << " Hz: " << r.now.peak_N << " N felt, " << r.now.fraction * 100 << " %):\n";
      if (r.fast_rate_hz > 0)
        os << "    servo at " << std::lround(r.fast_rate_hz) << " Hz: " << r.fast.peak_N << " N, roughness "
           << map.percept_of(r.fast.peak_N) << "\n";
      if (r.smoothing_m > 0)
        os << "    smoothing " << r.smoothing_m * 1e3 << " mm on the grating: " << r.smoothed.peak_N << " N, roughness "
           << map.percept_of(r.smoothed.peak_N) << "\n";
    }
  }
  const std::vector<double> out_speeds = device_output_speeds(design_speed_m_s);
  if (const auto out = device_output_at_speed(p, device, out_speeds, rates); !out.empty()) {
    const auto& chain = out.front();
    os << "\nout of " << device.name << " (positions to the servo at " << std::lround(chain.position_rate_hz)
       << " Hz, ticks at " << std::lround(chain.servo_rate_hz) << " Hz, commands on the bus at "
       << std::lround(chain.command_rate_hz) << " Hz, the firmware's updates at " << std::lround(chain.update_rate_hz)
       << " Hz, its damper against the motion; mean peak per ridge, both ways; docs/USB_PID.md)\n";
    for (const auto& o : out)
      os << "  " << o.speed_m_s * 1e3 << " mm/s  " << o.peak_N << " N  (" << o.commanded_peak_N << " N commanded, "
         << o.damping_N << " N damper)\n";
  }
  if (device.emulated && device.position_resolution_m > 0) {
    const double step_N = device.quantized() ? device.force_step_N(0) : 0.0;
    const auto tables = quantize_tables(p, device.position_resolution_m, step_N, device.command_max);
    if (!tables.empty())
      os << "\non " << device.name << " (positions in " << device.position_resolution_m * 1e3 << " mm steps, forces in "
         << step_N * 1e3 << " mN command units up to " << device.command_max << ", tables sample-and-hold)\n";
    for (const auto& q : tables)
      os << "  " << q.kind << "  " << q.positions_per_spacing << " position samples per "
         << (q.kind == "grating" ? "period" : "table sample") << " (" << q.spacing_m * 1e3 << " mm); "
         << q.device_levels << " distinct force levels sent (of " << q.table_levels << " in the table), largest "
         << q.largest_N << " N\n";
  }
  if (auto k = knowledge_text(assess_knowledge(m, p, cal), cal); !k.empty())
    os << "\nknowledge (what Minsky 1995 found; calibration/knowledge/)\n" << k;
  // The roughness maps relate a texture's peak lateral force to roughness; without a texture they
  // say nothing about this material.
  if (p.max_lateral_force_N > 0)
    os << "\nmaps (" << map.percept << ": the map compiled through, and the comparisons beside it)\n" << maps_text(cal);
  if (!p.warnings.empty()) {
    os << "\nwarnings\n";
    for (const auto& w : p.warnings) os << "  " << w.code << " " << w.message << "\n";
  }
  return os.str();
}

}  // namespace sandpaper::compiler

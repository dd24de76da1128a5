// The "explain" sections of a compile as JSON (explain_json.hpp).
#include "sandpaper/compiler/explain_json.hpp"

#include <algorithm>
#include <numbers>
#include <vector>

#include "sandpaper/compiler/felt_at_speed.hpp"
#include "sandpaper/compiler/force_levels.hpp"
#include "sandpaper/compiler/knowledge_report.hpp"
#include "sandpaper/compiler/percepts.hpp"

namespace sandpaper::compiler {

nlohmann::json explain_json(const ResolvedMaterial& material, const schema::PatchProgram& prog, const Compiler& c,
                            double design_speed_m_s, const DeviceRates& rates) {
  check_design_speed(design_speed_m_s);
  nlohmann::json j = nlohmann::json::object();
  j["knowledge"] = compiler::knowledge_json(compiler::assess_knowledge(material, prog, c.calibration()),
                                            c.calibration());
  j["maps"] = compiler::maps_json(c.calibration());
  j["percepts"] = compiler::percepts_json(material, c.calibration());
  // The same names as a run's report: `run --json` measures felt_peak_N where this predicts it.
  const auto& map = c.calibration().roughness_map();
  nlohmann::json felt = nlohmann::json::array();
  const double rate = compiler::default_servo_rate_hz(c.device());
  for (const auto& f : compiler::felt_at_explain_speeds(prog, rate))
    felt.push_back({{"speed_mm_s", f.speed_m_s * 1e3}, {"rate_hz", f.rate_hz}, {"felt_peak_N", f.peak_N},
                    {"felt_roughness", map.percept_of(f.peak_N)}, {"fraction", f.fraction}});
  j["felt_at_speed"] = felt;
  // Through the device's own firmware ([firmware] in its calibration file): empty without one.
  nlohmann::json out = nlohmann::json::array();
  const std::vector<double> out_speeds = compiler::device_output_speeds(design_speed_m_s);
  for (const auto& o : compiler::device_output_at_speed(prog, c.device(), out_speeds, rates))
    out.push_back({{"speed_mm_s", o.speed_m_s * 1e3}, {"rate_hz", o.rate_hz}, {"servo_rate_hz", o.servo_rate_hz},
                   {"position_rate_hz", o.position_rate_hz}, {"command_rate_hz", o.command_rate_hz},
                   {"update_rate_hz", o.update_rate_hz}, {"commanded_peak_N", o.commanded_peak_N},
                   {"damping_N", o.damping_N}, {"device_peak_N", o.peak_N}});
  j["device_output_at_speed"] = out;
  // The remedies at each common hand speed (W0350), measured: a faster servo, or wider walls.
  nlohmann::json remedies = nlohmann::json::array();
  const double weber = c.calibration().knowledge().force_jnd.weber_fraction;
  std::vector<double> speeds = compiler::kCommonHandSpeeds_m_s;
  if (design_speed_m_s > 0) speeds.push_back(design_speed_m_s);
  for (double v : speeds) {
    const auto r = compiler::felt_remedies(material, prog, v, rate, std::max(rate, c.device().max_rate_hz), weber);
    if (r.speed_m_s == 0) continue;
    remedies.push_back({{"speed_mm_s", v * 1e3}, {"design_speed", design_speed_m_s > 0 && v == speeds.back()},
                        {"rate_hz", rate}, {"felt_peak_N", r.now.peak_N}, {"fraction", r.now.fraction},
                        {"faster_servo", r.fast_rate_hz > 0 ? nlohmann::json{{"rate_hz", r.fast_rate_hz}, {"felt_peak_N", r.fast.peak_N}}
                                                            : nlohmann::json(nullptr)},
                        {"smoothing", r.smoothing_m > 0 ? nlohmann::json{{"smoothing_mm", r.smoothing_m * 1e3}, {"felt_peak_N", r.smoothed.peak_N}}
                                                        : nlohmann::json(nullptr)}});
  }
  j["felt_remedies"] = remedies;
  const auto& dev = c.device();
  // A wheel: how the patch's millimetres along x map onto its rotation.
  if (dev.wheel())
    j["wheel"] = {{"device", dev.name}, {"rim_radius_mm", dev.wheel_rim_radius_m * 1e3},
                  {"rotation_range_deg", dev.wheel_rotation_range_rad * 180 / std::numbers::pi},
                  {"deg_per_mm", dev.wheel_deg_per_mm()}, {"torque_N_m_per_N", dev.wheel_rim_radius_m}};
  // An emulated device (sandpaper-1995): what its quantisation leaves of each force table.
  if (dev.emulated && dev.position_resolution_m > 0) {
    const double step_N = dev.quantized() ? dev.force_step_N(0) : 0.0;
    nlohmann::json q = nlohmann::json::array();
    for (const auto& t : compiler::quantize_tables(prog, dev.position_resolution_m, step_N, dev.command_max))
      q.push_back({{"kind", t.kind}, {"spacing_mm", t.spacing_m * 1e3}, {"positions_per_spacing", t.positions_per_spacing},
                   {"table_levels", t.table_levels}, {"device_levels", t.device_levels}, {"largest_N", t.largest_N}});
    j["device_quantization"] = {{"device", dev.name}, {"position_step_mm", dev.position_resolution_m * 1e3},
                                {"force_step_N", step_N}, {"command_max", dev.command_max}, {"tables", q}};
  }
  return j;
}

}  // namespace sandpaper::compiler

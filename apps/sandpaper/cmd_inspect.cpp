#include <iostream>

#include "cli.hpp"
#include "sandpaper/schema/json_text.hpp"
#include "sandpaper/schema/patch_io.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::cli {

void print_patch_program(const schema::PatchProgram& p) {
  const auto j = schema::to_json(p, false);
  std::cout << "  material   " << p.name << "\n";
  if (!p.describes.empty()) std::cout << "  describes  \"" << p.describes << "\"\n";
  std::cout << "  device     " << p.device << "\n";
  std::cout << "  size       " << p.size_m[0] * 1e3 << " mm x " << p.size_m[1] * 1e3 << " mm\n";
  if (p.max_lateral_force_N > 0)
    std::cout << "  compiled maximum lateral force " << p.max_lateral_force_N << " N, compiled roughness " << schema::roughness_text(p.roughness) << " ("
              << p.roughness_map << ")\n";
  else
    std::cout << "  no texture (no lateral-force roughness)\n";
  if (p.energy_budget_J > 0 || p.energy_refill_W > 0)
    std::cout << "  energy bound " << p.energy_budget_J * 1e3 << " mJ, refill " << p.energy_refill_W * 1e3 << " mW\n";
  std::cout << "  terms\n";
  for (const auto& t : j["terms"]) std::cout << "    " << schema::json_text(t) << "\n";
  std::cout << "  provenance\n";
  for (const auto& pv : p.provenance)
    std::cout << "    " << pv.parameter << " = "
              << (pv.si_unit.empty() ? pv.stated : schema::display_value(pv.value_si, pv.si_unit)) << "  [" << pv.layer
              << "; " << pv.source << "]\n";
  for (const auto& w : p.warnings) std::cout << "  warning " << w.code << ": " << w.message << "\n";
}

int cmd_inspect(const std::string& file, bool json, bool tables) {
  auto p = schema::read_patch_file(file);
  if (json) {
    std::cout << schema::json_text(schema::to_json(p, tables), 2) << "\n";
    return kExitOk;
  }
  std::cout << file << ": Sandpaper patch program, format version " << schema::kPatchFormatVersion << "\n";
  print_patch_program(p);
  return kExitOk;
}

}  // namespace sandpaper::cli

#include <cmath>
#include <iostream>
#include <sstream>

#include "cli.hpp"
#include "sandpaper/compiler/compile_json.hpp"
#include "sandpaper/compiler/explain.hpp"
#include "sandpaper/compiler/sources_report.hpp"
#include "sandpaper/compiler/knowledge_report.hpp"
#include "sandpaper/schema/patch_io.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::cli {

namespace {

// The texture's maximum lateral force in the device's command units, as the device would round it.
std::string command_units(const schema::PatchProgram& p) {
  double u = p.max_lateral_force_N / p.command.newtons_per_command_unit[0];
  if (p.command.command_max > 0) u = std::round(u);
  std::ostringstream os;
  os << u << " " << p.command.command_unit;
  return os.str();
}

}  // namespace

int cmd_compile(const CommonOptions& o, const std::string& output, bool explain) {
  auto c = make_compiler(o);
  auto in = load_input(o, c, /*allow_patch=*/false);
  if (!in) return kExitBadInput;
  const auto& prog = in->program;
  std::string out_path = output;
  if (!explain && out_path.empty() && o.expression.empty())
    out_path = std::filesystem::path(o.file).replace_extension(".patch").string();
  if (!explain && !out_path.empty()) schema::write_patch_file(out_path, prog);

  if (o.json) {
    // One object with the studio's POST /api/compile (compiler/compile_json.hpp).
    auto j = compiler::compile_json(*in->compile, out_path.empty() ? std::nullopt : std::optional<std::string>(out_path));
    if (explain) {
      j.erase("output");
      j["knowledge"] = compiler::knowledge_json(compiler::assess_knowledge(*in->compile->material, prog, c.calibration()),
                                                c.calibration());
      j["maps"] = compiler::maps_json(c.calibration());
    }
    std::cout << j.dump(2) << "\n";
  } else if (explain) {
    std::cout << compiler::explain_text(*in->compile->material, prog, c.calibration(), c.device())
              << compiler::sources_text(*in->compile->material, c.library());
  } else {
    std::cout << prog.name << ": ";
    // Without a texture there is no lateral-force roughness to report (issue 2's rule for `run`).
    if (prog.max_lateral_force_N > 0)
      std::cout << "maximum lateral force " << prog.max_lateral_force_N << " N"
                << (prog.command.command_unit == "N" ? std::string() : " (" + command_units(prog) + ")") << ", roughness "
                << prog.roughness << ", ";
    else
      std::cout << "no texture, ";
    std::cout << prog.terms.size() << " term(s) for device " << prog.device;
    if (!out_path.empty()) std::cout << " -> " << out_path;
    std::cout << "\n";
  }
  return kExitOk;
}

int cmd_library(const CommonOptions& o) {
  auto c = make_compiler(o);
  nlohmann::json arr = nlohmann::json::array();
  int bad = 0;
  std::size_t width = 16;
  for (const auto& e : c.library().entries()) width = std::max(width, e.name.size() + 2);
  for (const auto& e : c.library().entries()) {
    auto r = c.compile_text(e.name, "<library " + e.name + ">");
    if (!r.ok()) {
      ++bad;
      std::cerr << compiler::format_diagnostics(r.diagnostics);
      continue;
    }
    const auto& p = *r.program;
    if (o.json) {
      arr.push_back({{"name", e.name}, {"family", e.family}, {"aliases", e.aliases}, {"describes", p.describes},
                     {"max_lateral_force_N", p.max_lateral_force_N}, {"roughness", p.roughness},
                     {"deprecated_by", e.deprecated_by}, {"file", e.relative_path}});
    } else {
      std::cout << e.name << std::string(width - e.name.size(), ' ') << e.family
                << std::string(e.family.size() < 20 ? 20 - e.family.size() : 1, ' ') << "roughness " << p.roughness << "  \""
                << p.describes << "\"" << (e.deprecated_by.empty() ? "" : "  [deprecated: use " + e.deprecated_by + "]") << "\n";
    }
  }
  if (o.json) std::cout << arr.dump(2) << "\n";
  return bad ? kExitBadInput : kExitOk;
}

}  // namespace sandpaper::cli

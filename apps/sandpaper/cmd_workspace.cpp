// `sandpaper compile|explain|run ws.hws`: workspaces of patches (thesis Appendix B).
#include <cmath>
#include <iostream>
#include <sstream>

#include <fmt/format.h>
#include <unistd.h>

#include "cli.hpp"
#include "sandpaper/player/play.hpp"
#include "sandpaper/compiler/knowledge_report.hpp"
#include "sandpaper/compiler/workspace.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/runtime/workspace_evaluator.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/json_text.hpp"
#include "sandpaper/schema/workspace_io.hpp"
#include "sandpaper/schema/workspace_json.hpp"

namespace sandpaper::cli {
namespace {

std::optional<schema::WorkspaceProgram> load_workspace(const CommonOptions& o, const compiler::Compiler& c,
                                                       compiler::Diagnostics& diags) {
  auto r = compiler::compile_workspace_file(c, o.file);
  std::cerr << compiler::format_diagnostics(r.diagnostics);
  diags = r.diagnostics;
  if (!r.ok()) {
    if (o.json)
      std::cout << schema::json_text(nlohmann::json{{"ok", false}, {"diagnostics", diagnostics_json(r.diagnostics)}}, 2)
                << "\n";
    return std::nullopt;
  }
  return std::move(*r.program);
}

}  // namespace

int cmd_workspace_compile(const CommonOptions& o, const std::string& output, bool explain) {
  auto c = make_compiler(o);
  compiler::Diagnostics diags;
  auto ws = load_workspace(o, c, diags);
  if (!ws) return kExitBadInput;
  std::string out_path = output;
  if (!explain && out_path.empty()) out_path = std::filesystem::path(o.file).replace_extension(".json").string();
  // A `.wsp` output is the binary workspace program the runtime-only player plays; anything else the JSON view.
  // The JSON view holds every patch's program, so it is built only when asked for (65,536 patches: 1 GB).
  const bool wsp = !explain && std::filesystem::path(out_path).extension() == ".wsp";
  nlohmann::json j;
  if (o.json || (!explain && !wsp)) j = schema::to_json(*ws);
  if (wsp)
    schema::write_workspace_program_file(out_path, *ws, {o.compact});
  else if (!explain)
    schema::write_file_atomically(out_path, schema::json_text(j, 2) + "\n");

  const auto& jnd = c.calibration().knowledge().force_jnd;
  const auto order = compiler::roughness_order(*ws, jnd);
  if (o.json) {
    auto out = j;
    out["ok"] = true;
    out["diagnostics"] = diagnostics_json(diags);
    if (!explain) out["output"] = out_path;
    if (explain) {
      nlohmann::json steps = nlohmann::json::array();
      for (std::size_t i = 0; i < order.size(); ++i)
        steps.push_back({{"patch", order[i].patch + 1},
                         {"material", order[i].material},
                         {"name", order[i].name},
                         {"compiled_max_lateral_force_N", order[i].force_N},
                         {"compiled_roughness", order[i].roughness},
                         {"jnd_steps_to_next", i + 1 < order.size() ? nlohmann::json(order[i].jnd_to_next) : nlohmann::json(nullptr)}});
      out["roughness_order"] = steps;
      out["force_jnd"] = {{"weber_fraction", jnd.weber_fraction}, {"source", compiler::jnd_source(jnd)}, {"file", jnd.file}};
    }
    std::cout << schema::json_text(out, 2) << "\n";
    return kExitOk;
  }
  std::cout << fmt::format("workspace \"{}\": {:g} mm x {:g} mm, {} patch{} for device {}", ws->name, ws->size_m[0] * 1e3,
                           ws->size_m[1] * 1e3, ws->patches.size(), ws->patches.size() == 1 ? "" : "es", o.device);
  if (!explain) {
    std::cout << " -> " << out_path << "\n";
    return kExitOk;
  }
  std::cout << "\n  painting order: patch 1 is at the back, each later patch lies in front; only the frontmost patch\n"
               "  under the hand sends force (thesis Appendix B). Positions are patch centres, origin at the workspace centre.\n";
  for (std::size_t i = 0; i < ws->patches.size(); ++i) {
    const auto& p = *ws->patches[i].program;
    std::cout << "  " << patch_line(*ws, i) << "\n";
    std::cout << fmt::format("      material {}; maximum lateral force {:.4g} N, roughness {:.3g}; {} term{}\n", p.name,
                             p.max_lateral_force_N, p.roughness, p.terms.size(), p.terms.size() == 1 ? "" : "s");
    if (!p.describes.empty()) std::cout << "      describes \"" << p.describes << "\"\n";
  }
  if (!order.empty()) {
    std::cout << "  roughness order: the textured materials by maximum lateral force, with the force JNDs between\n"
                 "  neighbours (one JND = " << compiler::jnd_source(jnd) << ")\n";
    for (std::size_t i = 0; i < order.size(); ++i) {
      std::cout << fmt::format("    {:<28} patch {:<3} {:.4g} N, roughness {:.3g}\n", "\"" + order[i].material + "\"",
                               order[i].patch + 1, order[i].force_N, order[i].roughness);
      if (i + 1 == order.size()) continue;
      const double steps = order[i].jnd_to_next;
      if (order[i + 1].force_N <= order[i].force_N * (1 + 1e-9))
        std::cout << "      same force, equally rough (W0503 warns only for forces that differ, by less than one JND)\n";
      else
        std::cout << fmt::format("      {:.2f} JND{}\n", steps, steps < 1 ? " (less than one: they feel equally rough, W0503)" : "");
    }
  }
  return kExitOk;
}

int cmd_workspace_run(const CommonOptions& o, const WorkspaceRunOptions& ro) {
  auto c = make_compiler(o);
  if (o.device != "sim") {
    std::cerr << "sandpaper: error: device '" << o.device << "' cannot be played yet; only --device sim runs\n";
    return kExitUsage;
  }
  const runtime::DeviceLimits limits = limits_of(c);
  if (const int rc = check_workspace_request(ro, limits); rc != kExitOk) return rc;
  compiler::Diagnostics diags;
  auto ws = load_workspace(o, c, diags);
  if (!ws) return kExitBadInput;
  return play_workspace_on_sim(*ws, c.calibration(), ro);
}

}  // namespace sandpaper::cli

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

#include "cli.hpp"
#include "sandpaper/compiler/compile_json.hpp"
#include "sandpaper/compiler/explain.hpp"
#include "sandpaper/compiler/explain_json.hpp"
#include "sandpaper/compiler/display_paths.hpp"
#include "sandpaper/compiler/felt_at_speed.hpp"
#include "sandpaper/compiler/force_levels.hpp"
#include "sandpaper/compiler/sources_report.hpp"
#include "sandpaper/compiler/knowledge_report.hpp"
#include "sandpaper/schema/json_text.hpp"
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

// What --compact did, on stderr: nothing to say without height fields.
std::string compact_note(const schema::CompactReport& r) {
  if (r.compacted + r.kept == 0) return {};
  std::ostringstream os;
  os << "compact: " << r.compacted << " height-field grid pair(s) as 16-bit floats (largest error "
     << r.largest_error * 100 << " % of the grid's largest force)";
  if (r.kept) os << ", " << r.kept << " kept as 32-bit floats (16 bits would move a force by more than 0.1 %)";
  os << "\n";
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
  schema::CompactReport compacted;
  if (!explain && !out_path.empty()) schema::write_patch_file(out_path, prog, {o.compact}, &compacted);
  if (o.compact && !o.json) std::cerr << compact_note(compacted);

  if (o.json) {
    // One object with the studio's POST /api/compile (compiler/compile_json.hpp).
    auto j = compiler::compile_json(*in->compile, out_path.empty() ? std::nullopt : std::optional<std::string>(out_path));
    if (explain) {
      j.erase("output");
      j.update(compiler::explain_json(*in->compile->material, prog, c, o.design_speed_mm_s * 1e-3,
                                              {0, o.position_rate_hz, o.command_rate_hz}));
    }
    std::cout << schema::json_text(j, 2) << "\n";
  } else if (explain) {
    // Library files where the user can open them, as `library check` and `library show` print them.
    const compiler::DisplayPaths shown(c.library());
    std::cout << shown.in_text(compiler::explain_text(*in->compile->material, prog, c.calibration(), c.device(),
                                                      o.design_speed_mm_s * 1e-3,
                                                      {0, o.position_rate_hz, o.command_rate_hz}) +
                               compiler::sources_text(*in->compile->material, c.library()));
  } else {
    std::cout << prog.name << ": ";
    // Without a texture there is no lateral-force roughness to report (the rule `run` follows).
    if (prog.max_lateral_force_N > 0)
      std::cout << "compiled maximum lateral force " << prog.max_lateral_force_N << " N"
                << (prog.command.command_unit == "N" ? std::string() : " (" + command_units(prog) + ")") << ", compiled roughness "
                << schema::roughness_text(prog.roughness) << ", ";
    else
      std::cout << "no texture, ";
    std::cout << prog.terms.size() << " term(s) for device " << prog.device;
    if (!out_path.empty()) std::cout << " -> " << out_path;
    std::cout << "\n";
  }
  return kExitOk;
}

// Many materials in one process: the library and calibration are read once, and each material costs
// only its own compile (docs/performance.md, "Batch compile").
int cmd_compile_batch(const CommonOptions& o, const std::vector<std::string>& inputs, const std::string& out_dir) {
  if (out_dir.empty()) {
    std::cerr << "sandpaper compile: several inputs (or a folder) need -o FOLDER for the patch programs\n";
    return kExitUsage;
  }
  // (input file, output file): a folder's materials keep their place below it.
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> jobs;
  for (const auto& in : inputs) {
    const std::filesystem::path path(in);
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
      std::vector<std::filesystem::path> found;
      for (auto it = std::filesystem::recursive_directory_iterator(path, ec); !ec && it != std::filesystem::recursive_directory_iterator();
           it.increment(ec))
        if (it->is_regular_file() && it->path().extension() == ".hmat") found.push_back(it->path());
      std::sort(found.begin(), found.end());
      for (const auto& f : found)
        jobs.emplace_back(f, std::filesystem::path(out_dir) / std::filesystem::relative(f, path).replace_extension(".patch"));
    } else if (std::filesystem::is_regular_file(path, ec) && path.extension() == ".hmat") {
      jobs.emplace_back(path, std::filesystem::path(out_dir) / path.filename().replace_extension(".patch"));
    } else {
      std::cerr << "sandpaper compile: " << in << " is neither a material file (.hmat) nor a folder\n";
      return kExitUsage;
    }
  }
  std::map<std::filesystem::path, std::filesystem::path> claimed;
  for (const auto& [in, out] : jobs)
    if (auto [it, fresh] = claimed.emplace(out, in); !fresh) {
      std::cerr << "sandpaper compile: " << it->second.string() << " and " << in.string() << " would both write " << out.string()
                << "; compile them into different folders\n";
      return kExitUsage;
    }
  if (jobs.empty()) {
    std::cerr << "sandpaper compile: no material files (.hmat) in " << inputs.front() << "\n";
    return kExitUsage;
  }
  const auto start = std::chrono::steady_clock::now();
  auto c = make_compiler(o);
  std::size_t failed = 0;
  nlohmann::json results = nlohmann::json::array();
  for (const auto& [in, out] : jobs) {
    auto r = c.compile_file(in);
    std::cerr << compiler::format_diagnostics(r.diagnostics);
    if (r.ok()) {
      std::filesystem::create_directories(out.parent_path());
      schema::CompactReport compacted;
      schema::write_patch_file(out, *r.program, {o.compact}, &compacted);  // written to a temporary file and renamed
    } else {
      ++failed;
    }
    if (o.json)
      results.push_back({{"input", in.string()},
                         {"output", r.ok() ? nlohmann::json(out.string()) : nlohmann::json(nullptr)},
                         {"ok", r.ok()},
                         {"diagnostics", diagnostics_json(r.diagnostics)}});
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (o.json)
    std::cout << schema::json_text(nlohmann::json{{"ok", failed == 0},
                                                  {"compiled", jobs.size() - failed},
                                                  {"failed", failed},
                                                  {"seconds", seconds},
                                                  {"results", results}},
                                   2)
              << "\n";
  else
    std::cout << "compiled " << jobs.size() - failed << " of " << jobs.size() << " material(s) into " << out_dir << " in "
              << std::round(seconds * 100) / 100 << " s" << (failed ? ", " + std::to_string(failed) + " with errors (nothing written for them)" : "")
              << "\n";
  return failed ? kExitBadInput : kExitOk;
}

int cmd_library(const CommonOptions& o) {
  auto c = make_compiler(o);
  nlohmann::json arr = nlohmann::json::array();
  int bad = 0;
  std::size_t width = 16;
  const auto& lib = c.library();
  // In a layered library every root's entries are listed by qualified name (lab:corduroy), the
  // hidden ones too, marked.
  for (const auto& e : lib.entries()) width = std::max(width, lib.qualified_name(e).size() + 2);
  for (const auto& e : lib.entries()) {
    const std::string name = lib.qualified_name(e);
    auto r = c.compile_text(name, "<library " + name + ">");
    if (!r.ok()) {
      ++bad;
      std::cerr << compiler::format_diagnostics(r.diagnostics);
      continue;
    }
    const auto& p = *r.program;
    if (o.json) {
      nlohmann::json j{{"name", e.name}, {"family", e.family}, {"aliases", e.aliases}, {"describes", p.describes},
                       {"compiled_max_lateral_force_N", p.max_lateral_force_N}, {"compiled_roughness", p.roughness},
                       {"deprecated_by", e.deprecated_by}, {"file", e.relative_path}};
      if (lib.layered()) j["root"] = lib.roots()[e.root].id, j["hidden"] = lib.entry(e.name) != &e;
      arr.push_back(std::move(j));
    } else {
      std::cout << name << std::string(width - name.size(), ' ') << e.family
                << std::string(e.family.size() < 20 ? 20 - e.family.size() : 1, ' ') << "roughness " << schema::roughness_text(p.roughness) << "  \""
                << p.describes << "\"" << (e.deprecated_by.empty() ? "" : "  [deprecated: use " + e.deprecated_by + "]")
                << (lib.entry(e.name) == &e ? "" : "  [hidden by " + lib.qualified_name(*lib.entry(e.name)) + "]") << "\n";
    }
  }
  if (o.json) std::cout << schema::json_text(arr, 2) << "\n";
  return bad ? kExitBadInput : kExitOk;
}

}  // namespace sandpaper::cli

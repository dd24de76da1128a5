#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "sandpaper/compiler/knowledge_report.hpp"
#include "sandpaper/compiler/workspace.hpp"
#include "sandpaper/compiler/workspace_parser.hpp"
#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::compiler {
namespace {

namespace fs = std::filesystem;

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string mm(double m) {
  std::ostringstream os;
  os.precision(6);
  os << m * 1e3 << " mm";
  return os.str();
}

// One compiled material, shared by every patch that names it (a 1,000-patch workspace of a few
// materials compiles each once).
struct CompiledMaterial {
  std::shared_ptr<const CompileResult> result;
  std::vector<std::size_t> patches;  // indices of the patches that use it
};

// The key that makes two patches the same material: the resolved file for paths, the text otherwise.
std::string material_key(const std::string& material, const fs::path& base_dir, fs::path& file) {
  if (ends_with(material, ".hmat")) {
    file = (base_dir / material).lexically_normal();
    return "file:" + file.string();
  }
  file.clear();
  return "text:" + material;
}

// Appends the material's diagnostics, each with notes pointing at the patches that use it.
void report_material(const CompiledMaterial& cm, const WorkspaceSyntax& syntax, Diagnostics& out) {
  Diagnostics annotated;
  for (Diagnostic d : cm.result->diagnostics.all()) {
    constexpr std::size_t kShown = 3;
    for (std::size_t k = 0; k < cm.patches.size() && k < kShown; ++k) {
      const std::size_t i = cm.patches[k];
      d.notes.push_back({syntax.patches[i].material_location, "in the material of patch " + std::to_string(i + 1) + ", placed here"});
    }
    if (cm.patches.size() > kShown)
      d.notes.push_back({syntax.patches[cm.patches[kShown]].material_location,
                         "and " + std::to_string(cm.patches.size() - kShown) + " more patches with the same material"});
    if (d.severity == Severity::Error)
      annotated.error(schema::Code::of(d.code), d.location, d.message, d.suggestion).notes = d.notes;
    else
      annotated.warning(schema::Code::of(d.code), d.location, d.message, d.suggestion).notes = d.notes;
  }
  out.append(annotated);
}

std::string sig(double v, int precision) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}
std::string newtons(double f) { return sig(f, 4) + " N"; }

// W0503: two textured materials whose maximum lateral forces differ by less than one force JND
// (5.4.2) feel equally rough, whatever else differs. Exactly equal forces are the same roughness
// asked for on purpose (Table 8's one level at five periods, examples/workspace/periods.hws) and
// are not warned about.
void warn_within_one_jnd(const Compiler& compiler, const WorkspaceSyntax& syntax,
                         const std::vector<CompiledMaterial>& materials, Diagnostics& diags) {
  const auto& jnd = compiler.calibration().knowledge().force_jnd;
  const auto& map = compiler.calibration().roughness_map();
  struct Textured {
    std::size_t patch;
    double force;
  };
  std::vector<Textured> textured;
  for (const auto& cm : materials)
    if (cm.result->ok() && cm.result->program->max_lateral_force_N > 0 && !cm.patches.empty())
      textured.push_back({cm.patches.front(), cm.result->program->max_lateral_force_N});
  std::sort(textured.begin(), textured.end(), [](const auto& a, const auto& b) { return a.patch < b.patch; });
  auto label = [&](const Textured& t) {
    return "patch " + std::to_string(t.patch + 1) + " (\"" + syntax.patches[t.patch].material + "\", " + newtons(t.force) + ")";
  };
  // Every pair is compared, but only the first kShownPairs are spelled out: 2,000 materials have
  // millions of close pairs, and one summary says how many more there are.
  constexpr std::size_t kShownPairs = 20;
  std::size_t close_pairs = 0;
  for (std::size_t j = 1; j < textured.size(); ++j)
    for (std::size_t i = 0; i < j; ++i) {
      const double lo = std::min(textured[i].force, textured[j].force), hi = std::max(textured[i].force, textured[j].force);
      if (hi <= lo * (1 + 1e-9)) continue;
      const double steps = jnd.steps_between(lo, hi);
      if (steps >= 1) continue;
      if (++close_pairs > kShownPairs) continue;
      const double apart = lo * (1 + jnd.weber_fraction);
      auto& d = diags.warning(
          "W0503", syntax.patches[textured[j].patch].material_location,
          label(textured[j]) + " and " + label(textured[i]) + " differ by " + sig(steps, 2) +
              " force JND in maximum lateral force: they will feel equally rough (one JND at " + newtons(lo) + " is " +
              newtons(jnd.jnd_at(lo)) + ", " + jnd_source(jnd) + ")",
          "make the stronger one at least " + newtons(apart) + " (roughness " +
              sig(map.percept_of(apart), 3) + "), or give both patches the same material");
      d.notes.push_back({syntax.patches[textured[i].patch].material_location,
                         "patch " + std::to_string(textured[i].patch + 1) + "'s material"});
    }
  if (close_pairs > kShownPairs)
    diags.warning("W0503", syntax.name_location.file ? syntax.name_location : SourceLocation{syntax.file, 0, 0, 1},
                  "and " + std::to_string(close_pairs - kShownPairs) +
                      " more pairs of textured materials less than one force JND apart (" +
                      std::to_string(kShownPairs) + " are listed above)",
                  "spread the materials' forces by at least one JND, or use fewer distinct materials");
}

// The force tables a workspace holds, against limits::kMaxWorkspaceGridBytes: distinct textures are
// not shared, and six at 4000 x 4000 samples took 1.1 GB (F35).
struct GridBudget {
  std::uint64_t limit = schema::limits::kMaxWorkspaceGridBytes;
  std::uint64_t held = 0;
  bool over = false;
  // Counts `program`'s tables for patch `i`; past the budget, E0535 at the patch and false.
  bool take(const schema::PatchProgram& program, std::size_t i, const PatchPlacementSyntax& p, Diagnostics& diags,
            const std::string& what) {
    const std::uint64_t bytes = schema::grid_bytes(program);
    if (bytes <= limit && held <= limit - bytes) {
      held += bytes;
      return true;
    }
    over = true;
    diags.error("E0535", p.material_location,
                "patch " + std::to_string(i + 1) + " needs " + mib(bytes) + " of force tables for " + what + ", with " +
                    mib(held) + " already held: over the workspace's limit of " + mib(limit),
                "use fewer distinct large textures, a coarser `sampling` or a smaller image, or place the patches of "
                "one material at one size (they then share one program)");
    return false;
  }
  static std::string mib(std::uint64_t bytes) { return sig(static_cast<double>(bytes) / (1 << 20), 4) + " MiB"; }
};

std::shared_ptr<const CompileResult> compile_material(const Compiler& compiler, const WorkspaceMaterial& m,
                                                      const WorkspaceOptions& options) {
  if (options.compile_material) {
    auto r = options.compile_material(compiler, m);
    if (!r) throw std::logic_error("WorkspaceOptions::compile_material returned no result for " + m.text);
    return r;
  }
  return compile_workspace_material(compiler, m);
}

WorkspaceResult compile_syntax(const Compiler& compiler, const WorkspaceSyntax& syntax, const fs::path& base_dir,
                               Diagnostics diags, const WorkspaceOptions& options) {
  WorkspaceResult r;
  schema::WorkspaceProgram ws;
  ws.name = syntax.name;
  if (syntax.width) {
    ws.size_m[0] = syntax.width->si;
    ws.size_m[1] = syntax.height ? syntax.height->si : syntax.width->si;
  }

  // Compile each distinct material once, in order of first use. The force tables held (compiled and
  // placed) are counted as they come, and the first patch past the budget stops the compile (F35).
  GridBudget grids{options.max_grid_bytes};
  std::map<std::string, std::size_t> index_of;
  std::vector<CompiledMaterial> materials;
  std::vector<std::size_t> material_of(syntax.patches.size());
  for (std::size_t i = 0; i < syntax.patches.size(); ++i) {
    const auto& p = syntax.patches[i];
    fs::path file;
    const std::string key = material_key(p.material, base_dir, file);
    auto [it, fresh] = index_of.emplace(key, materials.size());
    if (fresh) {
      CompiledMaterial cm;
      cm.result = compile_material(compiler, {p.material, file, "<patch " + std::to_string(i + 1) + ">"}, options);
      const bool within = !cm.result->ok() || grids.take(*cm.result->program, i, p, diags, "its material's program");
      materials.push_back(std::move(cm));
      if (!within) break;
    }
    materials[it->second].patches.push_back(i);
    material_of[i] = it->second;
  }
  for (const auto& cm : materials) report_material(cm, syntax, diags);
  if (grids.over) {
    r.diagnostics = std::move(diags);
    return r;
  }

  // Place the patches: the placed size, or the material's own.
  std::map<std::tuple<std::size_t, double, double>, std::shared_ptr<const schema::PatchProgram>> placed;
  const double half_w = 0.5 * ws.size_m[0], half_h = 0.5 * ws.size_m[1];
  for (std::size_t i = 0; i < syntax.patches.size(); ++i) {
    const auto& p = syntax.patches[i];
    const CompileResult& cr = *materials[material_of[i]].result;
    if (!cr.ok()) continue;
    double size[2];
    if (p.width) {
      size[0] = p.width->si;
      size[1] = p.height ? p.height->si : p.width->si;
    } else {
      size[0] = cr.program->size_m[0];
      size[1] = cr.program->size_m[1];
    }
    const double centre[2] = {p.x.si, p.y.si};
    // A nanometre of slack so that a patch written flush with the edge ("at 94.3 mm" for a 40 mm patch
    // in a 228.6 mm workspace) is not refused for the rounding of its decimal millimetres.
    constexpr double kSlack_m = 1e-9;
    const double left = centre[0] - 0.5 * size[0], right = centre[0] + 0.5 * size[0];
    const double bottom = centre[1] - 0.5 * size[1], top = centre[1] + 0.5 * size[1];
    if (left < -half_w - kSlack_m || right > half_w + kSlack_m || bottom < -half_h - kSlack_m || top > half_h + kSlack_m) {
      diags.error("E0507", p.at_location,
                  "patch " + std::to_string(i + 1) + " (" + mm(size[0]) + " x " + mm(size[1]) + ") spans x " + mm(left) +
                      " to " + mm(right) + ", y " + mm(bottom) + " to " + mm(top) + ": outside the workspace (x and y within +-" +
                      mm(half_w) + ", +-" + mm(half_h) + ")",
                  "move it inward, make it smaller, or make the workspace larger with `size W x H`");
      continue;
    }
    // One program per material and size, shared by every patch that places it so.
    auto& shared = placed[{material_of[i], size[0], size[1]}];
    if (!shared) {
      if (!grids.take(*cr.program, i, p, diags, "a copy of its material's program placed at " + mm(size[0]) + " x " + mm(size[1])))
        break;
      shared = schema::place_patch(*cr.program, centre, size, p.material).program;
    }
    ws.patches.push_back(schema::place_shared_patch(shared, centre, p.material));
  }
  if (diags.has_errors()) {
    r.diagnostics = std::move(diags);
    return r;
  }

  if (ws.patches.empty())
    diags.warning("W0501", syntax.name_location.file ? syntax.name_location : SourceLocation{syntax.file, 0, 0, 1},
                  "the workspace has no patches", "add patch \"material\" at X, Y size W x H lines");
  // A patch inside one later (in front of it) never sends force. O(n^2) over rectangles: 10^6 cheap
  // tests for 1,000 patches.
  for (std::size_t i = 0; i < ws.patches.size(); ++i) {
    const auto& a = ws.patches[i];
    for (std::size_t j = ws.patches.size(); j-- > i + 1;) {
      const auto& b = ws.patches[j];
      const bool inside = std::abs(a.centre_m[0] - b.centre_m[0]) + 0.5 * a.size_m[0] <= 0.5 * b.size_m[0] &&
                          std::abs(a.centre_m[1] - b.centre_m[1]) + 0.5 * a.size_m[1] <= 0.5 * b.size_m[1];
      if (!inside) continue;
      auto& d = diags.warning("W0502", syntax.patches[i].location,
                              "patch " + std::to_string(i + 1) + " lies wholly behind patch " + std::to_string(j + 1) +
                                  " and never sends force",
                              "move it, or put it after patch " + std::to_string(j + 1) + " to bring it to the front");
      d.notes.push_back({syntax.patches[j].location, "patch " + std::to_string(j + 1) + " covers it"});
      break;
    }
  }
  warn_within_one_jnd(compiler, syntax, materials, diags);
  r.diagnostics = std::move(diags);
  r.program = std::move(ws);
  return r;
}

}  // namespace

std::vector<RoughnessStep> roughness_order(const schema::WorkspaceProgram& ws, const calibration::ForceJndData& jnd) {
  std::vector<RoughnessStep> out;
  for (std::size_t i = 0; i < ws.patches.size(); ++i) {
    const auto& p = ws.patches[i];
    if (!(p.program->max_lateral_force_N > 0)) continue;
    bool seen = false;
    for (const auto& s : out) seen = seen || s.material == p.source;
    if (!seen) out.push_back({i, p.source, p.program->name, p.program->max_lateral_force_N, p.program->roughness, 0});
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.force_N < b.force_N; });
  for (std::size_t i = 0; i + 1 < out.size(); ++i) out[i].jnd_to_next = jnd.steps_between(out[i].force_N, out[i + 1].force_N);
  return out;
}

bool is_workspace_path(const fs::path& path) { return path.extension() == ".hws"; }

std::shared_ptr<const CompileResult> compile_workspace_material(const Compiler& compiler, const WorkspaceMaterial& m) {
  return std::make_shared<const CompileResult>(m.file.empty() ? compiler.compile_text(m.text, m.display_name)
                                                              : compiler.compile_file(m.file));
}

WorkspaceResult compile_workspace_text(const Compiler& compiler, const std::string& text, const std::string& display_name,
                                       const fs::path& base_dir, const WorkspaceOptions& options) {
  auto file = std::make_shared<const SourceFile>(display_name, text);
  Diagnostics diags;
  auto tokens = lex(file, diags, LexOptions{.commas = true});
  WorkspaceSyntax syntax = parse_workspace(tokens, file, diags);
  // Never use the output of a failed phase: a syntax error stops before any material is compiled.
  if (diags.has_errors()) {
    WorkspaceResult r;
    r.diagnostics = std::move(diags);
    return r;
  }
  return compile_syntax(compiler, syntax, base_dir, std::move(diags), options);
}

WorkspaceResult compile_workspace_file(const Compiler& compiler, const fs::path& path, const WorkspaceOptions& options) {
  std::string text;
  try {
    text = schema::read_input_file(path, schema::limits::kMaxSourceBytes);
  } catch (const schema::InputFileError& e) {
    WorkspaceResult r;
    auto f = std::make_shared<const SourceFile>(path.string(), "");
    r.diagnostics.error("E0500", SourceLocation{f, 0, 0, 1}, "cannot open workspace file '" + path.string() + "': " + e.reason,
                        "check the path; workspace files end in .hws");
    return r;
  }
  return compile_workspace_text(compiler, text, path.string(), path.parent_path(), options);
}

}  // namespace sandpaper::compiler

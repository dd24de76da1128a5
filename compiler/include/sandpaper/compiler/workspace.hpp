#pragma once
// Workspace files (.hws) -> WorkspaceProgram: every patch's material compiled for the compiler's
// device and placed on the workspace (thesis Appendix B). Any error, in the workspace or in a
// patch's material, means no program. Language: schema/LANGUAGE.md, "Workspaces".
//
//   auto r = sandpaper::compiler::compile_workspace_file(compiler, "examples/workspace/sampler.hws");
//   if (!r.ok()) std::cerr << format_diagnostics(r.diagnostics);
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/schema/workspace_program.hpp"

namespace sandpaper::compiler {

struct WorkspaceResult {
  Diagnostics diagnostics;
  std::optional<schema::WorkspaceProgram> program;  // set only if there were no errors at all
  bool ok() const { return program.has_value() && !diagnostics.has_errors(); }
};

// The textured materials of a workspace in order of maximum lateral force (the roughness scale),
// each with the force JNDs to the next stronger one (Minsky 1995 5.4.2; calibration/knowledge/
// force-jnd.toml). Patches with the same material text are one material.
struct RoughnessStep {
  std::size_t patch = 0;        // the first patch (0-based) with this material
  std::string material;         // the patch's material as written
  std::string name;             // the compiled material's name
  double force_N = 0;           // maximum lateral force
  double roughness = 0;
  double jnd_to_next = 0;       // force JNDs to the next material in the order; 0 for the last
};
std::vector<RoughnessStep> roughness_order(const schema::WorkspaceProgram& ws, const calibration::ForceJndData& jnd);

// Whether `path` names a workspace file (extension .hws).
bool is_workspace_path(const std::filesystem::path& path);

// One distinct material of a workspace, as WorkspaceOptions::compile_material is asked for it.
struct WorkspaceMaterial {
  std::string text;             // the patch's material as written: "corduroy", "../grass.hmat"
  std::filesystem::path file;   // the .hmat it names, resolved against the workspace's folder; empty for material text
  std::string display_name;     // the name material text is shown under in diagnostics: "<patch 3>"
};

// How a workspace compiles `m` when no hook is set: compile_file for a .hmat, compile_text otherwise.
// Never null; errors are in the result's diagnostics. For hooks that keep results (WorkspaceOptions).
std::shared_ptr<const CompileResult> compile_workspace_material(const Compiler& compiler, const WorkspaceMaterial& m);

// What a workspace compile may hold, and how it compiles its materials. The default is the stated
// limit; tests set a smaller one.
struct WorkspaceOptions {
  // Bytes of force tables (schema::grid_bytes) over the distinct materials' programs and their
  // placed copies; past it, E0535 at the first patch over (docs/RELIABILITY.md, F35).
  std::uint64_t max_grid_bytes = schema::limits::kMaxWorkspaceGridBytes;
  // Compiles each distinct material, once per workspace. Unset: the compiler's compile_file for a
  // .hmat, compile_text otherwise. A caller that compiles many workspaces over files it knows are
  // unchanged (the workspace fuzz target) may answer from materials it compiled before; what it
  // returns is taken as the compile's, so it must be what the compiler would give. Never null.
  std::function<std::shared_ptr<const CompileResult>(const Compiler&, const WorkspaceMaterial&)> compile_material;
};

// `path` is shown in diagnostics as given; .hmat paths in the file are relative to its folder.
// A missing file is diagnostic E0500, not an exception.
WorkspaceResult compile_workspace_file(const Compiler& compiler, const std::filesystem::path& path,
                                       const WorkspaceOptions& options = {});
// `display_name` names the text in diagnostics; .hmat paths are relative to `base_dir`.
WorkspaceResult compile_workspace_text(const Compiler& compiler, const std::string& text, const std::string& display_name,
                                       const std::filesystem::path& base_dir, const WorkspaceOptions& options = {});

}  // namespace sandpaper::compiler

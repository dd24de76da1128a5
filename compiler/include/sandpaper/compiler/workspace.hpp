#pragma once
// Workspace files (.hws) -> WorkspaceProgram: every patch's material compiled for the compiler's
// device and placed on the workspace (thesis Appendix B). Any error, in the workspace or in a
// patch's material, means no program. Language: schema/LANGUAGE.md, "Workspaces".
//
//   auto r = sandpaper::compiler::compile_workspace_file(compiler, "examples/workspace/sampler.hws");
//   if (!r.ok()) std::cerr << format_diagnostics(r.diagnostics);
#include <filesystem>
#include <optional>
#include <string>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/schema/workspace_program.hpp"

namespace sandpaper::compiler {

struct WorkspaceResult {
  Diagnostics diagnostics;
  std::optional<schema::WorkspaceProgram> program;  // set only if there were no errors at all
  bool ok() const { return program.has_value() && !diagnostics.has_errors(); }
};

// Whether `path` names a workspace file (extension .hws).
bool is_workspace_path(const std::filesystem::path& path);

// `path` is shown in diagnostics as given; .hmat paths in the file are relative to its folder.
// A missing file is diagnostic E0500, not an exception.
WorkspaceResult compile_workspace_file(const Compiler& compiler, const std::filesystem::path& path);
// `display_name` names the text in diagnostics; .hmat paths are relative to `base_dir`.
WorkspaceResult compile_workspace_text(const Compiler& compiler, const std::string& text, const std::string& display_name,
                                       const std::filesystem::path& base_dir);

}  // namespace sandpaper::compiler

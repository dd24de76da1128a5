#pragma once
// Workspace files (.hws), phase 2: tokens -> the syntax of one workspace (patches placed on a
// rectangle, thesis Appendix B). Grammar and codes E05xx: schema/LANGUAGE.md, "Workspaces".
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/syntax.hpp"

namespace sandpaper::compiler {

// patch "material" at X, Y [size W [x H]]
struct PatchPlacementSyntax {
  std::string material;                // library name, one-line expression, or a .hmat path
  SourceLocation material_location;
  Quantity x, y;                       // patch centre, workspace coordinates (origin at the centre)
  SourceLocation at_location;          // spans `X, Y`
  std::optional<Quantity> width, height;  // absent: the material's own size; height absent: square
  SourceLocation location;             // the `patch` keyword
};

struct WorkspaceSyntax {
  std::shared_ptr<const SourceFile> file;
  std::string name;
  SourceLocation name_location;
  std::optional<Quantity> width, height;  // `size W [x H]`; absent: 9 in square (thesis Table 2)
  SourceLocation size_location;
  std::vector<PatchPlacementSyntax> patches;  // in file order = painting order (later in front)
};

// Tokens must come from lex(..., LexOptions{.commas = true}). Reports E0501-E0506 and the unit
// errors E0203-E0205 into `diags`, recovers at the next line, and returns what it could read.
WorkspaceSyntax parse_workspace(const std::vector<Token>& tokens, std::shared_ptr<const SourceFile> file,
                                Diagnostics& diags);

}  // namespace sandpaper::compiler

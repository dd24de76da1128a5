#pragma once
// JSON view of a workspace (`sandpaper compile|explain ws.hws --json`): the workspace's name and
// size, then one object per patch in painting order (back first) with its placement and its patch
// program as patch_json.hpp gives it. Keys carry their units; see docs/PATCH_FORMAT.md, "Workspaces".
#include <nlohmann/json.hpp>

#include "sandpaper/schema/workspace_program.hpp"

namespace sandpaper::schema {

inline constexpr int kWorkspaceJsonVersion = 1;

// `with_tables` adds every patch's force tables (large).
nlohmann::json to_json(const WorkspaceProgram& workspace, bool with_tables = false);

}  // namespace sandpaper::schema

#include "sandpaper/schema/workspace_json.hpp"

#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::schema {

nlohmann::json to_json(const WorkspaceProgram& ws, bool with_tables) {
  using nlohmann::json;
  json j;
  j["format"] = "sandpaper-workspace";
  j["format_version"] = kWorkspaceJsonVersion;
  j["workspace"] = ws.name;
  j["size_m"] = {ws.size_m[0], ws.size_m[1]};
  j["patch_count"] = ws.patches.size();
  j["patches"] = json::array();
  for (std::size_t i = 0; i < ws.patches.size(); ++i) {
    const auto& p = ws.patches[i];
    j["patches"].push_back({{"index", i},
                            {"source", p.source},
                            {"centre_m", {p.centre_m[0], p.centre_m[1]}},
                            {"size_m", {p.size_m[0], p.size_m[1]}},
                            {"program", to_json(*p.program, with_tables)}});
  }
  return j;
}

}  // namespace sandpaper::schema

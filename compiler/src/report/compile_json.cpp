#include "sandpaper/compiler/compile_json.hpp"

#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::compiler {

nlohmann::json diagnostics_json(const Diagnostics& ds) {
  auto arr = nlohmann::json::array();
  for (const auto& d : ds.all()) {
    nlohmann::json j{{"code", d.code},
                     {"severity", d.severity == Severity::Error ? "error" : d.severity == Severity::Warning ? "warning" : "accepted"},
                     {"location", d.location.str()},
                     {"line", d.location.line},
                     {"column", d.location.column},
                     {"message", d.message},
                     {"suggestion", d.suggestion}};
    for (const auto& n : d.notes) j["notes"].push_back({{"location", n.location.str()}, {"message", n.message}});
    arr.push_back(std::move(j));
  }
  return arr;
}

nlohmann::json compile_json(const CompileResult& result, const std::optional<std::string>& output) {
  if (!result.ok()) return nlohmann::json{{"ok", false}, {"diagnostics", diagnostics_json(result.diagnostics)}};
  return compile_json(*result.program, result.diagnostics, output);
}

nlohmann::json compile_json(const schema::PatchProgram& program, const Diagnostics& diagnostics,
                            const std::optional<std::string>& output) {
  auto j = schema::to_json(program);
  j["ok"] = true;
  j["diagnostics"] = diagnostics_json(diagnostics);
  j["output"] = output ? nlohmann::json(*output) : nlohmann::json(nullptr);
  return j;
}

}  // namespace sandpaper::compiler

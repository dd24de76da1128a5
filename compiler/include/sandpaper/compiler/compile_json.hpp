#pragma once
// The JSON of a compile, one object for every caller that prints it (`sandpaper compile --json`,
// the studio's POST /api/compile): {"ok", "diagnostics": [{code, severity, location, line, column,
// message, suggestion, notes?}], and, when ok, the program (schema/patch_json.hpp) and "output"}.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/compiler.hpp"

namespace sandpaper::compiler {

nlohmann::json diagnostics_json(const Diagnostics& diagnostics);
// `output`: the patch file written, or nullopt for none (JSON null).
nlohmann::json compile_json(const CompileResult& result, const std::optional<std::string>& output);
// The same for a compile that succeeded, its program already taken out of the result.
nlohmann::json compile_json(const schema::PatchProgram& program, const Diagnostics& diagnostics,
                            const std::optional<std::string>& output);

}  // namespace sandpaper::compiler

#pragma once
// The language features, each a pure function of a compiled document and an LSP position
// ({"line", "character"}: 0-based, UTF-16). Results are LSP JSON, or null for "nothing here".
#include <nlohmann/json.hpp>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/lsp/server.hpp"

namespace sandpaper::lsp {

// CompletionItem[]: statement keywords at a statement's start, library names after `like`,
// roughness levels after `roughness`, units after a number.
nlohmann::json completion(const Document& d, const nlohmann::json& position, const compiler::Compiler& c);
// Hover: for a number (or its unit), `explain`'s parameter lines whose source is that number
// (parameter, value in its unit, layer, source); for a `like` name, the library entry.
nlohmann::json hover(const Document& d, const nlohmann::json& position, const compiler::Compiler& c);
// Location of the library entry named by the `like` statement under the cursor.
nlohmann::json definition(const Document& d, const nlohmann::json& position, const compiler::Compiler& c);

}  // namespace sandpaper::lsp

#pragma once
// Each compiler phase's output as plain text, one line per item, so a change to one phase shows in
// that phase's golden files (tests/golden/stages/) and `sandpaper compile --dump STAGE` shows what a
// phase made of a file. Numbers are written in the shortest form that reads back to the same double;
// locations as line:col (the file is the one dumped).
#include <string>
#include <vector>

#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/compiler/syntax.hpp"

namespace sandpaper::compiler {

// Phase 1, text -> tokens: "2:3 Word like".
std::string dump_tokens(const std::vector<Token>& tokens);
// Phase 2, tokens -> syntax: one line per statement with its fields, SI values in brackets, then its
// `source` notes indented.
std::string dump_syntax(const MaterialSyntax& syntax);
// Phase 3, syntax -> resolved material: every resolved parameter in SI with its layer, what was
// stated and where it came from.
std::string dump_resolved(const ResolvedMaterial& material);

}  // namespace sandpaper::compiler

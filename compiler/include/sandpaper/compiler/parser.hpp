#pragma once
// Phase 2: tokens -> syntax. Reports every error it finds (it resynchronises at the end of each
// statement) and never hands on a statement it could not parse.
#include <vector>

#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/syntax.hpp"

namespace sandpaper::compiler {

MaterialSyntax parse(const std::vector<Token>& tokens, const std::shared_ptr<const SourceFile>& file,
                     Diagnostics& diags);

// The statement keywords, for suggestions and documentation.
const std::vector<std::string>& statement_keywords();

}  // namespace sandpaper::compiler

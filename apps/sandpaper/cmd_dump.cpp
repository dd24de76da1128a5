// `sandpaper compile FILE --dump STAGE`: what one phase of the compiler made of a material (the
// tokens, the syntax, the resolved material, or the patch program as JSON), as the golden files in
// tests/golden/stages/ hold it. Nothing is written to disk.
#include <iostream>

#include "cli.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/compiler/stage_dumps.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/schema/json_text.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::cli {

int cmd_dump(const CommonOptions& o, const std::string& stage) {
  std::string text = o.expression;
  if (text.empty()) {
    try {
      text = schema::read_input_file(o.file, schema::limits::kMaxSourceBytes);
    } catch (const schema::InputFileError& e) {
      std::cerr << "sandpaper: error: cannot read '" << o.file << "': " << e.reason << "\n";
      return kExitBadInput;
    }
  }
  if (stage == "tokens" || stage == "syntax") {
    // An -e expression separates statements with ';', as the compiler reads it.
    auto file = std::make_shared<const compiler::SourceFile>(o.expression.empty() ? o.file : "<-e>", text);
    compiler::Diagnostics diags;
    const auto tokens = compiler::lex(file, diags);
    std::cout << (stage == "tokens" ? compiler::dump_tokens(tokens) : compiler::dump_syntax(compiler::parse(tokens, file, diags)));
    std::cerr << compiler::format_diagnostics(diags);
    return diags.has_errors() ? kExitBadInput : kExitOk;
  }
  auto c = make_compiler(o);
  auto in = load_input(o, c, /*allow_patch=*/false);
  if (!in) return kExitBadInput;
  if (stage == "resolved") std::cout << compiler::dump_resolved(*in->compile->material);
  else std::cout << schema::json_text(schema::to_json(in->program), 2) << "\n";
  return kExitOk;
}

}  // namespace sandpaper::cli

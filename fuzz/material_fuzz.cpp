// Material text (.hmat, `-e`) through the whole compiler: lex, parse, resolve through the shipped
// library and calibration, codegen; then the diagnostics as printed, the compile's JSON, and for a
// program: read back, JSON, played on the simulated joystick (fuzz_compile.hpp); each phase's dump
// (compile --dump) of the tokens, the syntax and the resolved material.
// Bad input is a diagnostic: the compiler API throws nothing for it, so nothing is caught here.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "fuzz_compile.hpp"
#include "fuzz_support.hpp"
#include "sandpaper/compiler/compile_json.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/compiler/stage_dumps.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto result = fuzz::shipped_compiler().compile_text(text, "<fuzz>");
  (void)compiler::format_diagnostics(result.diagnostics);
  auto file = std::make_shared<const compiler::SourceFile>("<fuzz>", text);
  compiler::Diagnostics front;
  const auto tokens = compiler::lex(file, front);
  (void)compiler::dump_tokens(tokens);
  (void)compiler::dump_syntax(compiler::parse(tokens, file, front));
  if (result.material) (void)compiler::dump_resolved(*result.material);
  fuzz::dump_json(compiler::compile_json(result, std::nullopt));
  // compiler.hpp: a program only if there were no errors at all.
  fuzz::check(!result.program || !result.diagnostics.has_errors(), "a compile with errors produced a program");
  if (result.ok()) fuzz::check_compiled_program(*result.program, static_cast<std::uint32_t>(std::hash<std::string>{}(text)));
  return 0;
}

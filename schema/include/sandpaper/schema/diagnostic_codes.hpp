#pragma once
// The one table of diagnostic codes: every code the compiler, the workspace and movie readers and
// `library check` raise, with its severity, a one-line summary and where it is documented. The
// compiler refuses to raise a code that is not here (InternalError), the language server links each
// diagnostic to its `doc` anchor, and schema/LANGUAGE.md's "Diagnostics" table is generated from it
// (`sandpaper diagnostics --markdown`; the test `DiagnosticCodes.*` fails when they differ).
#include <span>
#include <string>
#include <string_view>

namespace sandpaper::schema {

enum class DiagnosticSeverity { Error, Warning };

struct DiagnosticCode {
  std::string_view code;     // "E0201": E = error, W = warning; the hundreds give the phase (01 lexer, 02 parser, ...)
  DiagnosticSeverity severity;
  std::string_view summary;  // one line, markdown
  std::string_view doc;      // the file below the source root that documents it: "schema/LANGUAGE.md"
};

// "schema/LANGUAGE.md#e0201": the code's doc file and the anchor of its row there.
std::string diagnostic_doc_link(const DiagnosticCode& d);

// Every registered code, sorted by code. Codes are stable: a retired code is never reused.
std::span<const DiagnosticCode> diagnostic_codes();
// The code's entry, or nullptr for an unregistered code.
const DiagnosticCode* find_diagnostic_code(std::string_view code);
// The markdown table kept in schema/LANGUAGE.md between its "diagnostic-codes" markers: a header and
// one row per code, each row carrying the HTML anchor its `doc` points at.
std::string diagnostic_codes_markdown();

}  // namespace sandpaper::schema

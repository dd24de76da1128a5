#pragma once
// The one table of diagnostic codes (diagnostic_code_table.hpp): every code the compiler, the
// workspace and movie readers and `library check` raise, with its severity, a one-line summary and
// where it is documented. A raise site that names a code not there does not compile (Code), the
// language server links each diagnostic to its `doc` anchor, and schema/LANGUAGE.md's "Diagnostics"
// table is generated from it (`sandpaper diagnostics --markdown`; the test `DiagnosticCodes.*` fails
// when they differ).
#include <span>
#include <string>
#include <string_view>

#include "sandpaper/schema/diagnostic_code_table.hpp"

namespace sandpaper::schema {

// A registered diagnostic code. From a string literal ("E0302") it is checked against the table
// when the raise site compiles: a code not in diagnostic_code_table.hpp does not compile. A code
// known only at run time (a diagnostic copied from another) goes through Code::of, which throws
// std::logic_error for an unregistered one (a bug, not the user's input).
class Code {
 public:
  consteval Code(const char* text) : entry_(lookup(text)) {
    // Not a constant expression, so an unknown code stops the compile here.
    if (!entry_) throw "not a diagnostic code of schema/include/sandpaper/schema/diagnostic_code_table.hpp";
  }
  static Code of(std::string_view text);
  std::string_view text() const { return entry_->code; }
  DiagnosticSeverity severity() const { return entry_->severity; }

 private:
  explicit constexpr Code(const DiagnosticCode* entry) : entry_(entry) {}
  static constexpr const DiagnosticCode* lookup(std::string_view text) {
    for (const auto& d : kDiagnosticCodes)
      if (d.code == text) return &d;
    return nullptr;
  }
  const DiagnosticCode* entry_;
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

#pragma once
// One row of the diagnostic-code table (diagnostic_code_table.hpp).
#include <string_view>

namespace sandpaper::schema {

enum class DiagnosticSeverity { Error, Warning };

struct DiagnosticCode {
  std::string_view code;     // "E0201": E = error, W = warning; the hundreds give the phase (01 lexer, 02 parser, ...)
  DiagnosticSeverity severity;
  std::string_view summary;  // one line, markdown
  std::string_view doc;      // the file below the source root that documents it: "schema/LANGUAGE.md"
};

}  // namespace sandpaper::schema

#include "sandpaper/schema/diagnostic_codes.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace sandpaper::schema {

namespace {


std::string anchor_of(std::string_view code) {
  std::string a(code);
  for (char& c : a) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return a;
}

}  // namespace

std::span<const DiagnosticCode> diagnostic_codes() { return kDiagnosticCodes; }

const DiagnosticCode* find_diagnostic_code(std::string_view code) {
  auto it = std::lower_bound(kDiagnosticCodes.begin(), kDiagnosticCodes.end(), code,
                             [](const DiagnosticCode& d, std::string_view c) { return d.code < c; });
  return it != kDiagnosticCodes.end() && it->code == code ? &*it : nullptr;
}

Code Code::of(std::string_view text) {
  const DiagnosticCode* entry = find_diagnostic_code(text);
  if (!entry)
    throw std::logic_error("diagnostic code " + std::string(text) + " is not in schema/include/sandpaper/schema/diagnostic_code_table.hpp");
  return Code(entry);
}

std::string diagnostic_doc_link(const DiagnosticCode& d) { return std::string(d.doc) + "#" + anchor_of(d.code); }

std::string diagnostic_codes_markdown() {
  std::string out = "| code | severity | meaning |\n|---|---|---|\n";
  for (const auto& d : kDiagnosticCodes) {
    out += "| <a id=\"" + anchor_of(d.code) + "\"></a>" + std::string(d.code) + " | " +
           (d.severity == DiagnosticSeverity::Error ? "error" : "warning") + " | " + std::string(d.summary) + " |\n";
  }
  return out;
}

}  // namespace sandpaper::schema

#include <iostream>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "sandpaper/schema/diagnostic_codes.hpp"
#include "sandpaper/schema/json_text.hpp"

namespace sandpaper::cli {

int cmd_diagnostics(bool markdown, bool json) {
  using schema::DiagnosticSeverity;
  if (markdown) {
    std::cout << schema::diagnostic_codes_markdown();
    return kExitOk;
  }
  if (json) {
    auto list = nlohmann::json::array();
    for (const auto& d : schema::diagnostic_codes())
      list.push_back({{"code", d.code},
                      {"severity", d.severity == DiagnosticSeverity::Error ? "error" : "warning"},
                      {"summary", d.summary},
                      {"doc", schema::diagnostic_doc_link(d)}});
    std::cout << schema::json_text(nlohmann::json{{"diagnostics", list}}, 2) << "\n";
    return kExitOk;
  }
  for (const auto& d : schema::diagnostic_codes())
    std::cout << d.code << "  " << (d.severity == DiagnosticSeverity::Error ? "error  " : "warning") << "  " << d.summary << "\n";
  return kExitOk;
}

}  // namespace sandpaper::cli

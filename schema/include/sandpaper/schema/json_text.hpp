#pragma once
// JSON as Sandpaper writes it for people and programs: `--json` output, the studio's and the
// subject page's replies, JSON files.
#include <string>

#include <nlohmann/json.hpp>

namespace sandpaper::schema {

// `j` as text; `indent` as nlohmann's dump (-1: one line). A string that is not UTF-8 (a file name
// in another encoding: Linux names are bytes) is written with U+FFFD for each bad byte, rather than
// thrown as nlohmann's type_error 316 (docs/RELIABILITY.md, F26).
inline std::string json_text(const nlohmann::json& j, int indent = -1) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace sandpaper::schema

#pragma once
// Text into HTML: every string the catalog writes into a page goes through one of these.
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace sandpaper::catalog {

// Escapes & < > " ' for element text and quoted attribute values.
std::string html_escape(std::string_view text);
// Percent-encodes everything but unreserved characters (RFC 3986), for a path segment in an href.
std::string url_segment(std::string_view text);
// JSON for a <script type="application/json"> element: < > & and U+2028/9 written as \uXXXX, so no
// text in the data can close the element or start a comment.
std::string json_for_script(const nlohmann::json& data);
// A data file's statement: `start`, then `json_text` (nlohmann's ASCII dump) as a JavaScript string
// literal for JSON.parse, then `end`. V8 parses JSON faster than an object literal (a third less time
// to the first rows at 100,000 entries); < and > are written \u003c and \u003e, so the text could sit
// inside a <script> element unchanged, and it reads the same whatever encoding the browser assumes.
std::string json_statement(std::string_view start, const std::string& json_text, std::string_view end);
// A number with `digits` significant digits, as people read it ("0.45", "3.2", "1.93").
std::string format_number(double value, int digits = 3);

}  // namespace sandpaper::catalog

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
// A number with `digits` significant digits, as people read it ("0.45", "3.2", "1.93").
std::string format_number(double value, int digits = 3);

}  // namespace sandpaper::catalog

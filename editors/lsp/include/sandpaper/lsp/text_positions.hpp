#pragma once
// Between the compiler's positions (1-based lines, 1-based byte columns, compiler/source.hpp) and
// LSP's (0-based lines, 0-based UTF-16 code units: LSP 3.17 "Position"), and between file paths and
// `file:` URIs (RFC 8089, percent-encoding as RFC 3986).
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/source.hpp"

namespace sandpaper::lsp {

// UTF-16 code units in the first `byte_column` bytes of `line` (malformed UTF-8: one unit a byte).
int utf16_units(std::string_view line, std::size_t byte_column);
// The byte offset in `line` of UTF-16 unit `units` (clamped to the line's length).
std::size_t byte_offset(std::string_view line, int units);

// {"line": L-1, "character": utf16(col-1)} for a compiler location's start and end; a location
// outside `file` (another file, or none) is the document's first character.
nlohmann::json range_of(const compiler::SourceLocation& loc, const compiler::SourceFile& file);

// "file:///home/a%20b/x.hmat" -> "/home/a b/x.hmat"; any other URI scheme -> empty.
std::string path_of_uri(std::string_view uri);
std::string uri_of_path(std::string_view absolute_path);

}  // namespace sandpaper::lsp

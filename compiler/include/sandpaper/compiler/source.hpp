#pragma once
// Source text and positions in it. Lines and columns are 1-based; columns count bytes.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace sandpaper::compiler {

// One material file or -e expression, kept alive for as long as diagnostics point into it.
struct SourceFile {
  std::string name;  // as shown in diagnostics: the path as given, "<-e>", or "library/corduroy.hmat"
  std::string text;
  std::vector<std::size_t> line_starts;  // byte offset of each line's first character

  SourceFile(std::string name_, std::string text_);
  // Text of 1-based line `line`, without its newline; empty if out of range.
  std::string_view line_text(int line) const;
};

struct SourceLocation {
  std::shared_ptr<const SourceFile> file;  // null for locations that are not in any file
  int line = 0;
  int column = 0;
  int length = 1;  // caret width in bytes

  // "file:line:col", or the file name alone if no line.
  std::string str() const;
};

}  // namespace sandpaper::compiler

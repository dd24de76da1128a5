#include "sandpaper/compiler/source.hpp"

namespace sandpaper::compiler {

SourceFile::SourceFile(std::string name_, std::string text_) : name(std::move(name_)), text(std::move(text_)) {
  line_starts.push_back(0);
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') line_starts.push_back(i + 1);
}

std::string_view SourceFile::line_text(int line) const {
  if (line < 1 || static_cast<std::size_t>(line) > line_starts.size()) return {};
  std::size_t b = line_starts[static_cast<std::size_t>(line - 1)];
  std::size_t e = text.find('\n', b);
  if (e == std::string::npos) e = text.size();
  std::string_view v(text.data() + b, e - b);
  if (!v.empty() && v.back() == '\r') v.remove_suffix(1);
  return v;
}

std::string SourceLocation::str() const {
  if (!file) return "<unknown>";
  if (line <= 0) return file->name;
  return file->name + ":" + std::to_string(line) + ":" + std::to_string(column);
}

}  // namespace sandpaper::compiler

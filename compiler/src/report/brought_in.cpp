#include "sandpaper/compiler/brought_in.hpp"

#include <variant>

#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/parser.hpp"

namespace sandpaper::compiler {

namespace {

bool in(const SourceLocation& loc, const SourceFile& file) {
  return loc.file && (loc.file.get() == &file || loc.file->name == file.name) && loc.line > 0;
}

SourceLocation material_origin(const std::shared_ptr<const SourceFile>& file) {
  Diagnostics ignored;  // the file's own diagnostics are the compile's
  const auto syntax = parse(lex(file, ignored), file, ignored);
  for (const auto& st : syntax.statements)
    if (const auto* like = std::get_if<LikeStmt>(&st.node); like && in(like->name_location, *file)) return like->name_location;
  for (const auto& st : syntax.statements)
    if (const auto* r = std::get_if<RoughnessStmt>(&st.node); r && in(r->value_location, *file)) return r->value_location;
  for (const auto& st : syntax.statements)
    if (in(st.location, *file)) return st.location;
  return SourceLocation{file, 1, 1, 1};
}

}  // namespace

std::optional<BroughtIn> brought_in(const Diagnostic& d, const std::shared_ptr<const SourceFile>& file,
                                    const Library& library) {
  if (!d.location.file || in(d.location, *file) || d.location.file->name == file->name) return std::nullopt;
  BroughtIn b;
  for (const auto& e : library.entries())
    if (library.source_name(e) == d.location.file->name) {
      b.entry = library.qualified_name(e);
      break;
    }
  for (const auto& n : d.notes)
    if (in(n.location, *file)) {
      b.at = n.location;
      return b;
    }
  b.at = material_origin(file);
  return b;
}

}  // namespace sandpaper::compiler

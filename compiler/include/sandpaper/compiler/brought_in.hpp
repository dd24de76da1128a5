#pragma once
// Where a diagnostic raised in another file came into the file being edited: a library entry's
// warning (W0350 at library/textiles/silk-satin.hmat:8:3) belongs, in the text that uses the entry,
// to the `like` that brought the entry in, or to the workspace patch that placed it. For an editor
// that marks the open file's lines (the studio's page).
#include <memory>
#include <optional>
#include <string>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/library.hpp"

namespace sandpaper::compiler {

struct BroughtIn {
  SourceLocation at;  // in the edited file
  std::string entry;  // the library entry (qualified name) whose file holds the diagnostic; empty if none does
};

// nullopt when `d` lies in `file` itself or in no file. Otherwise the first of `d`'s notes that lies
// in `file` (a workspace's patch that uses the material, as the workspace compiler notes it), else
// the `like` name of `file` parsed as a material, else its bare `roughness` value (felt on the
// library's reference texture), else its first statement, else line 1.
std::optional<BroughtIn> brought_in(const Diagnostic& d, const std::shared_ptr<const SourceFile>& file,
                                    const Library& library);

}  // namespace sandpaper::compiler

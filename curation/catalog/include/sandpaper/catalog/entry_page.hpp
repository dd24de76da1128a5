#pragma once
// One entry's page: its picture and force plot, its three layers (representative, perceptual,
// physical; thesis 1.5.2), the provenance of every compiled number with the entry's `source` notes,
// its licence, a banner when it is deprecated, how to feel it (the commands), and the entries
// nearest it (assets/similar.js, from the index's data, so that the page need not change when
// another entry does).
#include <string>
#include <vector>

#include "sandpaper/catalog/plot.hpp"
#include "sandpaper/catalog/render.hpp"
#include "sandpaper/compiler/library.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::catalog {

// Everything one page shows. Pointers are borrowed for the call.
struct EntryView {
  const compiler::Library* library = nullptr;
  const compiler::LibraryEntry* entry = nullptr;
  const compiler::ResolvedMaterial* material = nullptr;
  const schema::PatchProgram* program = nullptr;
  const Picture* picture = nullptr;      // may be empty()
  const ForceScan* scan = nullptr;
  std::string picture_file;              // "corduroy.png", beside the page; empty without a picture
  std::string shade_file;                // "corduroy.shade" (Sandpaper's array file), or empty
  std::string root;                      // in a layered library, the id of the entry's root; else ""
  std::string hides;                     // the entry of a root below it hides ("world:corduroy"), or ""
  double weber_fraction = 0;             // the force JND the similar entries are measured in (calibration's knowledge)
};

// The `source` notes of the library statement a provenance record points at ("... (path:line:col)"),
// found by file and line among the library's entries; empty if the record names no library statement.
std::vector<compiler::SourceNote> notes_for(const compiler::Library& library, const std::string& provenance_source);

// The page's HTML (a complete document; links are relative: ../index.html, ../assets/catalog.css).
std::string entry_page_html(const EntryView& view);

}  // namespace sandpaper::catalog

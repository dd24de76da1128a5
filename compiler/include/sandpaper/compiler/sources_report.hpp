#pragma once
// The `source` notes behind a material's inherited numbers: for each library entry in its `like`
// chain, the entry's statements with their sources (schema/LANGUAGE.md "Library entries"). Shown by
// `sandpaper explain` after the account of the compile, so a designer sees why each number is what it is.
#include <string>

#include "sandpaper/compiler/library.hpp"
#include "sandpaper/compiler/resolved.hpp"

namespace sandpaper::compiler {

// Empty when no entry in the chain has a sourced statement (thesis stimuli, plain files).
std::string sources_text(const ResolvedMaterial& m, const Library& library);

}  // namespace sandpaper::compiler

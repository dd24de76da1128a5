#pragma once
// What an entry's index rows depend on, as one hash per entry (internal to sandpaper_curation):
// the entry's file, the images its heightmaps name, every entry it is built on through `like`
// (recursively, so a change reaches every entry built on it), the library's reference entry for
// a bare perceptual description, and `global` (index schema, compiler version, device,
// calibration files, library.toml).
#include <map>
#include <string>

#include "sandpaper/compiler/library.hpp"

namespace sandpaper::curation {

// `file_hashes`: content hash by tagged path ("library/textiles/corduroy.hmat"). Returns the
// input hash by entry name, for every entry that owns its name (a second file with a taken name
// is left out, as the index leaves it out).
std::map<std::string, std::string> entry_input_hashes(const compiler::Library& lib,
                                                      const std::map<std::string, std::string>& file_hashes,
                                                      const std::string& global);

// `global` for entry_input_hashes from the files' hashes ("library/...", "calibration/..."): the
// index schema, library.toml, every calibration file, the compiler version, the device.
std::string global_inputs(const std::map<std::string, std::string>& file_hashes, const std::string& device);

}  // namespace sandpaper::curation

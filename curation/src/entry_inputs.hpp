#pragma once
// What an entry's index rows depend on, as one hash per entry (internal to sandpaper_curation):
// the entry's file, the images its heightmaps name, every entry it is built on through `like`
// (recursively, so a change reaches every entry built on it), the library's reference entry for
// a bare perceptual description, and `global` (index schema, compiler version, device,
// calibration files, library.toml).
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "sandpaper/compiler/library.hpp"

namespace sandpaper::curation {

// `file_hashes`: content hash by tagged path ("library/textiles/corduroy.hmat"). Returns the
// input hash by entry name, for every entry that owns its name (a second file with a taken name
// is left out, as the index leaves it out).
std::map<std::string, std::string> entry_input_hashes(const compiler::Library& lib,
                                                      const std::map<std::string, std::string>& file_hashes,
                                                      const std::string& global);

// One entry's input hash and what it was made of: the tagged paths of the files it read (its own,
// its images, thesis/version1.toml for a thesis stimulus) and the names it is built on as written
// (`like` targets, the reference entry). An incremental build follows these backwards: an entry
// is redone when a file it read changed or a name it is built on changed what it means.
struct EntryInputs {
  std::string hash;
  std::vector<std::string> files, entries;
};

// The same for every entry of `lib` that owns its name; `file_hash` gives a tagged path's content
// hash ("absent" for none).
std::map<std::string, EntryInputs> entry_inputs(const compiler::Library& lib,
                                                const std::function<std::string(const std::string&)>& file_hash,
                                                const std::string& global);

// `global` for entry_input_hashes from the files' hashes ("library/...", "calibration/..."): the
// index schema, library.toml, every calibration file, the compiler version, the device.
std::string global_inputs(const std::map<std::string, std::string>& file_hashes, const std::string& device);

}  // namespace sandpaper::curation

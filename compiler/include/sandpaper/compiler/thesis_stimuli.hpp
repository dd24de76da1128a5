#pragma once
// The thesis' stimuli by name, as representatives (`like barsB15W20_2`, `-e a10p25`): when no
// library file has the name, the resolver asks this generator, which recognises the names of
// Minsky 1995's texture sets and writes the material text for them:
//   version-1 set (3.5.1, Ch. 4): barsB<valley px>W<hill px>[_<kernel>[_<refilter>]][Fless|Fmore|Fmost],
//     gridB<v>W<h>[off<px>][_<kernel>[_<refilter>]][F...], perlin<feature px>[F...];
//   non-texturals (4.3): Noise<pu>, 2StripesWeak, 2StripesStrong, Nothing, Bump, Slick, Spring, Viscous;
//   version-2 set (3.5.2, Table 8): a<level>p<period in 0.1 mm>, command 40 ju per level.
// Forces the OCR loses are readings from library/thesis/version1.toml (docs/TEXTURES.md).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sandpaper::compiler {

struct ThesisStimulus {
  std::string name;
  std::string source_text;  // a material file's text, compiled like a library entry
  std::string origin;       // "thesis stimulus generator (Minsky 1995, ...)", for explain and provenance
};

struct ThesisLookup {
  std::optional<ThesisStimulus> stimulus;
  std::string error;  // set when the name has a thesis stimulus's form but cannot be made (says why)
};

// Neither set: not a thesis stimulus name. The version-1 and non-textural names need
// <library_dir>/thesis/version1.toml; a missing or malformed file is an `error`.
ThesisLookup find_thesis_stimulus(const std::string& name, const std::filesystem::path& library_dir);

// Ch. 4's 102 stimuli as reconstructed in library/thesis/version1.toml, in file order, each with
// where its name was read ("figure 13", "figure 12", "appendix A", "reconstructed").
struct ListedStimulus {
  std::string name;
  std::string read_from;
  std::string note;
};
// Throws std::runtime_error if the file is missing or malformed.
std::vector<ListedStimulus> thesis_version1_list(const std::filesystem::path& library_dir);

// Table 8's twelve version-2 stimuli (Ch. 6), a1p7 ... a19p100.
const std::vector<std::string>& thesis_table8_names();

}  // namespace sandpaper::compiler

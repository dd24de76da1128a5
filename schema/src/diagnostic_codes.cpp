#include "sandpaper/schema/diagnostic_codes.hpp"

#include <algorithm>
#include <array>

namespace sandpaper::schema {

namespace {

constexpr auto E = DiagnosticSeverity::Error;
constexpr auto W = DiagnosticSeverity::Warning;
constexpr std::string_view kLang = "schema/LANGUAGE.md";
constexpr std::string_view kGltf = "docs/GLTF.md";

// Kept sorted by code (checked by the test DiagnosticCodes.SortedAndUnique). The phases: 00 files
// and limits, 01 lexer, 02 parser, 03 resolver, 04 images, 05 workspaces, movies and shuffles,
// 06 `library check`.
constexpr std::array kCodes = {
    DiagnosticCode{"E0001", E, "the material file cannot be opened, is not a regular file (a device or FIFO), or is over 4 MiB", kLang},
    DiagnosticCode{"E0009", E, "too many errors (more than 50): the rest are counted, not shown (docs/RELIABILITY.md)", kLang},
    DiagnosticCode{"E0101", E, "unterminated string", kLang},
    DiagnosticCode{"E0102", E, "unexpected characters (a run of them is one error)", kLang},
    DiagnosticCode{"E0103", E, "malformed number, or a quantity outside 1e-12 to 1e12 in SI units", kLang},
    DiagnosticCode{"E0104", E, "a byte that is not UTF-8 (one error per line, at the byte); material and workspace files are UTF-8 text", kLang},
    DiagnosticCode{"E0105", E, "text over 4 MiB given to the compiler (`compile_text`, the studio)", kLang},
    DiagnosticCode{"E0201", E, "expected a statement, or `{` after the material's name (the message says what was found)", kLang},
    DiagnosticCode{"E0202", E, "unknown statement (with \"did you mean\")", kLang},
    DiagnosticCode{"E0203", E, "a number without its unit", kLang},
    DiagnosticCode{"E0204", E, "unknown unit (with \"did you mean\")", kLang},
    DiagnosticCode{"E0205", E, "a unit of the wrong dimension", kLang},
    DiagnosticCode{"E0206", E, "an option given twice in one statement", kLang},
    DiagnosticCode{"E0207", E, "material block not closed", kLang},
    DiagnosticCode{"E0208", E, "text after the material block", kLang},
    DiagnosticCode{"E0209", E, "unknown option of a statement", kLang},
    DiagnosticCode{"E0210", E, "more text after a complete statement", kLang},
    DiagnosticCode{"E0211", E, "unknown force law or physics model (with \"did you mean\")", kLang},
    DiagnosticCode{"E0212", E, "`source` with no statement before it", kLang},
    DiagnosticCode{"E0213", E, "`source` without a known kind (measurement, standard, publication, derived, by-ear)", kLang},
    DiagnosticCode{"E0214", E, "expected a quoted text: the material's name, a source, a licence, a description or an image path", kLang},
    DiagnosticCode{"E0215", E, "expected a number: a plain number, a number with its unit, or a perceptual number or level", kLang},
    DiagnosticCode{"E0216", E, "a statement's second word is missing (`grating period`, `heightmap ... size`, `energy budget`, `quantize N bit`, `deprecated replaced-by`)", kLang},
    DiagnosticCode{"E0217", E, "expected a name: a library entry, a family, an image channel, a force law, a pattern kind, or the axes x, y or xy", kLang},
    DiagnosticCode{"E0218", E, "a `}` with no open material block", kLang},
    DiagnosticCode{"E0219", E, "a pattern without an option its kind needs (bars need `hill`, stripes `count`, ...)", kLang},
    DiagnosticCode{"E0220", E, "`accept` without a registered warning code and a quoted reason (an error cannot be accepted)", kLang},
    DiagnosticCode{"E0301", E, "no such library entry or thesis stimulus (with \"did you mean\", or why the thesis name cannot be made)", kLang},
    DiagnosticCode{"E0302", E, "two statements in one file set the same quantity", kLang},
    DiagnosticCode{"E0303", E, "roughness above 1, or another perceptual word above the top of its map's domain, without `extrapolate`", kLang},
    DiagnosticCode{"E0304", E, "a value out of range (negative period, a grating period finer than two of the device's position steps or 1 um, hill outside 0-100 %, smoothing too sharp, too wide or past its budget of multiply-adds, a pattern length under one pixel, a flat pattern, `quantize` on an image, ...)", kLang},
    DiagnosticCode{"E0305", E, "a `like` cycle", kLang},
    DiagnosticCode{"E0306", E, "a library entry with errors", kLang},
    DiagnosticCode{"E0307", E, "unknown level of roughness or another perceptual word (with \"did you mean\")", kLang},
    DiagnosticCode{"E0308", E, "a texture with no force (neither roughness nor amplitude, nor an image's depth and press)", kLang},
    DiagnosticCode{"E0309", E, "a roughness or amplitude with no texture", kLang},
    DiagnosticCode{"E0310", E, "the device cannot reach the force; says the highest roughness it can (rounded down, so it compiles)", kLang},
    DiagnosticCode{"E0311", E, "a force law without a parameter it needs", kLang},
    DiagnosticCode{"E0312", E, "a physics model too stiff for its mass at the device's slowest servo rate", kLang},
    DiagnosticCode{"E0313", E, "a `like` chain deeper than 64 entries (the message names the chain)", kLang},
    DiagnosticCode{"E0314", E, "a library entry's `heightmap` image outside the library (absolute, or climbing out with `..`)", kLang},
    DiagnosticCode{"E0315", E, "a grating with no period, in a file that inherits no grating to take it from", kLang},
    DiagnosticCode{"E0316", E, "an empty material: no statement (a material meant to feel like nothing says `force Nothing`)", kLang},
    DiagnosticCode{"E0320", E, "a perceptual word whose percept has no compile map in the calibration", kLang},
    DiagnosticCode{"E0401", E, "image unreadable: missing, junk bytes, truncated, not a regular file, or over 512 MiB", kLang},
    DiagnosticCode{"E0402", E, "image empty, under 3 x 3 samples (5 x 5 without `repeat`) or over 4096 x 4096 (also after `sampling`), over 64 channels, over 256 MiB as stored or as read, or a `sampling` whose resize walks over 65,537 rows a sample, holds over 2^24 x-window weights or makes over 2e9 pixel visits", kLang},
    DiagnosticCode{"E0403", E, "image all one height (no slope) or non-finite", kLang},
    DiagnosticCode{"E0404", E, "the image has no channel of that name (lists its channels, \"did you mean\")", kLang},
    DiagnosticCode{"E0405", E, "a `.depth` array file whose size is not width x height + 4 bytes", kLang},
    DiagnosticCode{"E0406", E, "a `.shade` array file given as a height map (it is a picture: use the `.depth`)", kLang},
    DiagnosticCode{"E0407", E, "`depth` without `press`, or `press` without `depth`", kLang},
    DiagnosticCode{"E0500", E, "the workspace file cannot be opened", kLang},
    DiagnosticCode{"E0501", E, "workspace syntax: expected `workspace`, the `{` after its name, or a workspace statement (`size`, `patch`)", kLang},
    DiagnosticCode{"E0502", E, "unknown workspace statement (with \"did you mean\")", kLang},
    DiagnosticCode{"E0503", E, "workspace block not closed", kLang},
    DiagnosticCode{"E0504", E, "text after the workspace block", kLang},
    DiagnosticCode{"E0505", E, "the workspace size given twice", kLang},
    DiagnosticCode{"E0506", E, "a workspace or patch size that is not positive, or outside 1e-12 m to 1e12 m", kLang},
    DiagnosticCode{"E0507", E, "a patch that reaches outside the workspace", kLang},
    DiagnosticCode{"E0508", E, "a patch with an empty material", kLang},
    DiagnosticCode{"E0509", E, "more than 65,536 patches in one workspace", kLang},
    DiagnosticCode{"E0510", E, "movie: the file cannot be opened", kLang},
    DiagnosticCode{"E0511", E, "movie: more than 100 frames", kLang},
    DiagnosticCode{"E0512", E, "movie: a frame's workspace file is missing", kLang},
    DiagnosticCode{"E0513", E, "movie: no frames", kLang},
    DiagnosticCode{"E0520", E, "shuffle: the file cannot be opened", kLang},
    DiagnosticCode{"E0521", E, "shuffle: bad header (Movie:, Date:, Time:, blank line)", kLang},
    DiagnosticCode{"E0522", E, "shuffle: bad frame line", kLang},
    DiagnosticCode{"E0523", E, "shuffle: original indices not 1..N each once", kLang},
    DiagnosticCode{"E0524", E, "shuffle: does not fit its movie", kLang},
    DiagnosticCode{"E0531", E, "workspace: expected a quoted text, the workspace's name or a patch's material", kLang},
    DiagnosticCode{"E0532", E, "workspace: a `patch` without `at X, Y`, or without the comma between X and Y", kLang},
    DiagnosticCode{"E0533", E, "workspace: expected a length (a number and a length unit) for a size or a position", kLang},
    DiagnosticCode{"E0534", E, "workspace: more text after a complete statement", kLang},
    DiagnosticCode{"E0535", E, "workspace: its materials' force tables over 512 MiB in all", kLang},
    DiagnosticCode{"E0601", E, "`library check`: `library.toml` is missing, is not TOML, or lacks a key (docs/LIBRARY.md)", kLang},
    DiagnosticCode{"E0602", E, "`library check`: no `material` block, or its name is not its file stem", kLang},
    DiagnosticCode{"E0603", E, "`library check`: no `describes`", kLang},
    DiagnosticCode{"E0604", E, "`library check`: no `family`, or one `library.toml` does not declare", kLang},
    DiagnosticCode{"E0605", E, "`library check`: no `licence`, or one that is not an SPDX id or expression", kLang},
    DiagnosticCode{"E0606", E, "`library check`: a statement that carries numbers has no `source` after it", kLang},
    DiagnosticCode{"E0607", E, "`library check`: a name or alias already used", kLang},
    DiagnosticCode{"E0608", E, "`library check`: a `like` cycle (the message gives the whole path)", kLang},
    DiagnosticCode{"E0609", E, "`library check`: `deprecated replaced-by` names no entry, the entry itself, or a deprecated entry", kLang},
    DiagnosticCode{"E0610", E, "`library check`: the entry does not compile for a device of the calibration", kLang},
    DiagnosticCode{"E0611", E, "`library check`: `library.toml`'s `reference` is not an entry", kLang},
    DiagnosticCode{"E0612", E, "`library check`: a `heightmap` image outside the library", kLang},
    DiagnosticCode{"E0613", E, "`library check`: two roots of a layered library path have one `id`", kLang},
    DiagnosticCode{"E0614", E, "a library entry file whose path is not UTF-8: no `like` can name it, and it is not read", kLang},
    DiagnosticCode{"E0615", E, "`library check`: an image without its licence and credit (a REUSE sidecar `<image>.license` with `SPDX-License-Identifier` and `SPDX-FileCopyrightText`)", kLang},
    // glTF import and export (docs/GLTF.md).
    DiagnosticCode{"E0701", E, "`export --format gltf`: a material with no texture (grating or height map) for glTF's haptic textures to carry", kGltf},
    DiagnosticCode{"E0702", E, "`export --format gltf`: a texture that cannot be exported (a generated pattern, a height field without its material, a flat texture)", kGltf},
    DiagnosticCode{"E0710", E, "glTF file cannot be read: missing, not a regular file, or over 128 MiB", kGltf},
    DiagnosticCode{"E0711", E, "glTF file is not JSON, is a binary .glb, or has over 2^20 JSON values or nesting deeper than 64", kGltf},
    DiagnosticCode{"E0712", E, "not a glTF 2.0 asset Sandpaper reads: no `asset.version` \"2.0\", a bad scene, node or mesh index, a node rotated, scaled or off the ground plane", kGltf},
    DiagnosticCode{"E0713", E, "no usable MPEG_haptic_material: the extension, its materials, a mesh's `hapticMaterialIndex`, or several patches without a workspace", kGltf},
    DiagnosticCode{"E0714", E, "a haptic material's `extras.sandpaper` is missing, of another version, or has a key of the wrong type or out of range", kGltf},
    DiagnosticCode{"E0715", E, "a haptic texture that cannot be found (texture or image index) or is not an embedded `data:image/png;base64` URI", kGltf},
    DiagnosticCode{"E0716", E, "a haptic texture that is not a PNG or does not decode", kGltf},
    DiagnosticCode{"E0717", E, "a haptic texture over the size limits (4096 x 4096 px, 65536 texels for a grating, 2 x 4096^2 in all) or of the wrong shape", kGltf},
    DiagnosticCode{"E0718", E, "the asset's forces exceed what the device can play", kGltf},
    DiagnosticCode{"E0719", E, "more than 65536 haptic meshes in one asset", kGltf},
    DiagnosticCode{"W0009", W, "too many warnings (more than 200): the rest are counted, not shown", kLang},
    DiagnosticCode{"W0301", W, "roughness extrapolated below 18 gf, or another perceptual word below the bottom of its map's domain", kLang},
    DiagnosticCode{"W0302", W, "roughness extrapolated: period outside 0.7-10 mm", kLang},
    DiagnosticCode{"W0303", W, "roughness above 1, or another perceptual word above the top of its map's domain (with `extrapolate`)", kLang},
    DiagnosticCode{"W0304", W, "roughness extrapolated: an image or pattern texture", kLang},
    DiagnosticCode{"W0305", W, "the material has no force terms", kLang},
    DiagnosticCode{"W0306", W, "a non-passive force law, or `slipperiness` (its energy is bounded by the runtime)", kLang},
    DiagnosticCode{"W0307", W, "a height-map picture stretched: `size W x H` whose two sample spacings differ by more than 1 %", kLang},
    DiagnosticCode{"W0311", W, "the device's force step is coarser than one force JND at the material's force; says the least roughness it resolves", kLang},
    DiagnosticCode{"W0320", W, "provisional: the material compiles through a map not yet measured on a joystick (names the map and its file)", kLang},
    DiagnosticCode{"W0330", W, "a grating or grid in Ch. 4's low-confidence region: maximum lateral force below 30 pu and period above 9.25 mm (calibration/knowledge/believability.toml)", kLang},
    DiagnosticCode{"W0331", W, "the device is uncalibrated (its command scale is assumed); says how to calibrate it", kLang},
    DiagnosticCode{"W0340", W, "`like` a deprecated library entry; names its replacement", kLang},
    DiagnosticCode{"W0350", W, "at a common hand speed (50 or 100 mm/s) a grating's felt peak force is more than one force JND below its compiled maximum; offers a faster servo or a `smoothing` (docs/TEXTURES.md)", kLang},
    DiagnosticCode{"W0501", W, "a workspace with no patches", kLang},
    DiagnosticCode{"W0502", W, "a patch wholly behind a later one (never felt)", kLang},
    DiagnosticCode{"W0503", W, "two textured materials of a workspace less than one force JND apart in maximum lateral force (the first 20 pairs, then a count)", kLang},
    DiagnosticCode{"W0520", W, "`movie show`: a shuffle whose movie is not there to check it against", kLang},
    DiagnosticCode{"W0601", W, "`library check`: JND collision, two entries of one family the thesis' knowledge cannot tell apart", kLang},
    DiagnosticCode{"W0603", W, "`library check`: a well-formed licence id not in the check's short list", kLang},
    DiagnosticCode{"W0612", W, "`library check`: an entry hides one of a library root below it and does not say `overrides`", kLang},
    DiagnosticCode{"W0613", W, "`library check`: an entry says `overrides` but hides nothing below it", kLang},
    DiagnosticCode{"W0614", W, "`library check`: an entry accepts a warning that no device's compile gives it (remove the `accept`)", kLang},
    DiagnosticCode{"W0701", W, "`export --format gltf`: parts of the material glTF cannot carry (force laws, state, energy budgets) were left out", kGltf},
    DiagnosticCode{"W0702", W, "`export --format gltf`: the 16-bit heights give the forces back less closely than 0.5 % of the maximum lateral force", kGltf},
    DiagnosticCode{"W0703", W, "glTF import: the asset says parts of its material were left out when it was exported", kGltf},
};

std::string anchor_of(std::string_view code) {
  std::string a(code);
  for (char& c : a) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return a;
}

}  // namespace

std::span<const DiagnosticCode> diagnostic_codes() { return kCodes; }

const DiagnosticCode* find_diagnostic_code(std::string_view code) {
  auto it = std::lower_bound(kCodes.begin(), kCodes.end(), code,
                             [](const DiagnosticCode& d, std::string_view c) { return d.code < c; });
  return it != kCodes.end() && it->code == code ? &*it : nullptr;
}

std::string diagnostic_doc_link(const DiagnosticCode& d) { return std::string(d.doc) + "#" + anchor_of(d.code); }

std::string diagnostic_codes_markdown() {
  std::string out = "| code | severity | meaning |\n|---|---|---|\n";
  for (const auto& d : kCodes) {
    out += "| <a id=\"" + anchor_of(d.code) + "\"></a>" + std::string(d.code) + " | " +
           (d.severity == DiagnosticSeverity::Error ? "error" : "warning") + " | " + std::string(d.summary) + " |\n";
  }
  return out;
}

}  // namespace sandpaper::schema

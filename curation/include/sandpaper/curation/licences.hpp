#pragma once
// Licences in the library: SPDX licence expressions (SPDX 2.3, Annex D) for entries and images,
// and the REUSE sidecar an image carries its own licence and credit in (REUSE Specification 3.0:
// `gravel.png.license` beside `gravel.png`).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sandpaper::curation {

// A parsed SPDX licence expression:
//   expression := and-expr ('OR' and-expr)*
//   and-expr   := term ('AND' term)*
//   term       := '(' expression ')' | simple ['WITH' exception-id]
//   simple     := idstring ['+'] | ['DocumentRef-' idstring ':'] 'LicenseRef-' idstring
// `ids` are the licence ids (and LicenseRef-s) it names, in order, without '+'; `error` is empty
// when it parses, else what is wrong and `error_at` the byte offset (0-based) where.
struct LicenceExpression {
  std::vector<std::string> ids, exceptions;
  std::string error;
  std::size_t error_at = 0;
  bool ok() const { return error.empty(); }
};
LicenceExpression parse_licence_expression(const std::string& text);

// Whether `id` is a licence the check knows (a short list of SPDX ids used for content, plus
// LicenseRef-*); well_formed_licence: whether `text` parses as an SPDX expression.
bool known_licence(const std::string& id);
bool well_formed_licence(const std::string& text);
const std::vector<std::string>& known_licences();
// For an id the check does not know: a known id it likely means ("CC0" -> "CC0-1.0", by prefix or
// edit distance), or "".
std::string licence_guess(const std::string& id);

// An image's REUSE sidecar: `SPDX-License-Identifier: EXPR` and `SPDX-FileCopyrightText: TEXT`
// lines (other lines are kept out; the last of each tag wins). Line numbers are 1-based, 0 when absent.
struct ImageLicence {
  std::filesystem::path sidecar;  // <image>.license
  std::string licence, credit;
  int licence_line = 0, credit_line = 0;
};
// Reads the sidecar of `image`; nullopt if there is none (or it cannot be read). At most 64 KiB are read.
std::optional<ImageLicence> read_image_licence(const std::filesystem::path& image);
// The same from a sidecar's text (what read_image_licence parses).
ImageLicence parse_image_licence(const std::string& text);

}  // namespace sandpaper::curation

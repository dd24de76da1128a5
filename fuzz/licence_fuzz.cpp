// A library's licences (curation/include/sandpaper/curation/licences.hpp): the SPDX
// expression of an entry's `licence` and an image's REUSE sidecar, both written by contributors.
// Any text gives a parse or an error at an offset inside it, never a crash; what parses names only
// ids made of SPDX's id characters; the sidecar's values are substrings of its lines.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "sandpaper/curation/licences.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto ex = curation::parse_licence_expression(text);
  fuzz::check(ex.ok() || ex.error_at <= text.size(), "the error's offset lies past the text");
  if (ex.ok())
    for (const auto& id : ex.ids) {
      fuzz::check(!id.empty() && id.find_first_of(" \t()\n") == std::string::npos, "an id with a separator in it: " + id);
      (void)curation::known_licence(id);
      (void)curation::licence_guess(id);
    }
  const auto side = curation::parse_image_licence(text);
  fuzz::check(side.licence.empty() || text.find(side.licence) != std::string::npos, "a licence value not in the text");
  fuzz::check(side.credit.empty() || text.find(side.credit) != std::string::npos, "a credit value not in the text");
  fuzz::check(side.licence.find('\n') == std::string::npos && side.credit.find('\n') == std::string::npos, "a value spans lines");
  return 0;
}

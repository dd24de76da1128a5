// The licences `library check` knows: SPDX ids (https://spdx.org/licenses/) that suit data and
// creative content, and the common software ones. An id outside the list is a warning (W0603), not
// an error: SPDX has hundreds; the list catches misspellings of the likely ones.
#include <regex>

#include "sandpaper/curation/check.hpp"

namespace sandpaper::curation {

const std::vector<std::string>& known_licences() {
  static const std::vector<std::string> ids{
      "CC0-1.0",      "CC-BY-4.0",     "CC-BY-SA-4.0", "CC-BY-NC-4.0", "CC-BY-NC-SA-4.0", "CC-BY-ND-4.0",
      "CC-BY-NC-ND-4.0", "CC-BY-3.0",  "CC-BY-SA-3.0", "CC-PDDC",      "PDDL-1.0",         "ODC-By-1.0",
      "ODbL-1.0",     "Unlicense",     "MIT",          "Apache-2.0",   "BSD-2-Clause",     "BSD-3-Clause",
      "GPL-2.0-or-later", "GPL-3.0-or-later", "LGPL-3.0-or-later", "MPL-2.0"};
  return ids;
}

bool known_licence(const std::string& id) {
  if (id.rfind("LicenseRef-", 0) == 0 && id.size() > 11) return true;
  for (const auto& k : known_licences())
    if (k == id) return true;
  return false;
}

bool well_formed_licence(const std::string& id) {
  // An id (letters, digits, '.', '-', '+') or an expression of ids joined by AND / OR / WITH.
  static const std::regex expr(R"(^[A-Za-z0-9.+-]+( (AND|OR|WITH) [A-Za-z0-9.+-]+)*$)");
  return std::regex_match(id, expr);
}

}  // namespace sandpaper::curation

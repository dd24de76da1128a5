#include "sandpaper/compiler/sources_report.hpp"

#include <sstream>

namespace sandpaper::compiler {

std::string sources_text(const ResolvedMaterial& m, const Library& library) {
  std::ostringstream o;
  for (const auto& name : m.like_chain) {
    const LibraryEntry* e = library.entry(name);
    if (!e) continue;  // a thesis stimulus: its numbers are the generator's, cited in explain's provenance
    std::ostringstream entry;
    for (const auto& st : e->syntax.statements) {
      if (st.sources.empty()) continue;
      entry << "    " << st.location.line << "  " << st.text << "\n";
      for (const auto& s : st.sources) entry << "         " << source_kind_phrase(s.kind) << ": " << s.text << "\n";
    }
    if (entry.str().empty()) continue;
    o << "  library " << e->name << " (library/" << e->relative_path << (e->licence.empty() ? "" : ", " + e->licence)
      << ")\n"
      << entry.str();
  }
  if (o.str().empty()) return {};
  return "\nsources (where the inherited numbers come from: each entry's `source` statements)\n" + o.str();
}

}  // namespace sandpaper::compiler

#include "sandpaper/compiler/stage_dumps.hpp"

#include <charconv>
#include <sstream>
#include <type_traits>

namespace sandpaper::compiler {
namespace {

// The shortest text that reads back to `v` (std::to_chars without a precision).
std::string num(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// The enumerator's own name: token_kind_name's phrases ("a word") are for diagnostics.
const char* kind_name(TokenKind k) {
  switch (k) {
    case TokenKind::Word: return "Word";
    case TokenKind::Number: return "Number";
    case TokenKind::String: return "String";
    case TokenKind::LBrace: return "LBrace";
    case TokenKind::RBrace: return "RBrace";
    case TokenKind::Comma: return "Comma";
    case TokenKind::End: return "End";
    case TokenKind::Eof: return "Eof";
  }
  return "?";
}

std::string at(const SourceLocation& l) { return std::to_string(l.line) + ":" + std::to_string(l.column); }

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string quantity(const Quantity& q) { return num(q.value) + (q.unit.empty() ? "" : " " + q.unit) + " [" + num(q.si) + "]"; }

// Appends " name=value" for fields that are present.
struct Fields {
  std::string text;
  void q(const char* name, const std::optional<Quantity>& v) {
    if (v) text += std::string(" ") + name + "=" + quantity(*v);
  }
  void q(const char* name, const Quantity& v) { text += std::string(" ") + name + "=" + quantity(v); }
  void n(const char* name, const std::optional<PlainNumber>& v) {
    if (v) text += std::string(" ") + name + "=" + num(v->value);
  }
  void s(const char* name, const std::string& v) {
    if (!v.empty()) text += std::string(" ") + name + "=" + quoted(v);
  }
  void d(const char* name, const std::optional<double>& v) {
    if (v) text += std::string(" ") + name + "=" + num(*v);
  }
  void b(const char* name, bool v) {
    if (v) text += std::string(" ") + name;
  }
};

std::string node_fields(const StatementNode& node) {
  Fields f;
  std::visit(
      [&](const auto& st) {
        using T = std::decay_t<decltype(st)>;
        if constexpr (std::is_same_v<T, DescribesStmt>) f.s("text", st.text);
        else if constexpr (std::is_same_v<T, LikeStmt>) f.s("name", st.name);
        else if constexpr (std::is_same_v<T, RoughnessStmt>) {
          f.d("value", st.value);
          f.s("level", st.level);
        } else if constexpr (std::is_same_v<T, PerceptStmt>) {
          f.s("word", st.word);
          f.d("value", st.value);
          f.s("level", st.level);
        } else if constexpr (std::is_same_v<T, GratingStmt>) {
          f.q("period", st.period);
          f.q("hill", st.hill);
          f.q("amplitude", st.amplitude);
          f.q("orientation", st.orientation);
          f.q("smoothing", st.smoothing);
        } else if constexpr (std::is_same_v<T, HeightmapStmt>) {
          f.s("path", st.path);
          f.q("width", st.width);
          f.q("height", st.height);
          f.q("smoothing", st.smoothing);
          f.q("amplitude", st.amplitude);
          f.q("sampling", st.sampling);
          f.q("depth", st.depth);
          f.q("press", st.press);
          f.s("channel", st.channel);
          f.b("repeat", st.repeat);
          f.b("invert", st.invert);
        } else if constexpr (std::is_same_v<T, PatternStmt>) {
          f.s("kind", st.kind);
          f.q("valley", st.valley);
          f.q("hill", st.hill);
          f.q("offset", st.offset);
          f.q("feature", st.feature);
          f.q("pixel", st.pixel);
          f.q("amplitude", st.amplitude);
          f.n("kernel", st.kernel);
          f.n("refilter", st.refilter);
          f.n("seed", st.seed);
          f.n("count", st.count);
        } else if constexpr (std::is_same_v<T, QuantizeStmt>) {
          f.text += " bits=" + num(st.bits.value);
        } else if constexpr (std::is_same_v<T, SpringStmt>) {
          f.q("stiffness", st.stiffness);
        } else if constexpr (std::is_same_v<T, DamperStmt>) {
          f.q("damping", st.damping);
        } else if constexpr (std::is_same_v<T, SizeStmt>) {
          f.q("width", st.width);
          f.q("height", st.height);
        } else if constexpr (std::is_same_v<T, LawStmt>) {
          f.b("physics", st.physics);
          f.s("name", st.name);
          for (const auto& a : st.args) {
            if (a.quantity) f.q(a.name.c_str(), a.quantity);
            else f.s(a.name.c_str(), a.word);
          }
        } else if constexpr (std::is_same_v<T, EnergyStmt>) {
          f.q("budget", st.budget);
          f.q("refill", st.refill);
        } else if constexpr (std::is_same_v<T, FamilyStmt>) f.s("family", st.family);
        else if constexpr (std::is_same_v<T, AliasStmt>) f.s("name", st.name);
        else if constexpr (std::is_same_v<T, LicenceStmt>) f.s("licence", st.licence);
        else if constexpr (std::is_same_v<T, DeprecatedStmt>) f.s("replaced-by", st.replacement);
        else if constexpr (std::is_same_v<T, AcceptStmt>) {
          f.s("code", st.code);
          f.s("reason", st.reason);
        } else {
          static_assert(std::is_same_v<T, ExtrapolateStmt> || std::is_same_v<T, OverridesStmt>,
                        "a statement kind without a dump: add its fields here");
        }
      },
      node);
  return f.text;
}

std::string param(const Param& p) {
  return num(p.si) + " " + quoted(p.stated) + " " + layer_name(p.layer) + (p.source.empty() ? "" : " from " + p.source);
}

void line(std::ostringstream& os, const std::string& name, const std::optional<Param>& p, const char* indent = "") {
  if (p) os << indent << name << " " << param(*p) << "\n";
}
void line(std::ostringstream& os, const std::string& name, const Param& p, const char* indent = "") {
  os << indent << name << " " << param(p) << "\n";
}

}  // namespace

std::string dump_tokens(const std::vector<Token>& tokens) {
  std::ostringstream os;
  for (const auto& t : tokens) {
    os << at(t.location) << " " << kind_name(t.kind);
    if (t.kind == TokenKind::String) os << " " << quoted(t.text);
    else if (t.kind == TokenKind::Number) os << " " << t.text << " [" << num(t.number) << "]";
    else if (t.kind == TokenKind::Word) os << " " << t.text;
    os << "\n";
  }
  return os.str();
}

std::string dump_syntax(const MaterialSyntax& syntax) {
  std::ostringstream os;
  if (!syntax.name.empty()) os << "material " << quoted(syntax.name) << " " << at(syntax.name_location) << "\n";
  for (const auto& st : syntax.statements) {
    os << at(st.location) << " " << st.keyword << node_fields(st.node) << "\n";
    for (const auto& s : st.sources)
      os << "  " << at(s.location) << " source " << source_kind_word(s.kind) << " " << quoted(s.text) << "\n";
  }
  return os.str();
}

std::string dump_resolved(const ResolvedMaterial& m) {
  std::ostringstream os;
  os << "name " << quoted(m.name) << "\n";
  if (!m.describes.empty()) os << "describes " << quoted(m.describes) << "\n";
  for (std::size_t i = 0; i < m.like_chain.size(); ++i)
    os << "like " << m.like_chain[i] << (i < m.like_origins.size() ? " from " + m.like_origins[i] : std::string()) << "\n";
  std::visit(
      [&](const auto& t) {
        using T = std::decay_t<decltype(t)>;
        if constexpr (std::is_same_v<T, ResolvedGrating>) {
          os << "texture grating " << at(t.location) << "\n";
          line(os, "period", t.period, "  ");
          line(os, "hill", t.hill, "  ");
          line(os, "orientation", t.orientation, "  ");
          line(os, "smoothing", t.smoothing, "  ");
        } else if constexpr (std::is_same_v<T, ResolvedHeightmap>) {
          os << "texture heightmap " << quoted(t.stated_path) << " " << at(t.location) << (t.repeat ? " repeat" : "")
             << (t.invert ? " invert" : "") << (t.channel.empty() ? "" : " channel " + t.channel) << "\n";
          line(os, "width", t.width, "  ");
          line(os, "height", t.height, "  ");
          line(os, "smoothing", t.smoothing, "  ");
          line(os, "sampling", t.sampling, "  ");
          line(os, "depth", t.depth, "  ");
          line(os, "press", t.press, "  ");
        } else if constexpr (std::is_same_v<T, ResolvedPattern>) {
          os << "texture pattern " << pattern_kind_name(t.kind) << " " << at(t.location) << "\n";
          line(os, "pixel", t.pixel, "  ");
          line(os, "valley", t.valley, "  ");
          line(os, "hill", t.hill, "  ");
          line(os, "offset", t.offset, "  ");
          line(os, "feature", t.feature, "  ");
          line(os, "kernel", t.kernel, "  ");
          line(os, "refilter", t.refilter, "  ");
          line(os, "seed", t.seed, "  ");
          line(os, "count", t.count, "  ");
        }
      },
      m.texture);
  line(os, "quantize_bits", m.quantize_bits);
  line(os, "max_lateral_force", m.max_lateral_force);
  line(os, "roughness", m.roughness);
  line(os, "spring", m.spring);
  line(os, "damper", m.damper);
  line(os, "friction coefficient", m.friction_coefficient);
  for (const auto& p : m.percepts) {
    os << "percept " << p.word << " (" << p.percept << ") sets " << p.parameter << " through " << p.map_id
       << (p.provisional ? " (provisional)" : "") << "\n";
    line(os, "value", p.value, "  ");
  }
  for (const auto& law : m.laws) {
    os << (law.physics ? "physics " : "force ") << law.name << " " << at(law.location) << " axes " << law.axes << "\n";
    for (const auto& [name, p] : law.params) line(os, name, p, "  ");
  }
  line(os, "energy_budget", m.energy_budget);
  line(os, "energy_refill", m.energy_refill);
  line(os, "size_width", m.size_width);
  line(os, "size_height", m.size_height);
  if (m.extrapolate) os << "extrapolate\n";
  if (!m.family.empty()) os << "family " << m.family << "\n";
  for (const auto& a : m.aliases) os << "alias " << a << "\n";
  if (!m.licence.empty()) os << "licence " << quoted(m.licence) << "\n";
  if (!m.deprecated_by.empty()) os << "deprecated replaced-by " << m.deprecated_by << "\n";
  return os.str();
}

}  // namespace sandpaper::compiler

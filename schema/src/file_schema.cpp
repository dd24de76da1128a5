#include "sandpaper/schema/file_schema.hpp"

#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "sandpaper/schema/units.hpp"

// Generated at build time from schema/files/*.schema.json (schema/CMakeLists.txt), so the binary
// carries the schemas it validates with and cannot drift from the files editors use.
namespace sandpaper::schema::generated {
extern const std::map<std::string, std::string_view>& file_schemas();
}

namespace sandpaper::schema {
namespace {

using nlohmann::json;

const json& parsed(std::string_view name) {
  static const std::map<std::string, json> all = [] {
    std::map<std::string, json> m;
    for (const auto& [n, text] : generated::file_schemas()) m.emplace(n, json::parse(text));
    return m;
  }();
  auto it = all.find(std::string(name));
  if (it == all.end()) throw std::out_of_range("no file schema named '" + std::string(name) + "'");
  return it->second;
}

std::string type_of(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "object";
    case toml::node_type::array: return "array";
    case toml::node_type::string: return "string";
    case toml::node_type::integer: return "integer";
    case toml::node_type::floating_point: return "number";
    case toml::node_type::boolean: return "boolean";
    default: return "date/time";
  }
}

bool type_matches(const toml::node& n, const std::string& want) {
  std::string t = type_of(n);
  return t == want || (want == "number" && t == "integer");
}

std::string describe(const toml::node& n) {
  if (auto s = n.value<std::string>(); s && n.is_string()) return "\"" + *s + "\"";
  if (auto d = n.value<double>()) {
    std::ostringstream os;
    os << *d;
    return os.str();
  }
  return type_of(n);
}

std::optional<Dimension> dimension_named(const std::string& name) {
  for (Dimension d : {Dimension::Length, Dimension::Force, Dimension::Stiffness, Dimension::Damping, Dimension::Angle,
                      Dimension::Fraction, Dimension::Mass, Dimension::Time, Dimension::Energy, Dimension::Power,
                      Dimension::Speed})
    if (dimension_name(d) == name) return d;
  return std::nullopt;
}

class Validator {
 public:
  Validator(const json& root, std::vector<SchemaViolation>& out) : root_(root), out_(out) {}

  void check(const toml::node& n, const json& schema, const std::string& key, const toml::node* parent) {
    const json& s = resolve(schema);
    if (const json* any_of = get(s, "anyOf")) {
      bool any = false;
      std::vector<SchemaViolation> first;
      for (const auto& branch : *any_of) {
        std::vector<SchemaViolation> v;
        Validator(root_, v).check(n, branch, key, parent);
        if (v.empty()) any = true;
        else if (first.empty()) first = std::move(v);
      }
      if (!any) {
        std::string alt = s.value("x-anyOf-message", std::string());
        if (!alt.empty()) report(n, key, alt);
        else out_.insert(out_.end(), first.begin(), first.end());
      }
    }
    if (const json* type = get(s, "type")) {
      const std::string& want = type->get_ref<const std::string&>();
      if (!type_matches(n, want)) {
        report(n, key, "expected " + article(want) + ", found " + describe(n));
        return;
      }
    }
    if (const json* c = get(s, "const"); c && !equals(n, *c))
      report(n, key, "must be " + c->dump() + ", found " + describe(n));
    if (const json* options = get(s, "enum")) {
      bool ok = false;
      for (const auto& e : *options) ok = ok || equals(n, e);
      if (!ok) {
        std::string all;
        for (const auto& e : *options) all += (all.empty() ? "" : ", ") + e.dump();
        report(n, key, "must be one of " + all + ", found " + describe(n));
      }
    }
    if (n.is_number()) numeric(*n.value<double>(), s, n, key);
    if (n.is_string() && get(s, "x-dimension")) quantity(*n.value<std::string>(), s, n, key);
    if (const auto* t = n.as_table()) object(*t, s, key);
    if (const auto* a = n.as_array()) array(*a, s, key);
  }

 private:
  // The schema keyword `k` of `s`, or null: one look-up without a temporary key (the validator runs
  // for every value of every calibration file loaded, so this is most of a load's time).
  static const json* get(const json& s, std::string_view k) {
    const auto it = s.find(k);
    return it == s.end() ? nullptr : &*it;
  }

  const json& resolve(const json& s) const {
    const auto it = s.find("$ref");
    if (it == s.end()) return s;
    const std::string_view ref = it->get_ref<const std::string&>();
    constexpr std::string_view prefix = "#/definitions/";
    if (!ref.starts_with(prefix)) throw std::logic_error("file schema: unsupported $ref " + std::string(ref));
    const json& definitions = root_.at("definitions");
    const auto def = definitions.find(ref.substr(prefix.size()));
    if (def == definitions.end()) throw std::logic_error("file schema: no definition for $ref " + std::string(ref));
    return resolve(*def);
  }

  static std::string article(const std::string& t) {
    return (t == "object" || t == "array" || t == "integer") ? "an " + t : "a " + t;
  }

  static bool equals(const toml::node& n, const json& j) {
    if (j.is_string()) return n.is_string() && *n.value<std::string>() == j.get<std::string>();
    if (j.is_boolean()) return n.is_boolean() && *n.value<bool>() == j.get<bool>();
    if (j.is_number()) return n.is_number() && *n.value<double>() == j.get<double>();
    return false;
  }

  void numeric(double v, const json& s, const toml::node& n, const std::string& key) {
    if (!std::isfinite(v)) report(n, key, "must be a finite number");
    if (const json* m = get(s, "minimum"); m && v < m->get<double>())
      report(n, key, "must be at least " + m->dump() + ", found " + describe(n));
    if (const json* m = get(s, "exclusiveMinimum"); m && !(v > m->get<double>()))
      report(n, key, "must be greater than " + m->dump() + ", found " + describe(n));
    if (const json* m = get(s, "maximum"); m && v > m->get<double>())
      report(n, key, "must be at most " + m->dump() + ", found " + describe(n));
  }

  // "a length", "an angle".
  static std::string a(const std::string& noun) {
    return (noun.find_first_of("aeiou") == 0 ? "an " : "a ") + noun;
  }

  void quantity(const std::string& text, const json& s, const toml::node& n, const std::string& key) {
    const std::string& dim = get(s, "x-dimension")->get_ref<const std::string&>();
    auto want = dimension_named(dim);
    if (!want) throw std::logic_error("file schema: unknown x-dimension " + dim);
    auto q = parse_quantity(text);
    if (!q) {
      report(n, key, "expected " + a(dim) + " with its unit, e.g. \"2.5 " + std::string(si_unit_name(*want)) +
                         "\" (units: " + units_of(*want) + "), found \"" + text + "\"");
      return;
    }
    if (q->unit.dimension != *want) {
      report(n, key, "\"" + text + "\" is " + a(std::string(dimension_name(q->unit.dimension))) + ", expected " + a(dim) +
                         " (units: " + units_of(*want) + ")");
      return;
    }
    if (const json* m = get(s, "exclusiveMinimum"); m && !(q->value > m->get<double>()))
      report(n, key, "must be greater than " + m->dump() + ", found \"" + text + "\"");
    if (const json* m = get(s, "minimum"); m && q->value < m->get<double>())
      report(n, key, "must be at least " + m->dump() + ", found \"" + text + "\"");
  }

  void object(const toml::table& t, const json& s, const std::string& key) {
    static const json empty = json::object();
    const json* given = get(s, "properties");
    const json& props = given ? *given : empty;
    if (const json* required = get(s, "required"))
      for (const auto& r : *required) {
        const std::string& name = r.get_ref<const std::string&>();
        if (!t.contains(name)) report_missing(t, join(key, name), "missing required key `" + name + "`");
      }
    const json* extra = get(s, "additionalProperties");
    const bool closed = extra && extra->is_boolean() && !extra->get<bool>();
    for (const auto& [k, v] : t) {
      const std::string_view name = k.str();
      if (const json* rule = get(props, name)) check(v, *rule, join(key, std::string(name)), &t);
      else if (closed) {
        std::string known;
        for (const auto& [p, unused] : props.items()) known += (known.empty() ? "" : ", ") + p;
        report_key(k, join(key, std::string(name)), "unknown key `" + std::string(name) + "`; expected one of: " + known);
      }
    }
  }

  void array(const toml::array& a, const json& s, const std::string& key) {
    if (const json* m = get(s, "minItems"); m && a.size() < m->get<std::size_t>())
      report(a, key, "needs at least " + m->dump() + " item(s), found " + std::to_string(a.size()));
    if (const json* m = get(s, "maxItems"); m && a.size() > m->get<std::size_t>())
      report(a, key, "takes at most " + m->dump() + " item(s), found " + std::to_string(a.size()));
    if (const json* items = get(s, "items"))
      for (std::size_t i = 0; i < a.size(); ++i) check(a[i], *items, key + "[" + std::to_string(i) + "]", &a);
  }

  static std::string join(const std::string& a, const std::string& b) { return a.empty() ? b : a + "." + b; }

  void report(const toml::node& n, const std::string& key, const std::string& message) {
    const auto& src = n.source();
    out_.push_back({key, static_cast<int>(src.begin.line), static_cast<int>(src.begin.column), message});
  }
  void report_key(const toml::key& k, const std::string& key, const std::string& message) {
    const auto& src = k.source();
    out_.push_back({key, static_cast<int>(src.begin.line), static_cast<int>(src.begin.column), message});
  }
  // A missing key has no position of its own; point at the table that should hold it.
  void report_missing(const toml::table& t, const std::string& key, const std::string& message) {
    const auto& src = t.source();
    out_.push_back({key, static_cast<int>(src.begin.line), static_cast<int>(src.begin.column), message});
  }

  const json& root_;
  std::vector<SchemaViolation>& out_;
};

}  // namespace

std::vector<std::string> file_schema_names() {
  std::vector<std::string> names;
  for (const auto& [n, text] : generated::file_schemas()) names.push_back(n);
  return names;
}

std::string_view file_schema_text(std::string_view name) {
  const auto& all = generated::file_schemas();
  auto it = all.find(std::string(name));
  if (it == all.end()) throw std::out_of_range("no file schema named '" + std::string(name) + "'");
  return it->second;
}

std::vector<SchemaViolation> validate_file(const toml::table& doc, std::string_view name) {
  const json& root = parsed(name);
  std::vector<SchemaViolation> out;
  Validator(root, out).check(doc, root, "", nullptr);
  return out;
}

}  // namespace sandpaper::schema

// The term-kind entries (schema/term_kinds.hpp) drive the patch writer and reader, the JSON view and
// the runtime's parameter checks. Walking each entry's field list: every listed field reaches the
// file and comes back, shows in the JSON under its key, and is refused when it breaks its check;
// docs/PATCH_FORMAT.md lists each kind's fields as its entry does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/schema/patch_io.hpp"
#include "sandpaper/schema/patch_json.hpp"
#include "sandpaper/schema/term_kinds.hpp"
#include "term_samples.hpp"

namespace sandpaper::runtime {
namespace {

using namespace testing;
using schema::Term;
namespace terms = schema::terms;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The message check_program gives for `term` alone, or "" if it accepts it.
std::string refusal(const Term& term) {
  try {
    const auto program = program_of({term});
    PatchEvaluator evaluator(program);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// Values that break `check`, which the field's own check must refuse.
std::vector<double> breaking(terms::Check check) {
  switch (check) {
    case terms::Check::Any: return {};
    case terms::Check::Finite: return {kNaN, kInf, -kInf};
    case terms::Check::Positive: return {kNaN, kInf, 0.0, -1e-3};
    case terms::Check::NonNegative: return {kNaN, kInf, -1e-3};
  }
  return {};
}

// Calls f(sample, field) for every listed field of every kind's sample term.
template <class F>
void for_each_listed_field(F&& f) {
  for (const Term& sample : every_term_kind())
    std::visit(
        [&]<class T>(const T& term) {
          if constexpr (terms::Listed<T>) terms::for_each_field<T>([&](const auto& field) { f(term, field); });
        },
        sample);
}

TEST(TermKinds, EveryListedNumberIsRefusedWhenItBreaksItsCheck) {
  int refused = 0;
  for_each_listed_field([&]<class T, class M>(const T& sample, const terms::Field<T, M>& field) {
    ASSERT_EQ(refusal(sample), "") << terms::Kind<T>::label;
    const std::string prefix = "term 0 (" + std::string(terms::Kind<T>::label) + "): " + std::string(field.label);
    if constexpr (std::is_same_v<M, double> || std::is_same_v<M, double[2]>) {
      EXPECT_NE(field.check, terms::Check::Any) << prefix << ": every number played must at least be finite";
      for (double bad : breaking(field.check)) {
        for (int half = 0; half < (std::is_same_v<M, double> ? 1 : 2); ++half) {
          T broken = sample;
          if constexpr (std::is_same_v<M, double>) broken.*(field.member) = bad;
          else (broken.*(field.member))[half] = bad;
          const std::string why = refusal(broken);
          SCOPED_TRACE(prefix + " = " + std::to_string(bad));
          EXPECT_EQ(why.rfind(prefix, 0), 0u) << why;
          ++refused;
        }
      }
    } else if constexpr (std::is_enum_v<M>) {
      T broken = sample;
      broken.*(field.member) = static_cast<M>(terms::EnumNames<M>::names.size());
      EXPECT_EQ(refusal(broken).rfind("term 0 (" + std::string(terms::Kind<T>::label) + "): unknown " +
                                          std::string(field.label), 0),
                0u);
      ++refused;
    }
  });
  EXPECT_GE(refused, 120);  // 14 kinds, 43 numbers: not a loop over nothing
}

// Another valid value of the same field, so that a field the writer, reader or JSON forgot shows.
template <class M>
void perturb(M& v) {
  if constexpr (std::is_same_v<M, double>) v = v * 1.5 + 0.25;
  else if constexpr (std::is_same_v<M, double[2]>) {
    v[0] = v[0] * 1.5 + 0.001;
    v[1] = v[1] * 1.5 - 0.002;
  } else if constexpr (std::is_same_v<M, bool>) v = !v;
  else v = static_cast<M>((static_cast<std::size_t>(v) + 1) % terms::EnumNames<M>::names.size());
}

TEST(TermKinds, EveryListedFieldReachesTheFileComesBackAndShowsInTheJson) {
  int fields = 0;
  for_each_listed_field([&]<class T, class M>(const T& sample, const terms::Field<T, M>& field) {
    SCOPED_TRACE(std::string(terms::Kind<T>::label) + " " + std::string(field.label));
    T changed = sample;
    perturb(changed.*(field.member));
    const auto before = schema::serialize(program_of({sample}));
    const auto after = schema::serialize(program_of({changed}));
    EXPECT_NE(before, after) << "the writer leaves the field out";
    const auto back = schema::deserialize(after);
    ASSERT_EQ(back.terms.size(), 1u);
    const auto shown = schema::to_json(back)["terms"][0];
    EXPECT_EQ(shown, schema::to_json(program_of({changed}))["terms"][0]) << "the reader loses the field";
    const std::string key(field.json);
    ASSERT_TRUE(shown.contains(key));
    EXPECT_NE(shown[key], schema::to_json(program_of({sample}))["terms"][0][key]) << "the JSON does not show it";
    EXPECT_EQ(shown["kind"], std::string(terms::Kind<T>::json));
    ++fields;
  });
  EXPECT_EQ(fields, 42);
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string without_parentheses(std::string s) { return std::regex_replace(s, std::regex(R"(\s*\([^)]*\))"), ""); }

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(' ');
  const auto b = s.find_last_not_of(' ');
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

// docs/PATCH_FORMAT.md's byte layout of each term, by tag: "<label>" and the fields after column 20,
// continuation lines joined.
std::map<std::uint32_t, std::pair<std::string, std::string>> documented_layouts(const std::string& doc) {
  std::map<std::uint32_t, std::pair<std::string, std::string>> out;
  const auto begin = doc.find("then each term: u32 tag + fields\n");
  const auto end = doc.find("u32 n_provenance", begin);
  std::istringstream lines(doc.substr(begin, end - begin));
  std::string line;
  std::getline(lines, line);
  std::uint32_t tag = 0;
  const std::regex entry(R"(^ *(\d+) (.*)$)");
  while (std::getline(lines, line)) {
    if (line.size() <= 20) continue;
    std::smatch m;
    const std::string head = line.substr(0, 20);
    if (std::regex_match(head, m, entry)) {
      tag = static_cast<std::uint32_t>(std::stoul(m[1]));
      out[tag] = {trim(m[2]), ""};
    }
    out[tag].second += (out[tag].second.empty() ? "" : " ") + trim(line.substr(20));
  }
  return out;
}

// The layout an entry's field list implies: "f64 stiffness_N_per_m, f64 centre_x_m, f64 centre_y_m".
template <class T>
std::string implied_layout() {
  std::string out;
  terms::for_each_field<T>([&]<class M>(const terms::Field<T, M>& field) {
    const std::string key(field.json);
    auto add = [&](const std::string& s) { out += (out.empty() ? "" : ", ") + s; };
    if constexpr (std::is_same_v<M, double>) add("f64 " + key);
    else if constexpr (std::is_same_v<M, double[2]>) {
      const auto cut = key.find('_');
      add("f64 " + key.substr(0, cut) + "_x" + key.substr(cut));
      add("f64 " + key.substr(0, cut) + "_y" + key.substr(cut));
    } else add("u8 " + key);
  });
  return out;
}

TEST(TermKinds, PatchFormatDocumentListsEachKindsFieldsAsItsEntryDoes) {
  const std::string doc = read_text(std::string(SANDPAPER_SOURCE_DIR) + "/docs/PATCH_FORMAT.md");
  ASSERT_FALSE(doc.empty());
  const auto layouts = documented_layouts(doc);
  int kinds = 0;
  terms::for_each_kind([&]<class T>(std::type_identity<T>) {
    SCOPED_TRACE(std::string(terms::Kind<T>::label));
    ASSERT_TRUE(layouts.count(terms::Kind<T>::tag)) << "no layout for tag " << terms::Kind<T>::tag;
    const auto& [label, layout] = layouts.at(terms::Kind<T>::tag);
    EXPECT_EQ(label, terms::Kind<T>::label);
    // The JSON table's row: the keys in backquotes, outside parentheses.
    const std::regex row("\\| `" + std::string(terms::Kind<T>::json) + "` \\| ([^\n]*) \\|\n");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(doc, m, row)) << "no JSON row for " << terms::Kind<T>::json;
    if constexpr (terms::Listed<T>) {
      EXPECT_EQ(without_parentheses(layout), implied_layout<T>());
      std::vector<std::string> keys, listed;
      const std::string cells = without_parentheses(m[1]);
      const std::regex quoted("`([^`]+)`");
      for (auto it = std::sregex_iterator(cells.begin(), cells.end(), quoted); it != std::sregex_iterator(); ++it)
        keys.push_back((*it)[1]);
      terms::for_each_field<T>([&](const auto& field) { listed.emplace_back(field.json); });
      EXPECT_EQ(keys, listed);
      ++kinds;
    }
  });
  EXPECT_EQ(kinds, 14);
  // An enumeration's values, in their byte order.
  EXPECT_NE(doc.find("u8 shape (0 sine, 1 sawtooth, 2 triangle)"), std::string::npos);
  EXPECT_NE(doc.find("`shape` (`sine`, `sawtooth`, `triangle`)"), std::string::npos);
  EXPECT_EQ(terms::EnumNames<schema::PeriodicShape>::names[2], "triangle");
}

}  // namespace
}  // namespace sandpaper::runtime

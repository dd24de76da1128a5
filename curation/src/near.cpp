#include "sandpaper/curation/near.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <sstream>
#include <stdexcept>

namespace sandpaper::curation {

namespace {

std::string num(double v, int digits = 3) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

}  // namespace

Neighbour distance_between(const IndexedEntry& a, const IndexedEntry& b, const WeberFractions& webers, bool explain) {
  const double weber = webers.force;
  Neighbour n;
  if (explain) n.entry = b;
  const bool ta = a.max_lateral_force_N > 0, tb = b.max_lateral_force_N > 0;
  std::vector<std::string> why;
  double d2 = 0, extra = 0;
  if (ta && tb) {
    n.force_steps = std::log(b.max_lateral_force_N / a.max_lateral_force_N) / std::log1p(weber);
    d2 += n.force_steps * n.force_steps;
    // Under 0.005 JND reads "0.00": the same force, not a stronger one.
    if (explain)
      why.push_back(std::abs(n.force_steps) < 0.005
                        ? "same force (" + num(b.max_lateral_force_N) + " N)"
                        : num(std::abs(n.force_steps), 2) + " JND " + (n.force_steps >= 0 ? "stronger" : "weaker") + " (" +
                              num(b.max_lateral_force_N) + " vs " + num(a.max_lateral_force_N) + " N)");
    if (a.period_m > 0 && b.period_m > 0) {
      n.period_doublings = std::log2(b.period_m / a.period_m);
      const double p = kJndPerPeriodDoubling * n.period_doublings;
      d2 += p * p;
      if (explain) why.push_back(std::string(a.texture_kind == "image" && b.texture_kind == "image" ? "spatial scale " : "period ") + num(b.period_m * 1000) + " vs " + num(a.period_m * 1000) + " mm (" +
                    num(n.period_doublings, 2) + " doublings)");
    } else if ((a.period_m > 0) != (b.period_m > 0)) {
      extra += kJndPerPeriodDoubling;
      if (explain) why.push_back(std::string("only ") + (a.period_m > 0 ? "the first" : "this one") + " has a spatial period");
    }
    if (a.texture_kind != b.texture_kind) {
      extra += kKindSteps;
      if (explain) why.push_back("kind " + b.texture_kind + " vs " + a.texture_kind);
    } else {
      if (explain) why.push_back("same kind (" + a.texture_kind + ")");
    }
  } else if (ta != tb) {
    extra += kTextureSteps;
    if (explain) why.push_back(tb ? "textured (the other is not)" : "no texture (the other has one)");
  } else {
    if (explain) why.push_back("neither has a texture");
  }
  // Force laws: a spring's stiffness, a damper's damping and a friction coefficient in their own
  // percepts' JNDs (softness, viscosity, slipperiness); any other parameter in force JNDs, as at a
  // given hand speed or displacement its force scales with it; opposite signs (damping vs
  // anti-viscous) as a kind.
  for (const auto& [k, va] : a.term_params)
    for (const auto& [k2, vb] : b.term_params) {
      if (k != k2 || va == 0 || vb == 0) continue;
      if ((va < 0) != (vb < 0)) {
        extra += kKindSteps;
        if (explain) why.push_back(k + " of opposite sign (" + num(vb) + " vs " + num(va) + ")");
      } else if (va != vb) {
        const double w = webers.for_term(k);
        const double s = std::log(vb / va) / std::log1p(w);
        d2 += s * s;
        if (explain) why.push_back(k + " " + num(vb) + " vs " + num(va) + " (" + num(std::abs(s), 2) + " JND at " + num(w * 100, 2) + " %)");
      }
    }
  if (a.terms != b.terms) {
    extra += kKindSteps;
    if (explain) why.push_back("terms " + (b.terms.empty() ? std::string("none") : b.terms) + " vs " + (a.terms.empty() ? std::string("none") : a.terms));
  }
  n.distance = std::sqrt(d2) + extra;
  for (const auto& w : why) n.why += (n.why.empty() ? "" : "; ") + w;
  return n;
}

std::vector<Neighbour> nearest(const Index& index, const std::string& name, std::size_t limit, const std::string& family) {
  const auto from = index.entry(name);
  if (!from) return {};
  return nearest_to(index, *from, limit, index.weber_fractions(), family);
}

std::vector<Neighbour> nearest_to(const Index& index, const IndexedEntry& from_entry, std::size_t limit, const WeberFractions& webers,
                                  const std::string& family) {
  // A Weber fraction of 0 or NaN makes the box below never grow, and the search never ends.
  if (!webers.valid()) throw std::invalid_argument("nearest_to: every Weber fraction must be in (0, 1]");
  const double weber = webers.force;
  if (limit == 0) return {};
  const auto* from = &from_entry;
  // Every entry but `from` itself, when it is one of this index's.
  const std::size_t total = index.size() + (index.entry(from->name) ? 0 : 1);
  std::set<std::string> seen{from->name};
  std::vector<Neighbour> found;
  auto consider = [&](const std::vector<IndexedEntry>& entries) {
    for (const auto& e : entries)
      if (seen.insert(e.name).second && (family.empty() || e.family == family)) {
        found.push_back(distance_between(*from, e, webers, false));  // the why of the nearest only, below
        found.back().entry.name = e.name;
      }
  };
  auto within = [&](double r) {
    return static_cast<std::size_t>(std::count_if(found.begin(), found.end(), [&](const auto& n) { return n.distance < r; }));
  };
  // The distance is at least the larger of |force steps| and |period steps| (near.hpp), plus
  // kJndPerPeriodDoubling when only one of the two has a period and kTextureSteps when only one
  // has a texture. So every entry closer than r lies in a box of half-width r (less those
  // constants) around `from`: read the boxes from the R*Tree, growing r until `limit` entries are
  // closer than r or every entry was seen.
  if (from->max_lateral_force_N > 0) {
    const double f = std::log(from->max_lateral_force_N), step = std::log1p(weber);
    const bool periodic = from->period_m > 0;
    const double p = periodic ? std::log2(from->period_m) : 0.0;
    const double cls = index.class_of(from->texture_kind + "|" + from->terms);
    bool untextured_read = false;
    for (double r = 1;; r *= 2) {  // JND steps; small first: a large library is dense
      Index::Box same;  // same kind and terms, same period-ness: force and period within r
      same.ln_force_lo = f - r * step, same.ln_force_hi = f + r * step;
      if (periodic) same.log2_period_lo = p - r / kJndPerPeriodDoubling, same.log2_period_hi = p + r / kJndPerPeriodDoubling;
      same.class_lo = same.class_hi = cls;
      same.periodless = !periodic;
      consider(index.textured_in_box(same));
      // The other period-ness adds kJndPerPeriodDoubling: force within r less that.
      if (const double other = r - kJndPerPeriodDoubling; other >= 0) {
        Index::Box b;
        b.ln_force_lo = f - other * step, b.ln_force_hi = f + other * step;
        b.class_lo = b.class_hi = cls;
        b.periodless = periodic;
        consider(index.textured_in_box(b));
      }
      // Another kind or other terms adds kKindSteps: force within r less that, any class.
      if (const double other = r - kKindSteps; other >= 0) {
        Index::Box b;
        b.ln_force_lo = f - other * step, b.ln_force_hi = f + other * step;
        consider(index.textured_in_box(b));
      }
      if (!untextured_read && r >= kTextureSteps) {
        consider(index.untextured());
        untextured_read = true;
      }
      if (within(r) >= limit || seen.size() >= total) break;
    }
  } else {
    // No texture: the same terms lie in a box of half-width r JNDs on each law dimension `from`
    // has (the distance is at least the largest of them: laws_in_box); other terms are kKindSteps
    // or more away, textured entries kTextureSteps or more.
    // The index placed its entries with its own fractions; the box is read on that scale.
    const auto c = law_coordinates(from->term_params, index.weber_fractions());
    const double cls = index.class_of("|" + from->terms);
    bool others_read = false, textured_read = false;
    for (double r = 1;; r *= 2) {
      Index::LawBox box;
      for (std::size_t d = 0; d < c.size(); ++d)
        if (c[d]) box.lo[d] = *c[d] - r, box.hi[d] = *c[d] + r;
      box.class_lo = box.class_hi = cls;
      consider(index.untextured_in_box(box));
      if (!others_read && r >= kKindSteps) {
        consider(index.untextured());
        others_read = true;
      }
      if (!textured_read && r >= kTextureSteps) {
        consider(index.textured_in_box(Index::Box{}));
        textured_read = true;
      }
      if (within(r) >= limit || seen.size() >= total) break;
    }
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.entry.name < b.entry.name;
  });
  if (found.size() > limit) found.resize(limit);
  // The nearest, read whole (aliases and other percepts) for the caller.
  for (auto& n : found)
    if (auto e = index.entry(n.entry.name)) n = distance_between(*from, *e, webers);
  return found;
}

}  // namespace sandpaper::curation

#include "sandpaper/curation/near.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "sqlite_util.hpp"

namespace sandpaper::curation {

namespace {

std::string num(double v, int digits = 3) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

}  // namespace

Neighbour distance_between(const IndexedEntry& a, const IndexedEntry& b, double weber) {
  Neighbour n;
  n.entry = b;
  const bool ta = a.max_lateral_force_N > 0, tb = b.max_lateral_force_N > 0;
  std::vector<std::string> why;
  double d2 = 0, extra = 0;
  if (ta && tb) {
    n.force_steps = std::log(b.max_lateral_force_N / a.max_lateral_force_N) / std::log1p(weber);
    d2 += n.force_steps * n.force_steps;
    why.push_back(num(std::abs(n.force_steps), 2) + " JND " + (n.force_steps >= 0 ? "stronger" : "weaker") + " (" +
                  num(b.max_lateral_force_N) + " vs " + num(a.max_lateral_force_N) + " N)");
    if (a.period_m > 0 && b.period_m > 0) {
      n.period_doublings = std::log2(b.period_m / a.period_m);
      const double p = kJndPerPeriodDoubling * n.period_doublings;
      d2 += p * p;
      why.push_back("period " + num(b.period_m * 1000) + " vs " + num(a.period_m * 1000) + " mm (" +
                    num(n.period_doublings, 2) + " doublings)");
    } else if ((a.period_m > 0) != (b.period_m > 0)) {
      extra += kJndPerPeriodDoubling;
      why.push_back(std::string("only ") + (a.period_m > 0 ? "the first" : "this one") + " has a spatial period");
    }
    if (a.texture_kind != b.texture_kind) {
      extra += kKindSteps;
      why.push_back("kind " + b.texture_kind + " vs " + a.texture_kind);
    } else {
      why.push_back("same kind (" + a.texture_kind + ")");
    }
  } else if (ta != tb) {
    extra += kTextureSteps;
    why.push_back(tb ? "textured (the other is not)" : "no texture (the other has one)");
  } else {
    why.push_back("neither has a texture");
  }
  // Force laws: at a given hand speed or displacement their force scales with the parameter, so a
  // ratio of parameters is counted in force JNDs too; opposite signs (damping vs anti-viscous) as a kind.
  for (const auto& [k, va] : a.term_params)
    for (const auto& [k2, vb] : b.term_params) {
      if (k != k2 || va == 0 || vb == 0) continue;
      if ((va < 0) != (vb < 0)) {
        extra += kKindSteps;
        why.push_back(k + " of opposite sign (" + num(vb) + " vs " + num(va) + ")");
      } else if (va != vb) {
        const double s = std::log(vb / va) / std::log1p(weber);
        d2 += s * s;
        why.push_back(k + " " + num(vb) + " vs " + num(va) + " (" + num(std::abs(s), 2) + " JND)");
      }
    }
  if (a.terms != b.terms) {
    extra += kKindSteps;
    why.push_back("terms " + (b.terms.empty() ? std::string("none") : b.terms) + " vs " + (a.terms.empty() ? std::string("none") : a.terms));
  }
  n.distance = std::sqrt(d2) + extra;
  for (const auto& w : why) n.why += (n.why.empty() ? "" : "; ") + w;
  return n;
}

std::vector<Neighbour> nearest(const Index& index, const std::string& name, std::size_t limit) {
  const auto from = index.entry(name);
  if (!from || limit == 0) return {};
  const double weber = std::stod(index.meta("weber_fraction"));
  sqlite3* db = index.handle();
  std::int64_t total = 0;
  {
    sql::Stmt n(db, "SELECT count(*) FROM entries");
    if (n.step()) total = n.integer64(0);
  }
  std::set<std::int64_t> seen;
  std::vector<Neighbour> found;
  auto consider = [&](sql::Stmt& ids) {
    std::vector<std::int64_t> fresh;
    while (ids.step())
      if (seen.insert(ids.integer64(0)).second) fresh.push_back(ids.integer64(0));
    for (const auto& e : index.entries_by_rowid(fresh))
      if (e.name != from->name) found.push_back(distance_between(*from, e, weber));
  };
  auto within = [&](double r) {
    return static_cast<std::size_t>(std::count_if(found.begin(), found.end(), [&](const auto& n) { return n.distance < r; }));
  };
  // Every entry in a box of half-width r JND around `from` in (force steps, period steps) is a
  // candidate; outside it the distance is more than r, since the distance is at least the larger
  // of the two (near.hpp). Grow r until `limit` candidates are within r, or all were seen.
  double r = 2 * kJndPerPeriodDoubling;
  if (from->max_lateral_force_N > 0) {
    sql::Stmt box(db, "SELECT id FROM coordinates WHERE log_force_max >= ? AND log_force_min <= ? "
                      "AND log_period_max >= ? AND log_period_min <= ?");
    const double f = std::log(from->max_lateral_force_N);
    const double p = from->period_m > 0 ? std::log2(from->period_m) : 0.0;
    const double p_any = from->period_m > 0 ? 0.0 : 1e30;  // no period: the period axis does not bound the distance
    for (;; r *= 2) {
      const double df = r * std::log1p(weber), dp = r / kJndPerPeriodDoubling + p_any;
      box.bind(1, f - df).bind(2, f + df).bind(3, p - dp).bind(4, p + dp);
      consider(box);
      box.reset();
      // Untextured entries are kTextureSteps or more away.
      if (r >= kTextureSteps) {
        sql::Stmt flat(db, "SELECT rowid FROM entries WHERE max_lateral_force_N <= 0");
        consider(flat);
      }
      if (within(r) >= limit || static_cast<std::int64_t>(seen.size()) >= total) break;
    }
  } else {
    // No texture: force laws differ by parameters the R*Tree does not hold; the untextured
    // entries first (textured ones are kTextureSteps or more away), then all if too few.
    sql::Stmt flat(db, "SELECT rowid FROM entries WHERE max_lateral_force_N <= 0");
    consider(flat);
    r = kTextureSteps;
    if (within(r) < limit) {
      sql::Stmt all(db, "SELECT rowid FROM entries");
      consider(all);
    }
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.entry.name < b.entry.name;
  });
  if (found.size() > limit) found.resize(limit);
  return found;
}

}  // namespace sandpaper::curation

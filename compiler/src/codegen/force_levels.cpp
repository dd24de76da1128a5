#include "sandpaper/compiler/force_levels.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>

namespace sandpaper::compiler {

ForceLevels count_force_levels(const schema::PatchProgram& p) {
  ForceLevels out;
  std::set<float> mags, values;
  auto add = [&](const std::vector<float>& table) {
    ++out.tables;
    out.samples += table.size();
    for (float f : table) {
      // +0 and -0 are one value: no force.
      values.insert(f == 0.0f ? 0.0f : f);
      if (f != 0.0f) mags.insert(std::abs(f));
    }
  };
  for (const auto& t : p.terms) {
    if (const auto* g = std::get_if<schema::GratingTerm>(&t)) add(g->force_N);
    else if (const auto* h = std::get_if<schema::HeightFieldTerm>(&t)) {
      add(h->force_x_N);
      add(h->force_y_N);
    }
  }
  out.magnitudes = mags.size();
  out.signed_values = values.size();
  return out;
}

namespace {

long command_of(double f, double step, long command_max) {
  if (!(step > 0)) return 0;
  const double units = std::round(f / step);
  const double cap = command_max > 0 ? static_cast<double>(command_max) : 1e15;
  return static_cast<long>(std::clamp(units, -cap, cap));
}

std::size_t table_levels(const std::vector<float>& t) {
  std::set<float> mags;
  for (float f : t)
    if (f != 0.0f) mags.insert(std::abs(f));
  return mags.size();
}

}  // namespace

std::vector<QuantizedTable> quantize_tables(const schema::PatchProgram& p, double position_step_m, double force_step_N,
                                            long command_max) {
  std::vector<QuantizedTable> out;
  for (const auto& t : p.terms) {
    if (const auto* g = std::get_if<schema::GratingTerm>(&t)) {
      QuantizedTable q;
      q.kind = "grating";
      q.spacing_m = g->period_m;
      q.positions_per_spacing = position_step_m > 0 ? g->period_m / position_step_m : 0;
      q.table_levels = table_levels(g->force_N);
      std::set<long> sent;
      const std::size_t n = g->force_N.size();
      // Every encoder count over 64 periods (at most 2^20 of them).
      const double counts = position_step_m > 0 ? std::min(64.0 * g->period_m / position_step_m, 1048576.0) : 0;
      for (long k = 0; k < static_cast<long>(counts); ++k) {
        const double u = static_cast<double>(k) * position_step_m / g->period_m;
        const auto i = static_cast<std::size_t>(std::llround((u - std::floor(u)) * static_cast<double>(n))) % n;
        const long c = command_of(g->force_N[i], force_step_N, command_max);
        if (c != 0) sent.insert(std::labs(c));
      }
      q.device_levels = sent.size();
      q.largest_N = sent.empty() ? 0 : static_cast<double>(*sent.rbegin()) * force_step_N;
      out.push_back(q);
    } else if (const auto* h = std::get_if<schema::HeightFieldTerm>(&t)) {
      QuantizedTable q;
      q.kind = "height field";
      q.spacing_m = h->spacing_m[0];
      q.positions_per_spacing = position_step_m > 0 ? h->spacing_m[0] / position_step_m : 0;
      std::vector<float> both(h->force_x_N);
      both.insert(both.end(), h->force_y_N.begin(), h->force_y_N.end());
      q.table_levels = table_levels(both);
      std::set<long> sent;
      for (float f : both)
        if (const long c = command_of(f, force_step_N, command_max); c != 0) sent.insert(std::labs(c));
      q.device_levels = sent.size();
      q.largest_N = sent.empty() ? 0 : static_cast<double>(*sent.rbegin()) * force_step_N;
      out.push_back(q);
    }
  }
  return out;
}

}  // namespace sandpaper::compiler

#include "sandpaper/runtime/patch_evaluator.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>

namespace sandpaper::runtime {
namespace {

using schema::DamperTerm;
using schema::GratingTerm;
using schema::HeightFieldTerm;
using schema::SpringTerm;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool positive_finite(double x) { return std::isfinite(x) && x > 0; }

// The tick indexes tables without bounds checks, so every shape the indexing relies on is checked
// once here, off the servo thread. Values may be anything: a NaN sample is the loop's to catch.
void check_grating(const GratingTerm& grating, std::size_t term) {
  if (!positive_finite(grating.period_m))
    throw std::invalid_argument("term " + std::to_string(term) + ": grating period must be a positive, finite length");
  if (!std::isfinite(grating.orientation_rad))
    throw std::invalid_argument("term " + std::to_string(term) + ": grating orientation must be finite");
  if (grating.force_N.size() < 2)
    throw std::invalid_argument("term " + std::to_string(term) + ": grating force table needs at least 2 samples");
}

void check_height_field(const HeightFieldTerm& field, std::size_t term) {
  const std::size_t samples = std::size_t{field.nx} * field.ny;
  if (samples == 0)
    throw std::invalid_argument("term " + std::to_string(term) + ": height field grid is empty");
  if (field.force_x_N.size() != samples || field.force_y_N.size() != samples)
    throw std::invalid_argument("term " + std::to_string(term) + ": height field force tables must hold nx * ny samples");
  if (!positive_finite(field.spacing_m[0]) || !positive_finite(field.spacing_m[1]))
    throw std::invalid_argument("term " + std::to_string(term) + ": height field spacing must be positive and finite");
  if (!std::isfinite(field.origin_m[0]) || !std::isfinite(field.origin_m[1]))
    throw std::invalid_argument("term " + std::to_string(term) + ": height field origin must be finite");
}

// Splits an index in [0, n] into a cell and the fraction across it. n itself can occur: x - floor(x)
// rounds up to exactly 1 for tiny negative x, and that is the start of cell 0 again.
void split_index(double index, std::size_t n, std::size_t& cell, double& frac) noexcept {
  const double whole = std::floor(index);
  cell = static_cast<std::size_t>(whole);
  frac = index - whole;
  if (cell >= n) {
    cell = 0;
    frac = 0;
  }
}

// Grid coordinate `x` (finite) wrapped with a period of `n` cells.
void wrap_cell(double x, std::size_t n, std::size_t& cell, double& frac) noexcept {
  const double turns = x / static_cast<double>(n);
  split_index((turns - std::floor(turns)) * static_cast<double>(n), n, cell, frac);
}

glm::dvec2 grating_force(const GratingTerm& grating, glm::dvec2 p) noexcept {
  const glm::dvec2 n{std::cos(grating.orientation_rad), std::sin(grating.orientation_rad)};
  const double u = (p.x * n.x + p.y * n.y) / grating.period_m;
  if (!std::isfinite(u)) return {kNaN, kNaN};  // a period too small to resolve: refuse, don't guess
  const std::size_t size = grating.force_N.size();
  std::size_t i = 0;
  double frac = 0;
  split_index((u - std::floor(u)) * static_cast<double>(size), size, i, frac);
  const double lo = grating.force_N[i];
  const double hi = grating.force_N[(i + 1) % size];
  return (lo + frac * (hi - lo)) * n;
}

// Non-repeating fields end at the last sample: the grid spans [0, n - 1] cells, edges included.
bool clamp_cell(double x, std::uint32_t n, std::size_t& cell, double& frac) noexcept {
  if (!(x >= 0 && x <= static_cast<double>(n - 1))) return false;
  const double whole = std::floor(x);
  cell = static_cast<std::size_t>(whole);
  frac = x - whole;
  if (cell >= n - 1) {  // on the far edge: no next sample to blend toward
    cell = n - 1;
    frac = 0;
  }
  return true;
}

glm::dvec2 height_field_force(const HeightFieldTerm& field, glm::dvec2 p) noexcept {
  const double gx = (p.x - field.origin_m[0]) / field.spacing_m[0];
  const double gy = (p.y - field.origin_m[1]) / field.spacing_m[1];
  std::size_t ix0 = 0, iy0 = 0, ix1 = 0, iy1 = 0;
  double fx = 0, fy = 0;
  if (field.repeat) {
    if (!std::isfinite(gx) || !std::isfinite(gy)) return {kNaN, kNaN};
    wrap_cell(gx, field.nx, ix0, fx);
    wrap_cell(gy, field.ny, iy0, fy);
    ix1 = (ix0 + 1) % field.nx;
    iy1 = (iy0 + 1) % field.ny;
  } else {
    if (!clamp_cell(gx, field.nx, ix0, fx) || !clamp_cell(gy, field.ny, iy0, fy)) return {0, 0};
    ix1 = ix0 + 1 < field.nx ? ix0 + 1 : ix0;
    iy1 = iy0 + 1 < field.ny ? iy0 + 1 : iy0;
  }
  const std::size_t row0 = iy0 * field.nx, row1 = iy1 * field.nx;
  const auto bilinear = [&](const std::vector<float>& grid) noexcept {
    const double bottom = grid[row0 + ix0] + fx * (static_cast<double>(grid[row0 + ix1]) - grid[row0 + ix0]);
    const double top = grid[row1 + ix0] + fx * (static_cast<double>(grid[row1 + ix1]) - grid[row1 + ix0]);
    return bottom + fy * (top - bottom);
  };
  return {bilinear(field.force_x_N), bilinear(field.force_y_N)};
}

}  // namespace

PatchEvaluator::PatchEvaluator(const schema::PatchProgram& program) : program_(program) {
  if (!positive_finite(program.size_m[0]) || !positive_finite(program.size_m[1]))
    throw std::invalid_argument("patch size must be positive and finite");
  for (std::size_t i = 0; i < program.terms.size(); ++i) {
    if (const auto* grating = std::get_if<GratingTerm>(&program.terms[i])) check_grating(*grating, i);
    if (const auto* field = std::get_if<HeightFieldTerm>(&program.terms[i])) check_height_field(*field, i);
  }
}

void PatchEvaluator::reset_rt(const HandState&) noexcept {}

glm::dvec2 PatchEvaluator::force_rt(const HandState& hand, double) noexcept {
  const glm::dvec2 p = hand.position_m;
  // A position the device cannot have reported is a fault; NaN makes the loop stop on it rather
  // than play the zero force the patch-rectangle test would otherwise give.
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return {kNaN, kNaN};
  if (std::abs(p.x) > 0.5 * program_.size_m[0] || std::abs(p.y) > 0.5 * program_.size_m[1]) return {0, 0};

  glm::dvec2 force{0, 0};
  for (const schema::Term& term : program_.terms) {
    if (const auto* spring = std::get_if<SpringTerm>(&term)) {
      force -= spring->stiffness_N_per_m * (p - glm::dvec2{spring->centre_m[0], spring->centre_m[1]});
    } else if (const auto* damper = std::get_if<DamperTerm>(&term)) {
      force -= damper->damping_Ns_per_m * hand.velocity_m_s;
    } else if (const auto* grating = std::get_if<GratingTerm>(&term)) {
      force += grating_force(*grating, p);
    } else if (const auto* field = std::get_if<HeightFieldTerm>(&term)) {
      force += height_field_force(*field, p);
    }
  }
  return force;
}

}  // namespace sandpaper::runtime

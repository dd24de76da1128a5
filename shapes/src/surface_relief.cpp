#include "sandpaper/shapes/surface_relief.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <variant>

#include <glm/geometric.hpp>

#include "sandpaper/runtime/texture_force.hpp"
#include "sandpaper/shapes/surface_texture.hpp"

namespace sandpaper::shapes {
namespace {

// Where x (in samples, finite) falls on a line of n samples: cell, next sample and the fraction
// between, and the scale of d/dx (1 inside, 0 where a grid that does not repeat is clamped). The
// wrap and the clamp are runtime/src/force_tables.cpp's, so the carve lies where the force does.
struct Cell {
  std::size_t i0 = 0, i1 = 0;
  double frac = 0;
  double slope = 1;
};

// An index in [0, n] split into a cell and the fraction across it.
Cell split(double index, std::size_t n) noexcept {
  Cell c;
  const double whole = std::floor(index);
  c.i0 = static_cast<std::size_t>(whole);
  c.frac = index - whole;
  // x - floor(x) can round up to exactly 1 for a tiny negative x: that is cell 0 again.
  if (c.i0 >= n) c.i0 = 0, c.frac = 0;
  c.i1 = (c.i0 + 1) % n;
  return c;
}

Cell wrapped(double x, std::size_t n) noexcept {
  const double turns = x / static_cast<double>(n);
  return split((turns - std::floor(turns)) * static_cast<double>(n), n);
}

// Outside the grid c keeps its edge's value: continuous, and flat there.
Cell clamped(double x, std::size_t n) noexcept {
  Cell c;
  if (n < 2 || !(x > 0)) {
    c.slope = 0;
    return c;
  }
  const double last = static_cast<double>(n - 1);
  if (x >= last) {
    c.i0 = c.i1 = n - 1;
    c.slope = 0;
    return c;
  }
  const double whole = std::floor(x);
  c.i0 = static_cast<std::size_t>(whole);
  c.i1 = c.i0 + 1;
  c.frac = x - whole;
  return c;
}

// U along one line of n samples (at `stride` apart in f), U[0] = 0: the cumulative trapezoid of -f
// with spacing h, exact for the linearly interpolated force. A repeating line also runs from its
// last sample back to its first; the drift over that whole turn is taken out linearly, so U closes.
void integrate_line(const float* f, std::size_t stride, std::size_t n, double h, bool wrap, double* out,
                    std::size_t out_stride) {
  double u = 0;
  out[0] = 0;
  for (std::size_t i = 1; i < n; ++i) {
    u -= 0.5 * h * (static_cast<double>(f[(i - 1) * stride]) + f[i * stride]);
    out[i * out_stride] = u;
  }
  if (!wrap) return;
  const double drift = u - 0.5 * h * (static_cast<double>(f[(n - 1) * stride]) + f[0]);
  for (std::size_t i = 1; i < n; ++i) out[i * out_stride] -= drift * static_cast<double>(i) / static_cast<double>(n);
}

std::vector<double> grating_potential(const schema::GratingTerm& g) {
  const std::size_t n = g.force_N.size();
  std::vector<double> u(n);
  integrate_line(g.force_N.data(), 1, n, g.period_m / static_cast<double>(n), true, u.data(), 1);
  return u;
}

// Integrated along rows then columns, and along columns then rows, and the two averaged: a table
// of forces that is not exactly a gradient (float rounding, smoothing at the edges) gives one U
// that depends on neither order.
std::vector<double> field_potential(const schema::HeightFieldTerm& t) {
  const std::size_t nx = t.nx, ny = t.ny;
  const double hx = t.spacing_m[0], hy = t.spacing_m[1];
  std::vector<double> a(nx * ny), b(nx * ny), line(std::max(nx, ny));
  // Rows first: along row 0, then up each column from it.
  integrate_line(t.force_x_N.data(), 1, nx, hx, t.repeat, line.data(), 1);
  for (std::size_t ix = 0; ix < nx; ++ix) {
    integrate_line(t.force_y_N.data() + ix, nx, ny, hy, t.repeat, a.data() + ix, nx);
    for (std::size_t iy = 0; iy < ny; ++iy) a[iy * nx + ix] += line[ix];
  }
  // Columns first: up column 0, then along each row from it.
  integrate_line(t.force_y_N.data(), nx, ny, hy, t.repeat, line.data(), 1);
  for (std::size_t iy = 0; iy < ny; ++iy) {
    integrate_line(t.force_x_N.data() + iy * nx, 1, nx, hx, t.repeat, b.data() + iy * nx, 1);
    for (std::size_t ix = 0; ix < nx; ++ix) b[iy * nx + ix] += line[iy];
  }
  for (std::size_t k = 0; k < a.size(); ++k) a[k] = 0.5 * (a[k] + b[k]);
  return a;
}

}  // namespace

SurfaceRelief SurfaceRelief::for_program_nonrt(const schema::PatchProgram& program, double relief_depth_m,
                                               std::optional<glm::dvec2> uv_size_m) {
  if (!(relief_depth_m > 0) || !std::isfinite(relief_depth_m))
    throw std::invalid_argument("surface relief: the relief depth must be positive and finite");
  const glm::dvec2 size = uv_size_m.value_or(glm::dvec2{program.size_m[0], program.size_m[1]});
  if (!(size.x > 0 && size.y > 0 && std::isfinite(size.x) && std::isfinite(size.y)))
    throw std::invalid_argument("surface relief: the patch metres per unit of u and v must be positive");
  const schema::PatchProgram texture = runtime::texture_terms_of(program);
  if (texture.terms.empty())
    throw std::invalid_argument("surface relief: the material has no texture (grating or height field) to follow");

  SurfaceRelief r;
  r.uv_size_m_ = size;
  r.depth_m_ = relief_depth_m;
  // Each term's U, then the carve D (Umax_i - U_i) / sum of the ranges, shared out term by term.
  std::vector<std::vector<double>*> tables;
  double range = 0;
  for (const schema::Term& term : texture.terms) {
    if (const auto* g = std::get_if<schema::GratingTerm>(&term)) {
      Grating out;
      out.direction = {std::cos(g->orientation_rad), std::sin(g->orientation_rad)};
      out.period_m = g->period_m;
      out.c = grating_potential(*g);
      r.gratings_.push_back(std::move(out));
    } else if (const auto* h = std::get_if<schema::HeightFieldTerm>(&term)) {
      Field out;
      out.nx = h->nx;
      out.ny = h->ny;
      out.origin_m = {h->origin_m[0], h->origin_m[1]};
      out.spacing_m = {h->spacing_m[0], h->spacing_m[1]};
      out.repeat = h->repeat;
      out.c = field_potential(*h);
      r.fields_.push_back(std::move(out));
    }
  }
  for (auto& g : r.gratings_) tables.push_back(&g.c);
  for (auto& f : r.fields_) tables.push_back(&f.c);
  std::vector<double> top(tables.size());
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const auto [lo, hi] = std::minmax_element(tables[i]->begin(), tables[i]->end());
    if (!std::isfinite(*lo) || !std::isfinite(*hi))
      throw std::invalid_argument("surface relief: the texture's potential is not finite");
    top[i] = *hi;
    range += *hi - *lo;
  }
  if (!std::isfinite(range)) throw std::invalid_argument("surface relief: the texture's potential is not finite");
  // No force anywhere, no relief: flat.
  const double scale = range > 0 ? relief_depth_m / range : 0.0;
  for (std::size_t i = 0; i < tables.size(); ++i)
    for (double& v : *tables[i]) v = scale * (top[i] - v);
  return r;
}

double SurfaceRelief::depth_at_rt(glm::dvec2 s, glm::dvec2* gradient) const noexcept {
  double c = 0;
  glm::dvec2 grad{0.0};
  for (const Grating& g : gratings_) {
    const double u = (s.x * g.direction.x + s.y * g.direction.y) / g.period_m;
    if (!std::isfinite(u)) continue;
    const std::size_t n = g.c.size();
    const Cell k = split((u - std::floor(u)) * static_cast<double>(n), n);
    const double lo = g.c[k.i0], hi = g.c[k.i1];
    c += lo + k.frac * (hi - lo);
    grad += (hi - lo) * (static_cast<double>(n) / g.period_m) * g.direction;
  }
  for (const Field& f : fields_) {
    const double gx = (s.x - f.origin_m.x) / f.spacing_m.x, gy = (s.y - f.origin_m.y) / f.spacing_m.y;
    if (std::isnan(gx) || std::isnan(gy) || (f.repeat && (!std::isfinite(gx) || !std::isfinite(gy)))) continue;
    const Cell x = f.repeat ? wrapped(gx, f.nx) : clamped(gx, f.nx);
    const Cell y = f.repeat ? wrapped(gy, f.ny) : clamped(gy, f.ny);
    const double c00 = f.c[y.i0 * f.nx + x.i0], c10 = f.c[y.i0 * f.nx + x.i1];
    const double c01 = f.c[y.i1 * f.nx + x.i0], c11 = f.c[y.i1 * f.nx + x.i1];
    const double bottom = c00 + x.frac * (c10 - c00), top = c01 + x.frac * (c11 - c01);
    c += bottom + y.frac * (top - bottom);
    // The bilinear interpolant's own derivative: a gradient field, so the relief is conservative.
    grad.x += x.slope * ((1 - y.frac) * (c10 - c00) + y.frac * (c11 - c01)) / f.spacing_m.x;
    grad.y += y.slope * (top - bottom) / f.spacing_m.y;
  }
  if (gradient) *gradient = grad;
  return c;
}

double SurfaceRelief::carve_rt(const Mesh& mesh, std::uint32_t triangle, const glm::dvec3& point_m,
                               glm::dvec3& slope) const noexcept {
  glm::dvec2 g{0.0};
  const double c = depth_at_rt(uv_patch_position_rt(mesh, triangle, point_m, uv_size_m_), &g);
  slope = uv_pull_back_rt(mesh, triangle, g, uv_size_m_);
  const double squared = glm::dot(slope, slope);
  if (squared > 1.0) slope /= std::sqrt(squared);
  return c;
}

}  // namespace sandpaper::shapes

#include "sandpaper/shapes/primitives.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace sandpaper::shapes {

MeshData uv_sphere_data(double radius_m, std::uint32_t n_lon, std::uint32_t n_lat, const glm::dvec3& center_m) {
  if (!(radius_m > 0.0) || n_lon < 3 || n_lat < 2) {
    throw std::invalid_argument("uv_sphere: needs radius > 0, n_lon >= 3 and n_lat >= 2");
  }
  MeshData data;
  const std::uint32_t cols = n_lon + 1;  // the seam column repeats column 0 with u = 1
  data.vertices.reserve(std::size_t{cols} * (n_lat + 1));
  data.uvs.reserve(data.vertices.capacity());
  for (std::uint32_t j = 0; j <= n_lat; ++j) {
    const double theta = std::numbers::pi * j / n_lat;
    // The poles are exact so that every pole vertex is the same point.
    const double sin_t = (j == 0 || j == n_lat) ? 0.0 : std::sin(theta);
    const double cos_t = j == 0 ? 1.0 : (j == n_lat ? -1.0 : std::cos(theta));
    for (std::uint32_t i = 0; i < cols; ++i) {
      const double phi = 2.0 * std::numbers::pi * (i == n_lon ? 0 : i) / n_lon;
      data.vertices.push_back(center_m + radius_m * glm::dvec3{sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t});
      data.uvs.emplace_back(static_cast<double>(i) / n_lon, static_cast<double>(j) / n_lat);
    }
  }
  auto at = [cols](std::uint32_t i, std::uint32_t j) { return j * cols + i; };
  data.triangles.reserve(std::size_t{2} * n_lon * (n_lat - 1));
  for (std::uint32_t j = 0; j < n_lat; ++j) {
    for (std::uint32_t i = 0; i < n_lon; ++i) {
      // a b on ring j, c d on ring j + 1; (theta, phi) increasing is (south, east), and
      // south x east is outward, so (a, c, d) and (a, d, b) face out.
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i, j + 1), d = at(i + 1, j + 1);
      if (j != 0) data.triangles.push_back({a, d, b});
      if (j != n_lat - 1) data.triangles.push_back({a, c, d});
    }
  }
  return data;
}

Mesh uv_sphere(double radius_m, std::uint32_t n_lon, std::uint32_t n_lat, const glm::dvec3& center_m) {
  return Mesh::build_nonrt(uv_sphere_data(radius_m, n_lon, n_lat, center_m));
}

Mesh box(const glm::dvec3& center_m, const glm::dvec3& half_extents_m, bool inward) {
  if (!(half_extents_m.x > 0.0 && half_extents_m.y > 0.0 && half_extents_m.z > 0.0)) {
    throw std::invalid_argument("box: half extents must be positive");
  }
  MeshData data;
  // Each face: its outward axis and sign, and two in-face axes u, v with u x v = outward.
  struct Face {
    int axis;
    double sign;
    int u;
    int v;
  };
  const Face faces[] = {{0, 1, 1, 2}, {0, -1, 2, 1}, {1, 1, 2, 0}, {1, -1, 0, 2}, {2, 1, 0, 1}, {2, -1, 1, 0}};
  for (const Face& f : faces) {
    const auto base = static_cast<std::uint32_t>(data.vertices.size());
    for (int k = 0; k < 4; ++k) {
      const double su = (k == 1 || k == 2) ? 1.0 : -1.0;
      const double sv = (k >= 2) ? 1.0 : -1.0;
      glm::dvec3 p{0.0};
      p[f.axis] = f.sign * half_extents_m[f.axis];
      p[f.u] = su * half_extents_m[f.u];
      p[f.v] = sv * half_extents_m[f.v];
      data.vertices.push_back(center_m + p);
      data.uvs.emplace_back(0.5 * (su + 1.0), 0.5 * (sv + 1.0));
    }
    // Corners in order (-,-), (+,-), (+,+), (-,+) of (u, v): counter-clockwise about u x v.
    if (!inward) {
      data.triangles.push_back({base, base + 1, base + 2});
      data.triangles.push_back({base, base + 2, base + 3});
    } else {
      data.triangles.push_back({base, base + 2, base + 1});
      data.triangles.push_back({base, base + 3, base + 2});
    }
  }
  return Mesh::build_nonrt(std::move(data));
}

Mesh plane(double half_x_m, double half_y_m, std::uint32_t nx, std::uint32_t ny, double z_m) {
  if (!(half_x_m > 0.0 && half_y_m > 0.0) || nx < 1 || ny < 1) {
    throw std::invalid_argument("plane: needs positive half sizes and at least one square each way");
  }
  MeshData data;
  for (std::uint32_t j = 0; j <= ny; ++j) {
    for (std::uint32_t i = 0; i <= nx; ++i) {
      const double u = static_cast<double>(i) / nx, v = static_cast<double>(j) / ny;
      data.vertices.emplace_back((2.0 * u - 1.0) * half_x_m, (2.0 * v - 1.0) * half_y_m, z_m);
      data.uvs.emplace_back(u, v);
    }
  }
  auto at = [nx](std::uint32_t i, std::uint32_t j) { return j * (nx + 1) + i; };
  for (std::uint32_t j = 0; j < ny; ++j) {
    for (std::uint32_t i = 0; i < nx; ++i) {
      data.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      data.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return Mesh::build_nonrt(std::move(data));
}

}  // namespace sandpaper::shapes

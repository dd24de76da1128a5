#pragma once
// Meshes whose exact shape is known in closed form, for scenes, tests and benches. All with UVs;
// the seams and poles repeat vertices at bit-identical positions so that the surface is closed.
#include <cstdint>

#include <glm/vec3.hpp>

#include "sandpaper/shapes/mesh.hpp"

namespace sandpaper::shapes {

// A UV sphere of radius_m about center_m: n_lon segments round (>= 3), n_lat bands pole to pole
// (>= 2); 2 n_lon (n_lat - 1) triangles. u = longitude / 2 pi, v = polar angle / pi. Its facets sag
// at most radius (1 - cos(pi / n_lon) cos(pi / (2 n_lat))) inside the sphere. Throws
// std::invalid_argument on too few segments or a radius that is not positive.
MeshData uv_sphere_data(double radius_m, std::uint32_t n_lon, std::uint32_t n_lat,
                        const glm::dvec3& center_m = glm::dvec3{0.0});
Mesh uv_sphere(double radius_m, std::uint32_t n_lon, std::uint32_t n_lat, const glm::dvec3& center_m = glm::dvec3{0.0});

// An axis-aligned box from its centre and half extents (m, each > 0): 6 faces of 2 triangles, each
// face with its own 4 vertices and UVs 0..1. inward = true winds the faces to be felt from inside
// (a room's walls), which makes every edge and corner concave. Throws std::invalid_argument.
Mesh box(const glm::dvec3& center_m, const glm::dvec3& half_extents_m, bool inward = false);

// The plane z = z_m facing +z, over [-half_x, half_x] x [-half_y, half_y] (m), as an nx x ny grid
// of squares split in two (nx, ny >= 1); u = (x + half_x) / (2 half_x), v likewise. Throws
// std::invalid_argument.
Mesh plane(double half_x_m, double half_y_m, std::uint32_t nx = 1, std::uint32_t ny = 1, double z_m = 0.0);

}  // namespace sandpaper::shapes

#pragma once
// Sampled force tables: gratings (thesis 3.5.2) and height-field gradients (3.4, EQ 12-13). The
// evaluator checked the tables' shapes before the first tick, so these index without bounds checks.
#include <glm/vec2.hpp>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::runtime::tables {

// Linear interpolation along the grating normal, wrapping every period. NaN if the position is too
// far out for the period to resolve.
glm::dvec2 grating_force(const schema::GratingTerm& grating, glm::dvec2 p) noexcept;

// Bilinear interpolation of the gradient grid; zero outside a non-repeating grid.
glm::dvec2 height_field_force(const schema::HeightFieldTerm& field, glm::dvec2 p) noexcept;

// Sample-and-hold, as the thesis' joystick read its tables (Appendix B 2.1: "Arrays are sampled at a
// resolution of one screen pixel per array item"): the nearest sample, held until the hand reaches
// the next one. Same wrapping, edges and NaN rules as the interpolating versions.
glm::dvec2 grating_force_held(const schema::GratingTerm& grating, glm::dvec2 p) noexcept;
glm::dvec2 height_field_force_held(const schema::HeightFieldTerm& field, glm::dvec2 p) noexcept;

}  // namespace sandpaper::runtime::tables

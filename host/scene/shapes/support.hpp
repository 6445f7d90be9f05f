#pragma once
// What the host files of the kinds of primitive (host/scene/shapes/<name>.cpp) share
// when they flatten a primitive for the kernel and bound it for the grid: the box,
// the rounding of their numbers to the kernel's floats, and the checks that keep a
// non-finite number out of the grid.
#include <initializer_list>

#include <glm/vec3.hpp>

#include "kernel/types.hpp"

namespace vkrt {

// An axis-aligned box, lo <= hi on each axis.
struct Aabb {
    glm::dvec3 lo{0.0};
    glm::dvec3 hi{0.0};
};

// A texel of a kernel record: xyz and w rounded to float.
kernel::vec4 to_vec4(const glm::dvec3& v, double w = 0.0);
// The xyz of a kernel record's texel, exactly.
glm::dvec3 to_dvec3(const kernel::vec4& v);

// The loaders reject non-finite input; these guard the grid's casts to cell indices,
// which are undefined for NaN and infinity, against any other caller: each throws
// std::invalid_argument ("grid: a <kind> has a non-finite coordinate"). glm::min and
// max drop a NaN operand, so a box built from them checks its input first
// (require_finite); every box checks its corners (finite_or_throw).
void require_finite(std::initializer_list<kernel::vec4> values, const char* kind);
Aabb finite_or_throw(const Aabb& box, const char* kind);

// The half-extents of a disc of `radius` perpendicular to `normal` (any length; a
// zero normal, which the loaders refuse, gets the box of the sphere around the disc):
// on axis a the disc reaches radius * sqrt(1 - n_a^2) from its centre, n the unit normal.
glm::dvec3 disc_extent(const glm::dvec3& normal, double radius);

}  // namespace vkrt

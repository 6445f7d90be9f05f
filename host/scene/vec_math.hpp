#pragma once
// Double-precision vector helpers for validating and preparing scene input. Values
// from a file can be tiny (1e-300) as well as large: glm::length would square them
// into underflow (0) or overflow (inf), so lengths scale by the largest component.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace vkrt {

inline bool is_nonzero(const glm::dvec3& v) { return v.x != 0.0 || v.y != 0.0 || v.z != 0.0; }

inline double max_abs(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// The unit vector along v, exact in direction for any finite non-zero v.
inline glm::dvec3 robust_normalize(const glm::dvec3& v) { return glm::normalize(v / max_abs(v)); }

// Two directions count as parallel when the sine of the angle between them is
// below this: such a camera basis or triangle has no usable orientation in the
// kernel's single precision, however exactly the file states it.
inline constexpr double kParallelSine = 1e-9;

// True when a or b is zero, or the sine of the angle between them is at most `sine`.
inline bool parallel_or_zero(const glm::dvec3& a, const glm::dvec3& b, double sine) {
    if (!is_nonzero(a) || !is_nonzero(b)) return true;
    return glm::length(glm::cross(robust_normalize(a), robust_normalize(b))) <= sine;
}

}  // namespace vkrt

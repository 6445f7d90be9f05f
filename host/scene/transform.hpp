#pragma once
// The "transform" object of the scene format (docs/scene-format.md): scale, then
// rotate about an axis, then translate. Kept apart from any one object type so that
// every kind of geometry placed from a file (meshes, generated surfaces) moves the
// same way.
#include <optional>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "scene/json_reader.hpp"
#include "scene/vec_math.hpp"

namespace vkrt {

struct Transform {
    glm::dmat3 linear{1.0};     // rotation * scale
    glm::dvec3 translate{0.0};
    // A positive multiple of the inverse transpose of `linear`: normals are
    // renormalized after it, so any positive factor will do, and one that keeps
    // its entries at most 1 cannot overflow for the tiniest allowed scale.
    glm::dmat3 normal_matrix{1.0};
    // The determinant is negative (an odd number of negative scale factors): the
    // image of a triangle is seen from its back, so callers swap two corners to
    // keep the front face on the same side of the surface.
    bool mirrors = false;

    glm::dvec3 apply_point(const glm::dvec3& p) const { return linear * p + translate; }
    // `n` must be non-zero; the result is unit length.
    glm::dvec3 apply_normal(const glm::dvec3& n) const { return robust_normalize(normal_matrix * robust_normalize(n)); }
};

// Reads {"scale": s or [x, y, z], "rotate": [[ax, ay, az], degrees], "translate":
// [x, y, z]}, every field optional. Fails at the offending field on a zero scale
// factor or a zero rotation axis.
Transform read_transform(const json::Node& n);

// Any invertible linear map and a translation (a glTF node's matrix), with the
// normal matrix from its cofactors; nothing when the map flattens space
// (determinant 0).
std::optional<Transform> affine_transform(const glm::dmat3& linear, const glm::dvec3& translate);

// The rotation by `degrees` about `axis` (any non-zero length), right-handed.
// Multiples of 90 degrees are exact (cos 90 is 0, not 6e-17), so a model turned a
// quarter keeps its axis-aligned faces exactly axis-aligned.
glm::dmat3 rotation(const glm::dvec3& axis, double degrees);

}  // namespace vkrt

#pragma once
// EXT_mesh_gpu_instancing (Khronos glTF registry, vendor extension): a node whose
// mesh is drawn once per instance, each instance placed by its own translation,
// rotation and scale before the node's transform.
#include <optional>
#include <vector>

#include <glm/mat4x4.hpp>

#include "scene/gltf_accessor.hpp"

namespace tinygltf {
class Model;
class Value;
}  // namespace tinygltf

namespace vkrt::gltf {

// T * R * S: a node's (or an instance's) translation `t`, rotation by the quaternion
// `q` = (x, y, z, w), normalized here, and scale `s` (glTF 2.0, 3.5.3); none when q
// is zero or not finite.
std::optional<glm::dmat4> compose_trs(const glm::dvec3& t, const glm::dvec4& q, const glm::dvec3& s);

// The instances' local matrices T * R * S, from the node's extension object
// `extension`. TRANSLATION and SCALE are VEC3 (plain integers too where the file
// uses KHR_mesh_quantization, `quantized`), ROTATION a VEC4 unit quaternion (x, y,
// z, w) of floats or normalized integers; an attribute left out is the identity.
// At least one must be given, and all with the same count; a zero quaternion or
// anything not finite refuses the file, naming the instance (a scale of zero is
// refused where the instance is placed, as a node's is).
// Attributes of the application's own ("_ID" and the like) are ignored.
std::vector<glm::dmat4> read_gpu_instances(const tinygltf::Model& model, const tinygltf::Value& extension,
                                           const Origin& origin, bool quantized);

}  // namespace vkrt::gltf

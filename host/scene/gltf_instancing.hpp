#pragma once
// EXT_mesh_gpu_instancing (Khronos glTF registry, vendor extension): a node whose
// mesh is drawn once per instance, each instance placed by its own translation,
// rotation and scale before the node's transform.
#include <vector>

#include <glm/mat4x4.hpp>

#include "scene/gltf_accessor.hpp"

namespace tinygltf {
class Model;
class Value;
}  // namespace tinygltf

namespace vkrt::gltf {

// The instances' local matrices T * R * S, from the node's extension object
// `extension`. TRANSLATION and SCALE are VEC3 (plain integers too where the file
// uses KHR_mesh_quantization, `quantized`), ROTATION a VEC4 unit quaternion (x, y,
// z, w) of floats or normalized integers; an attribute left out is the identity.
// At least one must be given, and all with the same count; a zero quaternion, a
// scale of zero or anything not finite refuses the file, naming the instance.
// Attributes of the application's own ("_ID" and the like) are ignored.
std::vector<glm::dmat4> read_gpu_instances(const tinygltf::Model& model, const tinygltf::Value& extension,
                                           const Origin& origin, bool quantized);

}  // namespace vkrt::gltf

#pragma once
// KHR_draco_mesh_compression: a primitive's attributes and indices held as one
// Draco stream in a buffer view, decoded with libdraco into plain buffers, buffer
// views and accessors that the loader then reads with every check a plain file
// gets (gltf_accessor.hpp).
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace tinygltf {
class Model;
}

namespace vkrt::gltf {

struct DracoPrimitive {
    std::size_t mesh = 0;
    std::size_t primitive = 0;
    int buffer_view = -1;                                 // the Draco stream
    std::vector<std::pair<std::string, int>> attributes;  // glTF attribute -> the stream's unique attribute id
    int indices = -1;  // the primitive's indices accessor, taken out of the JSON tinygltf reads; -1: none
};

// The file's Draco primitives, read from its JSON `root`. Their indices are taken
// out of `root`: tinygltf 2.7 refuses an indices accessor without a buffer view,
// which is how a Draco primitive's usually comes. Throws SceneError naming the
// element when an extension object is malformed.
std::vector<DracoPrimitive> take_draco_primitives(nlohmann::json& root, const std::string& file);

// Each primitive's stream decoded; its attributes and indices then refer to new
// accessors of the decoded values (indices as UNSIGNED_INT, attributes in their
// accessors' own types). Throws SceneError naming the file and the element when a
// stream cannot be decoded or does not match its accessors.
void decode_draco(tinygltf::Model& model, const std::vector<DracoPrimitive>& primitives, const std::string& file);

}  // namespace vkrt::gltf

#pragma once
// EXT_meshopt_compression: buffer views whose data is stored compressed elsewhere
// (modes ATTRIBUTES, TRIANGLES and INDICES; filters OCTAHEDRAL, QUATERNION and
// EXPONENTIAL), decoded with libmeshoptimizer into a buffer of their own. The
// extension's fallback buffers, which often hold no data, are not loaded.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace tinygltf {
class Model;
}

namespace vkrt::gltf {

struct MeshoptView {
    enum class Mode : std::uint8_t { Attributes, Triangles, Indices };
    enum class Filter : std::uint8_t { None, Octahedral, Quaternion, Exponential };
    std::size_t view = 0;  // bufferViews[view]
    std::size_t buffer = 0;  // where the compressed bytes are
    std::size_t byte_offset = 0;
    std::size_t byte_length = 0;
    std::size_t byte_stride = 0;  // of the decoded elements
    std::size_t count = 0;
    Mode mode = Mode::Attributes;
    Filter filter = Filter::None;
};

struct MeshoptViews {
    std::vector<MeshoptView> views;
    // Fallback buffers: given to tinygltf as one byte, then emptied.
    std::vector<std::size_t> placeholders;
};

// The compressed views of the file's JSON `root`, each checked against the
// extension's rules. Fallback buffers (marked so, or without data and referred to
// by compressed views only) are replaced in `root` by a one-byte data URI, since
// tinygltf 2.7 would refuse them or read them from the .glb's binary chunk.
// Throws SceneError naming the element when an extension object is malformed.
MeshoptViews take_meshopt_views(nlohmann::json& root, bool binary, const std::string& file);

// Each view decoded into a buffer of its own, which it then refers to. Throws
// SceneError naming the file and the view when its data cannot be decoded.
void decode_meshopt(tinygltf::Model& model, const MeshoptViews& views, const std::string& file);

}  // namespace vkrt::gltf

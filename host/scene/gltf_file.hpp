#pragma once
// A glTF file made ready for tinygltf 2.7 (glTF 2.0 specification, 3.1 and 4.4).
// Its JSON (the .gltf text, or a .glb's JSON chunk) is read here first, so that an
// extension the file requires and vkrt does not read is refused by name before
// anything else is said about the file. What tinygltf cannot take from a
// compressed file is set aside in that JSON and put back, decoded, once tinygltf
// has read the rest: KHR_draco_mesh_compression primitives (gltf_draco.hpp) and
// EXT_meshopt_compression buffer views (gltf_meshopt.hpp).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "scene/gltf_draco.hpp"
#include "scene/gltf_meshopt.hpp"

namespace tinygltf {
class Model;
}

namespace vkrt::gltf {

// Whether vkrt reads the extension (docs/gltf.md, "What is read").
bool reads_extension(std::string_view name);

struct PreparedFile {
    bool binary = false;               // a .glb, told by its first bytes whatever the file's name
    std::vector<unsigned char> bytes;  // the file, its JSON prepared; as it is when that JSON does not parse
    std::vector<DracoPrimitive> draco;
    MeshoptViews meshopt;
};

// Reads the file. Throws SceneError naming the file when it cannot be read, and
// naming the first extension of its extensionsRequired that vkrt does not read.
// JSON that does not parse is left for tinygltf to say why.
PreparedFile prepare_file(const std::filesystem::path& file);

// Puts back, decoded, what prepare_file set aside, into the model tinygltf read
// from `prepared.bytes`: the meshopt buffer views, then the Draco primitives
// (whose stream may lie in such a view).
void decode_set_aside(tinygltf::Model& model, const PreparedFile& prepared, const std::string& file);

}  // namespace vkrt::gltf

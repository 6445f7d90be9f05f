#include "loader_input.hpp"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "scene/json_scene_loader.hpp"
#include "scene/load_scene.hpp"
#include "scene/scene_error.hpp"

namespace vkrt::fuzz {
namespace {

namespace fs = std::filesystem;

// An open box in two materials, one face with file normals (after
// scenes/models/colour_box.obj): what inputs that name mesh.obj or mesh.mtl find.
constexpr std::string_view kMeshObj = R"(mtllib mesh.mtl
v -0.5 0 -0.5
v 0.5 0 -0.5
v 0.5 0 0.5
v -0.5 0 0.5
v -0.5 1 -0.5
v 0.5 1 -0.5
v 0.5 1 0.5
v -0.5 1 0.5
vn 0 1 0
usemtl red
f 1 5 6 2
f 4 3 7 8
usemtl glazed
f 1 4 8 5
f 2//1 6//1 7//1 3//1
f 5 8 7 6
)";
constexpr std::string_view kMeshMtl = R"(newmtl red
Kd 0.8 0.12 0.1
newmtl glazed
Kd 0.15 0.6 0.2
Ks 0.5 0.5 0.5
Ns 60
)";

// The OBJ whose library the MTL input is; its face asks for the first material of
// the seeds, so that a valid library loads whole.
constexpr std::string_view kMtlUserObj = R"(mtllib input.mtl
v 0 0 0
v 1 0 0
v 0 1 0
usemtl red
f 1 2 3
)";

// An OBJ reaches the loader as a scene's mesh object does, twice: with the scene's
// material and smooth normals (geometry only; mtllib lines are not followed), then
// with the file's own materials. Both paths of read_mesh, and add_mesh after them.
constexpr std::string_view kSceneHead =
    R"({"camera": {"eye": [0, 1, 4], "look_at": [0, 0, 0], "width": 8, "height": 6},
 "materials": {"grey": {"diffuse": [0.5, 0.5, 0.5]}},
 "objects": [)";

// The buffer a .gltf input may name as "mesh.bin": an octahedron's 6 positions,
// their 6 normals (the same unit vectors) and 24 unsigned short indices, 192 bytes
// (the layout of tests/scene/gltf_loader_test.cpp).
std::string octahedron_buffer() {
    const float p[18] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    const std::uint16_t i[24] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    std::string bytes(192, '\0');
    std::memcpy(bytes.data(), p, 72);
    std::memcpy(bytes.data() + 72, p, 72);
    std::memcpy(bytes.data() + 144, i, 48);
    return bytes;
}

// Fuzz inputs are bytes; a failed write is the harness's problem, not a finding
// in the loader, so it is a std::runtime_error that no caller catches.
void write_file(const fs::path& file, std::string_view bytes) {
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "wb"), &std::fclose);
    if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f.get()) != bytes.size() || std::fflush(f.get()) != 0) {
        throw std::runtime_error("fuzz: cannot write " + file.string());
    }
}

void load_mesh_object(const fs::path& dir, std::string_view object) {
    parse_json_scene(fmt::format("{}{}]}}", kSceneHead, object), dir / "scene.json");
}

}  // namespace

std::string_view loader_name(Loader loader) {
    switch (loader) {
    case Loader::Json: return "json";
    case Loader::Nff: return "nff";
    case Loader::Obj: return "obj";
    case Loader::Mtl: return "mtl";
    case Loader::Gltf: return "gltf";
    }
    return "?";
}

Scratch::Scratch(fs::path dir) : dir_(std::move(dir)) {
    fs::create_directories(dir_);
    write_file(dir_ / "mesh.obj", kMeshObj);
    write_file(dir_ / "mesh.mtl", kMeshMtl);
    write_file(dir_ / "mtl_user.obj", kMtlUserObj);
    write_file(dir_ / "mesh.bin", octahedron_buffer());
}

std::optional<std::string> Scratch::load(Loader loader, std::string_view bytes) const {
    try {
        switch (loader) {
        case Loader::Json:
            // In memory, as load_json_scene does after reading the file; mesh
            // paths are relative to dir_.
            parse_json_scene(std::string(bytes), dir_ / "input.json");
            break;
        case Loader::Nff:
            write_file(dir_ / "input.nff", bytes);
            load_scene(dir_ / "input.nff");
            break;
        case Loader::Obj:
            write_file(dir_ / "input.obj", bytes);
            load_mesh_object(dir_, R"({"type": "mesh", "file": "input.obj", "material": "grey", "smooth": true})");
            load_mesh_object(dir_, R"({"type": "mesh", "file": "input.obj"})");
            break;
        case Loader::Mtl:
            write_file(dir_ / "input.mtl", bytes);
            load_mesh_object(dir_, R"({"type": "mesh", "file": "mtl_user.obj"})");
            break;
        case Loader::Gltf: {
            const fs::path file = dir_ / (bytes.substr(0, 4) == "glTF" ? "input.glb" : "input.gltf");
            write_file(file, bytes);
            load_scene(file);
            break;
        }
        }
    } catch (const SceneError& e) {
        return e.what();
    }
    return std::nullopt;
}

}  // namespace vkrt::fuzz

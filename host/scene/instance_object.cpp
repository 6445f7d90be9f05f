#include "scene/instance_object.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "scene/gltf_loader.hpp"
#include "scene/indexed_mesh.hpp"
#include "scene/limits.hpp"
#include "scene/obj_mesh.hpp"
#include "scene/scene_error.hpp"
#include "scene/transform.hpp"

namespace vkrt {
namespace {

// Thrown when the copies would hold too many triangles, out of add_gltf (whose
// errors are otherwise the file's own, reported at the object's "file").
struct TooManyTriangles {
    std::uint64_t triangles;
};

void check_triangles(std::uint64_t placements, std::uint64_t triangles) {
    if (placements * triangles > limits::kMaxInstancedTriangles) throw TooManyTriangles{placements * triangles};
}

// Each placement `t` after the object's own transform `own`.
std::vector<Transform> placements(const std::vector<json::Node>& transforms, const std::optional<Transform>& own) {
    std::vector<Transform> out;
    out.reserve(transforms.size());
    for (const json::Node& node : transforms) {
        const Transform t = read_transform(node);
        if (!own) {
            out.push_back(t);
            continue;
        }
        const std::optional<Transform> both =
            affine_transform(t.linear * own->linear, t.linear * own->translate + t.translate);
        if (!both) node.fail("after the object's own \"transform\", this one flattens it (determinant 0)");
        out.push_back(*both);
    }
    return out;
}

// The OBJ mesh placed by each transform: as a "mesh" object with that transform,
// but read once, and its skipped triangles said in one warning.
void place_mesh_object(const json::Node& object, const std::vector<json::Node>& transforms,
                       const std::vector<Transform>& at, const MaterialLookup& material, Scene& scene) {
    const MeshObject mesh = read_mesh_object(object, material, scene);
    check_triangles(at.size(), mesh.mesh.faces.size());
    std::size_t skipped = 0;
    for (std::size_t i = 0; i < at.size(); ++i) {
        skipped += place_mesh(object, mesh.mesh, at[i], transforms[i], mesh.options, scene);
    }
    warn_skipped(object, skipped, at.size() * mesh.mesh.faces.size(), scene);
    if (at.size() > 1) {
        scene.instances.meshes += 1;
        scene.instances.placements += at.size();
    }
}

}  // namespace

void read_instance(const json::Node& n, const MaterialLookup& material, Scene& scene) {
    n.allow_only({"type", "object", "transforms"});
    const json::Node object = n.required("object");
    object.expect_object();
    const json::Node type = object.required("type");
    const std::string kind = type.string();
    if (kind != "mesh" && kind != "gltf") {
        type.fail(fmt::format("an instance places a \"mesh\" or a \"gltf\" object, not {}", json::quote_user(kind)));
    }
    const json::Node list = n.required("transforms");
    const std::vector<json::Node> transforms = list.elements();
    if (transforms.empty()) list.fail("expected at least one transform");
    if (transforms.size() > limits::kMaxInstances) {
        list.fail(fmt::format("{} transforms, more than the {} an instance may have", transforms.size(),
                              limits::kMaxInstances));
    }
    const std::optional<json::Node> own_node = object.find("transform");
    const std::optional<Transform> own = own_node ? std::optional(read_transform(*own_node)) : std::nullopt;
    const std::vector<Transform> at = placements(transforms, own);
    try {
        if (kind == "mesh") {
            place_mesh_object(object, transforms, at, material, scene);
            return;
        }
        object.allow_only({"type", "file", "transform"});
        const json::Node file = object.required("file");
        const std::filesystem::path path = file.file_path();
        try {
            add_gltf(path, at, scene, [&](std::size_t triangles) { check_triangles(at.size(), triangles); });
        } catch (const SceneError& e) {
            file.fail(e.what());  // the glTF's own message after the scene's path to it
        }
    } catch (const TooManyTriangles& too_many) {
        list.fail(fmt::format("{} placements copy {} triangles, more than the {} that instances may hold (each "
                              "placement is a copy of the object's triangles)",
                              at.size(), too_many.triangles, limits::kMaxInstancedTriangles));
    }
}

}  // namespace vkrt

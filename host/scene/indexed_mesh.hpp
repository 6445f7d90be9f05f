#pragma once
// A triangle mesh with shared vertices, as OBJ files and the torus-knot generator
// produce it, and its placement into a Scene: transform, skip degenerate triangles,
// smooth normals. Vertices shared by index share their computed normal, which is
// what makes a mesh look smooth across its edges.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "scene/json_reader.hpp"
#include "scene/scene.hpp"
#include "scene/transform.hpp"

namespace vkrt {

struct IndexedMesh {
    static constexpr std::uint32_t kNoNormal = 0xFFFFFFFFu;
    static constexpr std::uint32_t kNoMaterial = 0xFFFFFFFFu;
    static constexpr std::uint32_t kNoUv = 0xFFFFFFFFu;
    static constexpr std::uint32_t kNoColor = 0xFFFFFFFFu;
    static constexpr std::uint32_t kNoTangent = 0xFFFFFFFFu;

    struct Face {
        std::array<std::uint32_t, 3> position{};                          // into positions
        std::array<std::uint32_t, 3> normal{kNoNormal, kNoNormal, kNoNormal};  // into normals
        std::uint32_t material = kNoMaterial;                             // into materials
        std::array<std::uint32_t, 3> uv{kNoUv, kNoUv, kNoUv};           // into uvs
        std::array<std::uint32_t, 3> second_uv{kNoUv, kNoUv, kNoUv};    // into second_uvs
        std::array<std::uint32_t, 3> color{kNoColor, kNoColor, kNoColor};  // into colors
        std::array<std::uint32_t, 3> tangent{kNoTangent, kNoTangent, kNoTangent};  // into tangents
    };

    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals;  // given by the source (OBJ "vn"); may be empty
    std::vector<glm::dvec2> uvs;      // texture coordinates (OBJ "vt", glTF TEXCOORD_0); may be empty
    // A second set (glTF's TEXCOORD_<n> of a material's second mapping); may be empty.
    std::vector<glm::dvec2> second_uvs;
    std::vector<glm::vec4> colors;    // linear RGBA vertex colours (glTF COLOR_0); may be empty
    // Unit tangents along +u and, in w, the bitangent's sign (glTF TANGENT); may be empty.
    std::vector<glm::dvec4> tangents;
    std::vector<Face> faces;          // front face = cross(p1 - p0, p2 - p0)
    std::vector<Material> materials;  // the source's own (OBJ "usemtl" from its MTL file); may be empty
    std::vector<std::string> material_textures;  // per material, its colour texture file (OBJ map_Kd) or ""

};

// Moves positions and normals (normals renormalized; zero ones stay zero) and, if
// the transform mirrors, swaps two corners of every face so that the front faces
// stay on the same side of the surface.
void transform_mesh(IndexedMesh& mesh, const Transform& t);

// A triangle this thin (the sine of its angle at v0 at most this) has no usable
// normal in the kernel's single precision. The same bound as the JSON loader's
// refusal of zero-area "triangle" objects.
inline constexpr double kDegenerateSine = 1e-9;

bool is_degenerate(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2);

// Per position: the sum over the non-degenerate faces around it of the face's unit
// normal weighted by the face's angle at that corner, normalized (Thürmer and
// Wüthrich 1998, "Computing vertex normals from polygonal facets"). Unlike
// weighting by area or by nothing, the result does not change when a neighbouring
// face is split in two. A position with no usable sum gets a zero vector.
std::vector<glm::dvec3> angle_weighted_normals(const IndexedMesh& mesh);

struct MeshOptions {
    bool smooth = false;  // per-vertex normals: the mesh's own, else angle-weighted
    std::uint32_t material = 0;  // for faces without a material of their own
    // Face::material -> index into Scene::materials, where the faces have their own.
    std::vector<std::uint32_t> face_materials;
};

// The first vertex beyond json::kMaxMagnitude on some axis, if any.
std::optional<glm::dvec3> vertex_beyond_limit(const IndexedMesh& mesh);

// Appends the mesh's triangles, as they are, to scene.triangles, skipping the
// degenerate ones; returns how many it skipped.
std::size_t append_mesh(const IndexedMesh& mesh, const MeshOptions& options, Scene& scene);

// Transforms the mesh and appends its triangles to scene.triangles. Degenerate
// triangles are skipped and counted in a scene warning; a mesh left with no
// triangle at all, or moved beyond json::kMaxMagnitude, fails at `object` (the
// JSON object that made it). `transform` is the object's "transform" node, if any,
// for naming where a too-large result came from.
void add_mesh(const json::Node& object, IndexedMesh mesh, const Transform& t,
              const std::optional<json::Node>& transform, const MeshOptions& options, Scene& scene);

// add_mesh without its warning, for a mesh placed many times (an "instance"):
// returns how many triangles it skipped, which warn_skipped then reports once for
// the object's `triangles` in all.
std::size_t place_mesh(const json::Node& object, IndexedMesh mesh, const Transform& t,
                       const std::optional<json::Node>& transform, const MeshOptions& options, Scene& scene);
void warn_skipped(const json::Node& object, std::size_t skipped, std::size_t triangles, Scene& scene);

}  // namespace vkrt

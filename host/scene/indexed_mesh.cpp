#include "scene/indexed_mesh.hpp"

#include <cmath>
#include <optional>
#include <utility>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "scene/vec_math.hpp"

namespace vkrt {

using glm::dvec3;

void transform_mesh(IndexedMesh& mesh, const Transform& t) {
    for (dvec3& p : mesh.positions) p = t.apply_point(p);
    for (dvec3& n : mesh.normals) {
        if (is_nonzero(n)) n = t.apply_normal(n);
    }
    // A tangent turns with the surface (not as a normal does); a mirror flips the
    // bitangent's sign, which glTF gives as cross(n, t) w.
    for (glm::dvec4& v : mesh.tangents) {
        const dvec3 x(v);
        if (is_nonzero(x)) v = glm::dvec4(robust_normalize(t.linear * robust_normalize(x)), t.mirrors ? -v.w : v.w);
    }
    if (t.mirrors) {
        for (IndexedMesh::Face& f : mesh.faces) {
            std::swap(f.position[1], f.position[2]);
            std::swap(f.normal[1], f.normal[2]);
            std::swap(f.uv[1], f.uv[2]);
            std::swap(f.second_uv[1], f.second_uv[2]);
            std::swap(f.color[1], f.color[2]);
            std::swap(f.tangent[1], f.tangent[2]);
        }
    }
}

bool is_degenerate(const dvec3& p0, const dvec3& p1, const dvec3& p2) {
    return parallel_or_zero(p1 - p0, p2 - p0, kDegenerateSine);
}

namespace {

// The unit normal of a non-degenerate triangle. Edges are normalized first so that
// the cross product neither overflows for huge coordinates nor underflows for tiny.
dvec3 face_normal(const dvec3& p0, const dvec3& p1, const dvec3& p2) {
    return robust_normalize(glm::cross(robust_normalize(p1 - p0), robust_normalize(p2 - p0)));
}

// The angle at corner a of the triangle (a, b, c), in radians. atan2 of the sine
// and cosine parts stays accurate near 0 and pi, where acos of a dot product does not.
double corner_angle(const dvec3& a, const dvec3& b, const dvec3& c) {
    const dvec3 u = robust_normalize(b - a);
    const dvec3 v = robust_normalize(c - a);
    return std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v));
}

}  // namespace

std::vector<dvec3> angle_weighted_normals(const IndexedMesh& mesh) {
    std::vector<dvec3> sum(mesh.positions.size(), dvec3(0.0));
    std::vector<double> weight(mesh.positions.size(), 0.0);
    for (const IndexedMesh::Face& f : mesh.faces) {
        const dvec3 p[3] = {mesh.positions[f.position[0]], mesh.positions[f.position[1]],
                            mesh.positions[f.position[2]]};
        if (is_degenerate(p[0], p[1], p[2])) continue;
        const dvec3 n = face_normal(p[0], p[1], p[2]);
        for (int k = 0; k < 3; ++k) {
            const double angle = corner_angle(p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
            sum[f.position[k]] += angle * n;
            weight[f.position[k]] += angle;
        }
    }
    std::vector<dvec3> out(sum.size(), dvec3(0.0));
    for (std::size_t i = 0; i < sum.size(); ++i) {
        // Faces that nearly cancel (a vertex on a fold that turns back on itself)
        // leave a sum whose direction is rounding noise: no normal is better.
        if (glm::length(sum[i]) > 1e-9 * weight[i]) out[i] = glm::normalize(sum[i]);
    }
    return out;
}

namespace {

// The normals a face is shaded with: the mesh's own when it gives a usable one at
// every corner, else the computed ones, else (where even those are missing) the
// face's own, which makes that corner flat.
std::array<dvec3, 3> corner_normals(const IndexedMesh& mesh, const IndexedMesh::Face& f,
                                    const std::vector<dvec3>& computed, const dvec3 p[3]) {
    std::array<dvec3, 3> out{};
    bool given = true;
    for (int k = 0; k < 3; ++k) {
        given = given && f.normal[k] != IndexedMesh::kNoNormal && is_nonzero(mesh.normals[f.normal[k]]);
    }
    for (int k = 0; k < 3; ++k) {
        if (given) {
            out[k] = mesh.normals[f.normal[k]];
        } else if (is_nonzero(computed[f.position[k]])) {
            out[k] = computed[f.position[k]];
        } else {
            out[k] = face_normal(p[0], p[1], p[2]);
        }
    }
    return out;
}

bool needs_computed_normals(const IndexedMesh& mesh) {
    for (const IndexedMesh::Face& f : mesh.faces) {
        for (std::uint32_t n : f.normal) {
            if (n == IndexedMesh::kNoNormal || !is_nonzero(mesh.normals[n])) return true;
        }
    }
    return false;
}

// A face's tangents, in float, each w +-1; none when a corner's is zero (the kernel
// then derives the frame from the texture coordinates).
std::optional<std::array<glm::vec4, 3>> given_tangents(const IndexedMesh& mesh, const IndexedMesh::Face& f) {
    std::array<glm::vec4, 3> out{};
    for (int k = 0; k < 3; ++k) {
        const glm::dvec4& v = mesh.tangents[f.tangent[k]];
        if (!is_nonzero(dvec3(v))) return std::nullopt;
        out[k] = glm::vec4(glm::vec3(dvec3(v)), v.w < 0.0 ? -1.0f : 1.0f);
    }
    return out;
}

}  // namespace

std::optional<dvec3> vertex_beyond_limit(const IndexedMesh& mesh) {
    for (const dvec3& p : mesh.positions) {
        if (max_abs(p) > json::kMaxMagnitude) return p;
    }
    return std::nullopt;
}

std::size_t append_mesh(const IndexedMesh& mesh, const MeshOptions& options, Scene& scene) {
    std::vector<dvec3> computed;
    if (options.smooth && needs_computed_normals(mesh)) computed = angle_weighted_normals(mesh);

    std::size_t skipped = 0;
    for (const IndexedMesh::Face& f : mesh.faces) {
        const dvec3 p[3] = {mesh.positions[f.position[0]], mesh.positions[f.position[1]],
                            mesh.positions[f.position[2]]};
        if (is_degenerate(p[0], p[1], p[2])) {
            ++skipped;
            continue;
        }
        const std::uint32_t material =
            f.material == IndexedMesh::kNoMaterial ? options.material : options.face_materials.at(f.material);
        Triangle tri{{p[0], p[1], p[2]}, std::nullopt, material};
        if (options.smooth) tri.normals = corner_normals(mesh, f, computed, p);
        if (f.uv[0] != IndexedMesh::kNoUv) tri.uvs = {mesh.uvs[f.uv[0]], mesh.uvs[f.uv[1]], mesh.uvs[f.uv[2]]};
        if (f.second_uv[0] != IndexedMesh::kNoUv) {
            tri.second_uvs = {mesh.second_uvs[f.second_uv[0]], mesh.second_uvs[f.second_uv[1]],
                              mesh.second_uvs[f.second_uv[2]]};
        }
        if (f.tangent[0] != IndexedMesh::kNoTangent) tri.tangents = given_tangents(mesh, f);
        if (f.color[0] != IndexedMesh::kNoColor) {
            tri.colors = {mesh.colors[f.color[0]], mesh.colors[f.color[1]], mesh.colors[f.color[2]]};
        }
        scene.triangles.push_back(tri);
    }
    return skipped;
}

std::size_t place_mesh(const json::Node& object, IndexedMesh mesh, const Transform& t,
                       const std::optional<json::Node>& transform, const MeshOptions& options, Scene& scene) {
    transform_mesh(mesh, t);
    if (const std::optional<dvec3> p = vertex_beyond_limit(mesh)) {
        const std::string message =
            fmt::format("the {}mesh has a vertex at {}, beyond the largest coordinate allowed ({})",
                        transform ? "transformed " : "", json::format_vec3(*p), json::kMaxMagnitude);
        if (transform) transform->fail(message);
        object.fail(message);
    }
    const std::size_t skipped = append_mesh(mesh, options, scene);
    if (skipped == mesh.faces.size()) {
        object.fail(fmt::format("all {} triangles of the mesh have zero area{}", skipped,
                                transform ? " after the transform" : ""));
    }
    return skipped;
}

void warn_skipped(const json::Node& object, std::size_t skipped, std::size_t triangles, Scene& scene) {
    if (skipped == 0) return;
    scene.warnings.push_back(
        fmt::format("{}: {}: skipped {} of {} triangles that have zero area (coinciding vertices or all on one line)",
                    object.file(), object.path(), skipped, triangles));
}

void add_mesh(const json::Node& object, IndexedMesh mesh, const Transform& t,
              const std::optional<json::Node>& transform, const MeshOptions& options, Scene& scene) {
    const std::size_t triangles = mesh.faces.size();
    warn_skipped(object, place_mesh(object, std::move(mesh), t, transform, options, scene), triangles, scene);
}

}  // namespace vkrt

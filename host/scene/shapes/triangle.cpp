#include "scene/shapes/triangle.hpp"

#include <cmath>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "scene/vec_math.hpp"

namespace vkrt {
namespace {

// Which shape a Triangle record holds (kernel::Triangle meta.z): a parallelogram with
// perpendicular edges is a rectangle, which the kernel samples by solid angle when it
// emits (kernel/emitters.glsl).
std::uint32_t shape_of(const Triangle& t) {
    if (!t.parallelogram) return kernel::SHAPE_TRIANGLE;
    const glm::dvec3 e1 = t.vertices[1] - t.vertices[0];
    const glm::dvec3 e2 = t.vertices[2] - t.vertices[1];
    const bool perpendicular = std::abs(glm::dot(e1, e2)) <= 1e-6 * glm::length(e1) * glm::length(e2);
    return perpendicular ? kernel::SHAPE_RECTANGLE : kernel::SHAPE_PARALLELOGRAM;
}

}  // namespace

std::array<glm::dvec2, 3> texture_corners(const Triangle& t) {
    if (t.uvs) return *t.uvs;
    return {glm::dvec2(0, 0), glm::dvec2(1, 0), t.parallelogram ? glm::dvec2(1, 1) : glm::dvec2(0, 1)};
}

void read_shape(const json::Node& n, ShapeReader& reader, std::vector<Triangle>& out) {
    n.allow_only({"vertices", "normals", "colors", "tangents", "material", "type"});
    Triangle t;
    const json::Node vertices = n.required("vertices");
    const auto v = vertices.elements(3, "an array of 3 points");
    for (int i = 0; i < 3; ++i) t.vertices[i] = v[i].vec3();
    std::optional<std::array<glm::dvec3, 3>> normals;
    std::optional<json::Node> first_zero;  // the first zero normal's place
    if (auto given = n.find("normals")) {
        const auto e = given->elements(3, "an array of 3 vectors");
        normals.emplace();
        for (int i = 0; i < 3; ++i) {
            (*normals)[i] = e[i].vec3();
            if (!first_zero && !is_nonzero((*normals)[i])) first_zero = e[i];
        }
    }
    if (auto given = n.find("colors")) {
        const auto e = given->elements(3, "an array of 3 colours");
        t.colors.emplace();
        for (int i = 0; i < 3; ++i) (*t.colors)[i] = glm::vec4(glm::vec3(e[i].unit_color()), 1.0f);
    }
    if (auto given = n.find("tangents")) {
        const auto e = given->elements(3, "an array of 3 tangents");
        t.tangents.emplace();
        for (int i = 0; i < 3; ++i) {
            const auto x = e[i].elements(4, "a tangent [x, y, z, w]: a direction and the bitangent's sign, 1 or -1");
            const glm::dvec3 d(x[0].number(), x[1].number(), x[2].number());
            const double w = x[3].number();
            if (!is_nonzero(d)) e[i].fail("expected a non-zero tangent");
            if (w != 1.0 && w != -1.0) x[3].fail(fmt::format("expected 1 or -1 (the bitangent's sign), got {}", w));
            (*t.tangents)[i] = glm::vec4(glm::vec3(robust_normalize(d)), float(w));
        }
    }
    t.material = reader.material_of(n);
    if (parallel_or_zero(t.vertices[1] - t.vertices[0], t.vertices[2] - t.vertices[0], kParallelSine)) {
        if (reader.zero_area++ == 0) reader.first_zero_area = vertices.path();
        return;  // its normals do not count: it is not rendered
    }
    if (first_zero && reader.zero_normals++ == 0) reader.first_zero_normal = first_zero->path();
    if (normals) {
        const glm::dvec3 face =
            robust_normalize(glm::cross(t.vertices[1] - t.vertices[0], t.vertices[2] - t.vertices[0]));
        // Normalized here so the kernel can interpolate without renormalizing
        // inputs; the file may give any length.
        for (glm::dvec3& x : *normals) x = is_nonzero(x) ? robust_normalize(x) : face;
        t.normals = normals;
    }
    out.push_back(t);
}

kernel::Triangle flatten(const Triangle& t, const glm::dvec3& origin) {
    kernel::Triangle out{};
    out.p0 = to_vec4(t.vertices[0] - origin);
    out.p1 = to_vec4(t.vertices[1] - origin);
    out.p2 = to_vec4(t.vertices[2] - origin);
    if (t.normals) {
        out.n0 = to_vec4((*t.normals)[0]);
        out.n1 = to_vec4((*t.normals)[1]);
        out.n2 = to_vec4((*t.normals)[2]);
    }
    // Texture coordinates in the w lanes (kernel::Triangle).
    const std::array<glm::dvec2, 3> uv = texture_corners(t);
    out.p0.w = float(uv[0].x);
    out.p1.w = float(uv[0].y);
    out.p2.w = float(uv[1].x);
    out.n0.w = float(uv[1].y);
    out.n1.w = float(uv[2].x);
    out.n2.w = float(uv[2].y);
    const std::uint32_t flags = (t.normals ? kernel::TRIANGLE_NORMALS : 0u) | (t.colors ? kernel::TRIANGLE_COLORS : 0u) |
                                (t.tangents ? kernel::TRIANGLE_TANGENTS : 0u);
    out.meta = kernel::uvec4(t.material, flags, shape_of(t), 0u);
    return out;
}

std::uint32_t emitter_parts(const Triangle&) { return 1; }

double emitter_area(const Triangle& t, std::uint32_t) {
    const glm::dvec3 c = glm::cross(t.vertices[1] - t.vertices[0], t.vertices[2] - t.vertices[0]);
    return (t.parallelogram ? 1.0 : 0.5) * glm::length(c);
}

Aabb bounds(const kernel::Triangle& t) {
    const glm::dvec3 a = to_dvec3(t.p0), b = to_dvec3(t.p1), c = to_dvec3(t.p2);
    const glm::dvec3 d = t.meta.z == kernel::SHAPE_TRIANGLE ? c : to_dvec3(t.p0 + (t.p2 - t.p1));
    return finite_or_throw({glm::min(glm::min(a, b), glm::min(c, d)), glm::max(glm::max(a, b), glm::max(c, d))},
                           "triangle");
}

}  // namespace vkrt

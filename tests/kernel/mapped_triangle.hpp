#pragma once
// A triangle whose material has a normal map of one texel, and a hit on it, for
// kernel/normal_map.glsl's functions through the reference kernel
// (normal_map_test.cpp, coat_normal_test.cpp).
#include <array>
#include <cstdint>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "kernel/kernel.hpp"

namespace vkrt::test {

struct MappedTriangle {
    // Which of the material's maps the texel is: the material's own or its clear coat's.
    enum class Slot { Material, Coat };

    std::vector<kernel::Material> materials;
    std::vector<kernel::Triangle> triangles;
    // One half-float texel, scale 1.
    std::vector<kernel::Texture> records = {
        kernel::Texture(kernel::uvec4(0u, 1u, 1u, 0u), kernel::vec4(1.0f, 0.0f, 0.0f, 0.0f))};
    std::vector<std::uint32_t> words;
    kernel::Kernel k;

    // One texel of tangent-space normal `ts`, in glTF's encoding (ts + 1) / 2 (exact
    // for these values); a triangle in z = 0 facing +z with texture coordinates uv.
    MappedTriangle(kernel::vec3 ts, std::array<kernel::vec2, 3> uv, Slot slot = Slot::Material) {
        const kernel::vec3 c = (ts + 1.0f) * 0.5f;
        words = {glm::packHalf2x16(kernel::vec2(c.x, c.y)), glm::packHalf2x16(kernel::vec2(c.z, 1.0f))};
        kernel::Material m{};
        (slot == Slot::Material ? m.normal_map : m.coat_normal_map) = 1u;
        m.uv_u = kernel::vec3(1.0f, 0.0f, 0.0f);
        m.uv_v = kernel::vec3(0.0f, 1.0f, 0.0f);
        materials.push_back(m);
        kernel::Triangle t{};
        t.p0 = kernel::vec4(0.0f, 0.0f, 0.0f, uv[0].x);
        t.p1 = kernel::vec4(1.0f, 0.0f, 0.0f, uv[0].y);
        t.p2 = kernel::vec4(0.0f, 1.0f, 0.0f, uv[1].x);
        t.n0.w = uv[1].y;
        t.n1.w = uv[2].x;
        t.n2.w = uv[2].y;
        t.meta = kernel::uvec4(0u, 0u, kernel::SHAPE_TRIANGLE, 0u);
        triangles.push_back(t);
        k.materials = materials;
        k.triangles = triangles;
        k.textures = records;
        k.texture_words = words;
    }
    MappedTriangle(const MappedTriangle&) = delete;  // the kernel holds views of the arrays

    // A hit at texture coordinates (0.25, 0.25), its normal not yet mapped.
    kernel::Kernel::Hit hit() {
        kernel::Kernel::Hit h = k.no_hit();
        h.t = 1.0f;
        h.normal = h.geo_normal = kernel::vec3(0.0f, 0.0f, 1.0f);
        h.front_face = true;
        h.material = 0u;
        h.prim = kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT;
        h.uv = kernel::vec2(0.25f, 0.25f);
        return h;
    }
    // The shading normal there, seen from wo.
    kernel::vec3 normal(kernel::vec3 wo) { return k.mapped_normal(hit(), wo); }
    // The normal the material's clear coat lies on there.
    kernel::vec3 coat_normal(kernel::vec3 wo) { return k.coat_normal(hit(), wo); }
};

}  // namespace vkrt::test

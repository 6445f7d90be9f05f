// EXT_mesh_gpu_instancing (host/scene/gltf_instancing.cpp): files written here with
// one triangle and known instance attributes, placed exactly where the extension
// says; a clear refusal for each broken attribute; and gltfpack's instanced corpus
// files (scenes/gltf/variants/) holding the triangles of the files they came from.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "scene/load_scene.hpp"
#include "test_support.hpp"

namespace {

using glm::dvec3;
using vkrt::Scene;

// A glTF buffer built up attribute by attribute: each add() is one buffer view and
// one accessor over it, returning the accessor's index.
struct Buffer {
    std::string bytes;
    std::vector<std::string> views, accessors;

    int add(const void* data, std::size_t size, int component, std::size_t count, const char* type,
            bool normalized = false) {
        while (bytes.size() % 4) bytes += '\0';
        views.push_back(fmt::format(R"({{"buffer": 0, "byteOffset": {}, "byteLength": {}}})", bytes.size(), size));
        bytes.append(static_cast<const char*>(data), size);
        accessors.push_back(fmt::format(R"({{"bufferView": {}, "componentType": {}, "count": {}, "type": "{}"{}}})",
                                        views.size() - 1, component, count, type,
                                        normalized ? R"(, "normalized": true)" : ""));
        return static_cast<int>(accessors.size() - 1);
    }
    int floats(const std::vector<float>& v, std::size_t per, const char* type) {
        return add(v.data(), v.size() * sizeof(float), 5126, v.size() / per, type);
    }
};

// The triangle (0, 0, 0), (1, 0, 0), (0, 1, 0), facing +z, as accessor 0.
Buffer triangle_buffer() {
    Buffer b;
    b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, 3, "VEC3");
    return b;
}

// A .gltf whose one node places the triangle's mesh: `node` is that node's JSON
// members besides "mesh", `attributes` the extension's attributes object.
std::filesystem::path write_instanced(const std::string& name, const Buffer& b, const std::string& attributes,
                                      const std::string& node = "") {
    const std::filesystem::path dir = vkrt::test::temp_dir("gltf_instancing_" + name);
    std::ofstream(dir / "mesh.bin", std::ios::binary) << b.bytes;
    std::string views, accessors;
    for (const std::string& v : b.views) views += (views.empty() ? "" : ", ") + v;
    for (const std::string& a : b.accessors) accessors += (accessors.empty() ? "" : ", ") + a;
    const std::string json = fmt::format(
        R"({{"asset": {{"version": "2.0"}},
            "extensionsUsed": ["EXT_mesh_gpu_instancing"], "extensionsRequired": ["EXT_mesh_gpu_instancing"],
            "scene": 0, "scenes": [{{"nodes": [0]}}],
            "nodes": [{{"mesh": 0, {}"extensions": {{"EXT_mesh_gpu_instancing": {{"attributes": {}}}}}}}],
            "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
            "buffers": [{{"byteLength": {}, "uri": "mesh.bin"}}],
            "bufferViews": [{}], "accessors": [{}]}})",
        node, attributes, b.bytes.size(), views, accessors);
    std::ofstream(dir / (name + ".gltf"), std::ios::binary) << json;
    return dir / (name + ".gltf");
}

void expect_near(const dvec3& got, const dvec3& want, double tolerance = 1e-12) {
    EXPECT_NEAR(got.x, want.x, tolerance);
    EXPECT_NEAR(got.y, want.y, tolerance);
    EXPECT_NEAR(got.z, want.z, tolerance);
}

const double kHalfRoot2 = std::sqrt(0.5);

TEST(GltfInstancing, PlacesTheMeshOncePerInstanceBeforeTheNodesTransform) {
    Buffer b = triangle_buffer();
    const float h = static_cast<float>(kHalfRoot2);
    const int t = b.floats({0, 0, 0, 10, 0, 0, 0, 5, 0}, 3, "VEC3");
    const int r = b.floats({0, 0, 0, 1, 0, 0, h, h, 0, 0, 0, 1}, 4, "VEC4");  // the second a quarter turn about z
    const int s = b.floats({1, 1, 1, 1, 1, 1, 2, 3, 4}, 3, "VEC3");
    const Scene scene = vkrt::load_scene(write_instanced(
        "three", b, fmt::format(R"({{"TRANSLATION": {}, "ROTATION": {}, "SCALE": {}}})", t, r, s),
        R"("translation": [0, 0, -3], )"));
    ASSERT_EQ(scene.triangles.size(), 3u);
    const auto& v = [&](std::size_t i) { return scene.triangles[i].vertices; };
    expect_near(v(0)[0], {0, 0, -3});
    expect_near(v(0)[1], {1, 0, -3});
    expect_near(v(0)[2], {0, 1, -3});
    // The float quarter turn is one within 1e-7.
    expect_near(v(1)[0], {10, 0, -3}, 1e-6);
    expect_near(v(1)[1], {10, 1, -3}, 1e-6);
    expect_near(v(1)[2], {9, 0, -3}, 1e-6);
    expect_near(v(2)[0], {0, 5, -3});
    expect_near(v(2)[1], {2, 5, -3});
    expect_near(v(2)[2], {0, 8, -3});
}

TEST(GltfInstancing, AnAttributeLeftOutIsTheIdentity) {
    Buffer b = triangle_buffer();
    const int t = b.floats({0, 0, 0, 0, 0, 7}, 3, "VEC3");
    const Scene scene = vkrt::load_scene(write_instanced("translations", b, fmt::format(R"({{"TRANSLATION": {}, "_ID": 0}})", t)));
    ASSERT_EQ(scene.triangles.size(), 2u);
    expect_near(scene.triangles[1].vertices[1], {1, 0, 7});
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
}

TEST(GltfInstancing, ReadsRotationsAsNormalizedShorts) {
    Buffer b = triangle_buffer();
    // A quarter turn about z as gltfpack writes it: round(32767 sin 45 degrees).
    const std::vector<std::int16_t> q = {0, 0, 23170, 23170};
    const int r = b.add(q.data(), q.size() * 2, 5122, 1, "VEC4", true);
    const Scene scene = vkrt::load_scene(write_instanced("shorts", b, fmt::format(R"({{"ROTATION": {}}})", r)));
    ASSERT_EQ(scene.triangles.size(), 1u);
    // Renormalized, the quaternion is the quarter turn to within its rounding.
    expect_near(scene.triangles[0].vertices[1], {0, 1, 0}, 1e-4);
    expect_near(scene.triangles[0].vertices[2], {-1, 0, 0}, 1e-4);
}

TEST(GltfInstancing, AMirroringInstanceKeepsTheFrontFaceOutside) {
    Buffer b = triangle_buffer();
    const int s = b.floats({1, 1, 1, -1, 1, 1}, 3, "VEC3");
    const Scene scene = vkrt::load_scene(write_instanced("mirror", b, fmt::format(R"({{"SCALE": {}}})", s)));
    ASSERT_EQ(scene.triangles.size(), 2u);
    for (const auto& t : scene.triangles) {
        const dvec3 n = glm::cross(t.vertices[1] - t.vertices[0], t.vertices[2] - t.vertices[0]);
        EXPECT_GT(n.z, 0.0) << "the mirror about x leaves the triangle facing +z";
    }
}

TEST(GltfInstancing, RefusesBrokenAttributesNamingThem) {
    const auto error = [](const std::string& name, Buffer b, const std::string& attributes) {
        return vkrt::test::load_error_of(write_instanced(name, b, attributes));
    };
    const std::string prefix = "nodes[0].extensions.EXT_mesh_gpu_instancing";
    {
        Buffer b = triangle_buffer();
        const int t = b.floats({0, 0, 0, 1, 1, 1}, 3, "VEC3");
        const int s = b.floats({1, 1, 1}, 3, "VEC3");
        const std::string e = error("counts", b, fmt::format(R"({{"TRANSLATION": {}, "SCALE": {}}})", t, s));
        EXPECT_NE(e.find(prefix + ".attributes.SCALE: 1 instances, where the attributes before it have 2"),
                  std::string::npos)
            << e;
    }
    {
        Buffer b = triangle_buffer();
        const int r = b.floats({0, 0, 0, 0}, 4, "VEC4");
        const std::string e = error("zero_quaternion", b, fmt::format(R"({{"ROTATION": {}}})", r));
        EXPECT_NE(e.find(prefix + ".attributes.ROTATION: instance 0 has a zero quaternion"), std::string::npos) << e;
    }
    {
        Buffer b = triangle_buffer();
        const int s = b.floats({1, 1, 1, 1, 0, 1}, 3, "VEC3");
        const std::string e = error("zero_scale", b, fmt::format(R"({{"SCALE": {}}})", s));
        // Refused where it is placed, as a node of scale zero is.
        EXPECT_NE(e.find("nodes[0] (instance 1): the node's transform flattens its mesh (determinant 0)"),
                  std::string::npos)
            << e;
    }
    {
        const std::string e = error("none", triangle_buffer(), R"({"_ID": 0})");
        EXPECT_NE(e.find(prefix + ": no TRANSLATION, ROTATION or SCALE attribute"), std::string::npos) << e;
    }
    {
        const std::string e = error("not_an_index", triangle_buffer(), R"({"SCALE": "two"})");
        EXPECT_NE(e.find(prefix + ": attributes.SCALE is not an accessor index"), std::string::npos) << e;
    }
    {
        const std::string e = error("missing_accessor", triangle_buffer(), R"({"TRANSLATION": 9})");
        EXPECT_NE(e.find(prefix + ".attributes.TRANSLATION: accessor 9 does not exist"), std::string::npos) << e;
    }
    {
        Buffer b = triangle_buffer();
        const int t = b.floats({0, 0, 0, 1, NAN, 1}, 3, "VEC3");
        const std::string e = error("not_finite", b, fmt::format(R"({{"TRANSLATION": {}}})", t));
        EXPECT_NE(e.find(prefix + ".attributes.TRANSLATION"), std::string::npos) << e;
    }
}

TEST(GltfInstancing, RefusesMoreInstancesThanItCopies) {
    Buffer b = triangle_buffer();
    const std::vector<float> t(3 * 1'000'001, 0.0f);
    const int a = b.floats(t, 3, "VEC3");
    const std::string e = vkrt::test::load_error_of(write_instanced("too_many", b, fmt::format(R"({{"TRANSLATION": {}}})", a)));
    EXPECT_NE(e.find("nodes[0].extensions.EXT_mesh_gpu_instancing: the file's instances add up to 1000001 copies "
                     "holding 1000001 triangles"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("at most 1000000 instances"), std::string::npos) << e;
}

// The corpus files gltfpack wrote with instances hold the originals' triangles:
// the same count and the same box, to the rounding of the instances' rotations
// (normalized shorts, 1/32767).
TEST(GltfInstancing, GltfpacksInstancedFilesHoldTheOriginalsTriangles) {
    const std::filesystem::path scenes = vkrt::test::source_dir() / "scenes" / "gltf";
    for (const std::string name : {"dining_set", "radio"}) {
        const Scene original = vkrt::load_scene(scenes / "corpus" / (name + ".glb"));
        const Scene instanced = vkrt::load_scene(scenes / "variants" / (name + "_instanced.glb"));
        const auto box = [](const Scene& s) {
            dvec3 lo(1e300), hi(-1e300);
            for (const auto& t : s.triangles) {
                for (const dvec3& v : t.vertices) {
                    lo = glm::min(lo, v);
                    hi = glm::max(hi, v);
                }
            }
            return std::pair{lo, hi};
        };
        const auto [lo, hi] = box(original);
        const auto [ilo, ihi] = box(instanced);
        const double size = glm::length(hi - lo);
        expect_near(ilo, lo, 1e-4 * size);
        expect_near(ihi, hi, 1e-4 * size);
        // gltfpack drops some of the zero-area triangles the original holds (which
        // the loader skips anyway): the kept ones agree.
        EXPECT_EQ(instanced.triangles.size(), original.triangles.size()) << name;
        // The shared meshes: nodes sharing them in the original (the dining set's
        // legs and chairs 4 times each, the radio's knobs twice and feet 4 times),
        // instances in gltfpack's file, which splits the two-material chair in two.
        const bool dining = std::string(name) == "dining_set";
        EXPECT_EQ(original.instances.meshes, 2u) << name;
        EXPECT_EQ(original.instances.placements, dining ? 8u : 6u) << name;
        EXPECT_EQ(instanced.instances.meshes, dining ? 3u : 2u) << name;
        EXPECT_EQ(instanced.instances.placements, dining ? 12u : 6u) << name;
    }
}

}  // namespace

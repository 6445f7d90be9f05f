// The scene format's "instance" object (host/scene/instance_object.cpp): each
// placement is exactly the "mesh" or "gltf" object it stands for, the file is read
// once, and each mistake is refused at its field.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <fmt/format.h>

#include "scene/load_scene.hpp"
#include "test_support.hpp"

namespace {

using vkrt::Scene;

std::string models() { return (vkrt::test::source_dir() / "scenes" / "models").string(); }
std::string radio() { return (vkrt::test::source_dir() / "scenes" / "gltf" / "corpus" / "radio.glb").string(); }

// A scene of the given objects (JSON text, comma-separated) and a "clay" material.
std::string scene_text(const std::string& objects) {
    return R"({"camera": {"eye": [0, 0, 10], "look_at": [0, 0, 0]},
               "materials": {"clay": {"diffuse": [0.5, 0.5, 0.5]}},
               "objects": [)" +
           objects + "]}";
}

const char* kPlacements[] = {R"({"translate": [1, 2, 3]})", R"({"rotate": [[1, 1, 0], 30], "scale": [1, 2, 0.5]})",
                             R"({"scale": [-1, 1, 1], "translate": [0, 0, -4]})"};

void expect_same_triangles(const Scene& a, const Scene& b) {
    ASSERT_EQ(a.triangles.size(), b.triangles.size());
    for (std::size_t i = 0; i < a.triangles.size(); ++i) {
        EXPECT_EQ(a.triangles[i].vertices, b.triangles[i].vertices) << "triangle " << i;
        EXPECT_EQ(a.triangles[i].normals, b.triangles[i].normals) << "triangle " << i;
        EXPECT_EQ(a.materials[a.triangles[i].material].name, b.materials[b.triangles[i].material].name)
            << "triangle " << i;
    }
}

TEST(InstanceObject, EachPlacementIsTheMeshObjectItStandsFor) {
    const std::string mesh = fmt::format(R"("type": "mesh", "file": "{}/icosahedron.obj", "material": "clay", "smooth": true)",
                                         models());
    std::string meshes;
    for (const char* t : kPlacements) meshes += fmt::format(R"({}{{{}, "transform": {}}})", meshes.empty() ? "" : ", ", mesh, t);
    const Scene instanced = vkrt::test::scene_from_text(
        "instance_mesh", scene_text(fmt::format(R"({{"type": "instance", "object": {{{}}}, "transforms": [{}, {}, {}]}})",
                                                mesh, kPlacements[0], kPlacements[1], kPlacements[2])));
    const Scene separate = vkrt::test::scene_from_text("separate_meshes", scene_text(meshes));
    ASSERT_EQ(separate.triangles.size(), 60u);
    expect_same_triangles(instanced, separate);
    EXPECT_EQ(instanced.instances.meshes, 1u);
    EXPECT_EQ(instanced.instances.placements, 3u);
    EXPECT_EQ(separate.instances.placements, 0u);
}

TEST(InstanceObject, TheObjectsOwnTransformComesFirst) {
    const std::string mesh = fmt::format(R"("type": "mesh", "file": "{}/icosahedron.obj", "material": "clay")", models());
    const Scene instanced = vkrt::test::scene_from_text(
        "instance_own", scene_text(fmt::format(R"({{"type": "instance", "object": {{{}, "transform": {{"scale": 2}}}},
                                                    "transforms": [{{"translate": [5, 0, 0]}}]}})",
                                               mesh)));
    const Scene direct = vkrt::test::scene_from_text(
        "direct", scene_text(fmt::format(R"({{{}, "transform": {{"scale": 2, "translate": [5, 0, 0]}}}})", mesh)));
    expect_same_triangles(instanced, direct);
}

TEST(InstanceObject, AGltfFileIsReadOnceForAllItsPlacements) {
    const Scene instanced = vkrt::test::scene_from_text(
        "instance_gltf", scene_text(fmt::format(R"({{"type": "instance", "object": {{"type": "gltf", "file": "{}"}},
                                                     "transforms": [{}, {}, {}]}})",
                                                radio(), kPlacements[0], kPlacements[1], kPlacements[2])));
    std::string files;
    for (const char* t : kPlacements) {
        files += fmt::format(R"({}{{"type": "gltf", "file": "{}", "transform": {}}})", files.empty() ? "" : ", ", radio(), t);
    }
    const Scene separate = vkrt::test::scene_from_text("separate_gltf", scene_text(files));
    expect_same_triangles(instanced, separate);
    // The file's materials (and their textures) once, not once a placement.
    EXPECT_EQ(separate.materials.size() - 1, 3 * (instanced.materials.size() - 1));
    EXPECT_EQ(separate.textures.size(), 3 * instanced.textures.size());
    // Each of the radio's 7 meshes is placed three times, on its 11 mesh nodes (two
    // knobs share one mesh, four feet another).
    EXPECT_EQ(instanced.instances.meshes, 7u);
    EXPECT_EQ(instanced.instances.placements, 3u * 11u);
    // Its power light is emissive in every copy.
    std::size_t emissive = 0;
    for (const auto& t : instanced.triangles) emissive += instanced.materials[t.material].emission != glm::dvec3(0.0);
    EXPECT_GT(emissive, 0u);
    EXPECT_EQ(emissive % 3, 0u);
}

TEST(InstanceObject, RefusesMistakesAtTheirField) {
    const auto error = [](const std::string& name, const std::string& instance) {
        return vkrt::test::scene_error_of(name, scene_text(instance));
    };
    const std::string mesh = fmt::format(R"({{"type": "mesh", "file": "{}/icosahedron.obj", "material": "clay"}})", models());
    vkrt::test::expect_error_message(
        error("sphere", R"({"type": "instance", "object": {"type": "sphere"}, "transforms": [{}]})"), "",
        {"objects[0].object.type", "an instance places a \"mesh\" or a \"gltf\" object, not 'sphere'"});
    vkrt::test::expect_error_message(
        error("empty", fmt::format(R"({{"type": "instance", "object": {}, "transforms": []}})", mesh)), "",
        {"objects[0].transforms", "expected at least one transform"});
    vkrt::test::expect_error_message(error("missing", fmt::format(R"({{"type": "instance", "object": {}}})", mesh)), "",
                                     {"objects[0]", "transforms"});
    vkrt::test::expect_error_message(
        error("zero_scale",
              fmt::format(R"({{"type": "instance", "object": {}, "transforms": [{{}}, {{"scale": 0}}]}})", mesh)),
        "", {"objects[0].transforms[1].scale"});
    vkrt::test::expect_error_message(
        error("unknown", fmt::format(R"({{"type": "instance", "object": {}, "transforms": [{{}}], "copies": 3}})", mesh)),
        "", {"objects[0]", "copies"});
    vkrt::test::expect_error_message(
        error("no_file", R"({"type": "instance", "object": {"type": "gltf", "file": "nowhere.glb"}, "transforms": [{}]})"),
        "", {"objects[0].object.file", "nowhere.glb"});
}

TEST(InstanceObject, RefusesPlacementsThatCopyTooManyTriangles) {
    // A 32 x 64 grid of quads: 4096 triangles, placed 8193 times, is 2^25 + 4096.
    const std::filesystem::path dir = vkrt::test::temp_dir("instance_too_many");
    {
        std::ofstream obj(dir / "grid.obj");
        for (int y = 0; y <= 64; ++y) {
            for (int x = 0; x <= 32; ++x) obj << "v " << x << ' ' << y << " 0\n";
        }
        for (int y = 0; y < 64; ++y) {
            for (int x = 0; x < 32; ++x) {
                const int a = y * 33 + x + 1, b = a + 1, c = a + 33, d = c + 1;
                obj << "f " << a << ' ' << b << ' ' << d << "\nf " << a << ' ' << d << ' ' << c << '\n';
            }
        }
    }
    std::string transforms;
    for (int i = 0; i < 8193; ++i) transforms += fmt::format(R"({}{{"translate": [0, 0, {}]}})", i ? ", " : "", i);
    std::ofstream(dir / "scene.json") << scene_text(fmt::format(
        R"({{"type": "instance", "object": {{"type": "mesh", "file": "grid.obj", "material": "clay"}}, "transforms": [{}]}})",
        transforms));
    vkrt::test::expect_error_message(vkrt::test::load_error_of(dir / "scene.json"), "",
                                     {"objects[0].transforms",
                                      "8193 placements copy 33558528 triangles, more than the 33554432 that instances may hold"});
}

}  // namespace

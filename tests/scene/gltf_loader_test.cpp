// glTF 2.0 files (host/scene/gltf_loader.cpp): files written here byte by byte, so
// every value is known; the node hierarchy, materials, camera and lights as the
// scene gets them; a white sky's closed form on both backends; and one clear error
// for each way a file can be broken.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include "scene/gltf_loader.hpp"
#include "scene/load_scene.hpp"
#include "scene/scene_error.hpp"
#include "test_support.hpp"

namespace {

using glm::dvec3;
using vkrt::Scene;

// An octahedron of radius 1 around the origin: 6 vertices, 8 faces wound outward,
// and its unit normals (the vertices themselves).
struct Octahedron {
    std::vector<float> positions = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    std::vector<std::uint16_t> indices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
};

// The buffer: positions (72 bytes), normals (72 bytes), indices (48 bytes).
std::string octahedron_bytes() {
    const Octahedron o;
    std::string bytes(192, '\0');
    std::memcpy(bytes.data(), o.positions.data(), 72);
    std::memcpy(bytes.data() + 72, o.positions.data(), 72);
    std::memcpy(bytes.data() + 144, o.indices.data(), 48);
    return bytes;
}

// The glTF JSON around that buffer; `nodes`, `extra` (more top-level members) and
// `material` fill in what a test varies.
std::string gltf_json(const std::string& buffer_uri, const std::string& nodes, const std::string& extra = "",
                      const std::string& indices_accessor = R"({"bufferView": 2, "componentType": 5123, "count": 24, "type": "SCALAR"})") {
    return R"({
      "asset": {"version": "2.0"},
      "scene": 0,
      "scenes": [{"nodes": [0]}],
      "nodes": )" + nodes + R"(,
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
      "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0}}],
      "buffers": [{"byteLength": 192)" + (buffer_uri.empty() ? std::string() : R"(, "uri": ")" + buffer_uri + "\"") + R"(}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 72}, {"buffer": 0, "byteOffset": 72, "byteLength": 72},
                      {"buffer": 0, "byteOffset": 144, "byteLength": 48}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},
                    {"bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC3"},
                    )" + indices_accessor + R"(])" + extra + "}";
}

const std::string kOneNode = R"([{"mesh": 0}])";

// A .gltf with its .bin beside it, in a fresh directory; returns the .gltf's path.
std::filesystem::path write_gltf(const std::string& name, const std::string& json,
                                 const std::string& bin = octahedron_bytes()) {
    const std::filesystem::path dir = vkrt::test::temp_dir("gltf_" + name);
    std::ofstream(dir / "mesh.bin", std::ios::binary) << bin;
    std::ofstream(dir / (name + ".gltf"), std::ios::binary) << json;
    return dir / (name + ".gltf");
}

// A .glb: the 12-byte header, the JSON chunk padded with spaces, the BIN chunk
// padded with zeros (glTF 2.0 specification, 4.4).
std::filesystem::path write_glb(const std::string& name, std::string json, std::string bin) {
    while (json.size() % 4) json += ' ';
    while (bin.size() % 4) bin += '\0';
    std::string out;
    const auto u32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    u32(0x46546C67u);  // "glTF"
    u32(2);
    u32(static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    u32(static_cast<std::uint32_t>(json.size()));
    u32(0x4E4F534Au);  // "JSON"
    out += json;
    u32(static_cast<std::uint32_t>(bin.size()));
    u32(0x004E4942u);  // "BIN\0"
    out += bin;
    const std::filesystem::path file = vkrt::test::temp_dir("glb_" + name) / (name + ".glb");
    std::ofstream(file, std::ios::binary) << out;
    return file;
}

std::string load_error(const std::filesystem::path& file) {
    try {
        vkrt::load_scene(file);
    } catch (const vkrt::SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error for " << file;
    return {};
}

bool has_warning(const Scene& s, const std::string& piece) {
    for (const std::string& w : s.warnings) {
        if (w.find(piece) != std::string::npos) return true;
    }
    return false;
}

TEST(Gltf, ReadsTheMeshItsMaterialAndItsNormals) {
    const Scene s = vkrt::load_scene(write_gltf("plain", gltf_json("mesh.bin", kOneNode)));
    ASSERT_EQ(s.triangles.size(), 8u);
    EXPECT_EQ(s.triangles[0].vertices[0], dvec3(1, 0, 0));
    EXPECT_EQ(s.triangles[0].vertices[1], dvec3(0, 1, 0));
    EXPECT_EQ(s.triangles[0].vertices[2], dvec3(0, 0, 1));
    ASSERT_TRUE(s.triangles[0].normals.has_value());
    EXPECT_EQ((*s.triangles[0].normals)[2], dvec3(0, 0, 1));
    const vkrt::Material& m = s.materials.at(s.triangles[0].material);
    ASSERT_TRUE(m.metallic_roughness.has_value());
    EXPECT_EQ(m.metallic_roughness->base_color, dvec3(0.5));
    EXPECT_EQ(m.metallic_roughness->metallic, 0.0);
    EXPECT_EQ(m.metallic_roughness->roughness, 1.0) << "glTF's default";
    EXPECT_EQ(s.render.mode, vkrt::RenderMode::Global);
    EXPECT_EQ(s.render.background, dvec3(1.0)) << "a white sky when the file has no light";
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(Gltf, BinaryFilesReadTheSame) {
    const Scene s = vkrt::load_scene(write_glb("plain", gltf_json("", kOneNode), octahedron_bytes()));
    ASSERT_EQ(s.triangles.size(), 8u);
    EXPECT_EQ(s.triangles[7].vertices[2], dvec3(0, 0, -1));
}

// Translation, rotation (a quarter turn about y: x goes to -z) and scale, child
// after parent, as the specification composes them (T * R * S, parent first).
TEST(Gltf, NodesComposeTheirTransforms) {
    const std::string nodes = R"([{"translation": [10, 0, 0], "children": [1]},
                                   {"rotation": [0, 0.70710678118654752, 0, 0.70710678118654752], "scale": [2, 2, 2], "mesh": 0}])";
    const Scene s = vkrt::load_scene(write_gltf("nodes", gltf_json("mesh.bin", nodes)));
    ASSERT_EQ(s.triangles.size(), 8u);
    const dvec3 v = s.triangles[0].vertices[0];  // (1, 0, 0) scaled, turned, moved
    EXPECT_NEAR(v.x, 10.0, 1e-12);
    EXPECT_NEAR(v.y, 0.0, 1e-12);
    EXPECT_NEAR(v.z, -2.0, 1e-12);
    const dvec3 n = (*s.triangles[0].normals)[0];
    EXPECT_NEAR(n.z, -1.0, 1e-12);
}

TEST(Gltf, AMirroringNodeKeepsFrontFacesOutside) {
    const Scene s = vkrt::load_scene(write_gltf("mirror", gltf_json("mesh.bin", R"([{"scale": [-1, 1, 1], "mesh": 0}])")));
    for (const vkrt::Triangle& t : s.triangles) {
        const dvec3 face = glm::cross(t.vertices[1] - t.vertices[0], t.vertices[2] - t.vertices[0]);
        const dvec3 centre = (t.vertices[0] + t.vertices[1] + t.vertices[2]) / 3.0;
        EXPECT_GT(glm::dot(face, centre), 0.0);
    }
}

TEST(Gltf, TheFilesCameraIsUsed) {
    // A camera 5 in front of the origin on +z, looking down -z (its node's -z), 0.6
    // radians high, aspect 2.
    const std::string nodes = R"([{"mesh": 0, "children": [1]}, {"translation": [0, 0, 5], "camera": 0}])";
    const std::string cameras = R"(, "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 2, "znear": 0.1}}])";
    const Scene s = vkrt::load_scene(write_gltf("camera", gltf_json("mesh.bin", nodes, cameras)));
    EXPECT_EQ(s.camera.eye, dvec3(0, 0, 5));
    EXPECT_EQ(s.camera.look_at, dvec3(0, 0, 4));
    EXPECT_NEAR(s.camera.fov, 0.6 * 180.0 / M_PI, 1e-12);
    EXPECT_EQ(s.camera.width, 2 * s.camera.height);
}

TEST(Gltf, WithoutACameraTheSceneIsFramed) {
    const Scene s = vkrt::load_scene(write_gltf("framed", gltf_json("mesh.bin", kOneNode)));
    EXPECT_TRUE(s.camera.framed);
    EXPECT_EQ(s.camera.look_at, dvec3(0.0));
    EXPECT_EQ(s.camera.up, dvec3(0, 1, 0));
    // From the front (+z), the bounding sphere (radius sqrt 3 around the box) filling
    // the vertical view, the narrower of 800 x 600.
    EXPECT_EQ(s.camera.eye.x, 0.0);
    EXPECT_EQ(s.camera.eye.y, 0.0);
    EXPECT_NEAR(std::sqrt(3.0) / s.camera.eye.z, std::sin(s.camera.fov / 2.0 * M_PI / 180.0), 1e-12);
}

// Whatever the model's size and offset, and for a portrait image the horizontal
// angle, the narrower one, decides.
TEST(Gltf, FramingFollowsTheModelAndTheImagesShape) {
    Scene s = vkrt::load_scene(write_gltf("framed_far", gltf_json("mesh.bin", R"([{"mesh": 0, "translation": [1e5, -3e4, 7], "scale": [1e-4, 1e-4, 1e-4]}])")));
    const double radius = std::sqrt(3.0) * 1e-4;
    EXPECT_NEAR(s.camera.look_at.x, 1e5, 1e-9);
    EXPECT_NEAR(s.camera.look_at.y, -3e4, 1e-9);
    const double half = 20.0 * M_PI / 180.0;
    EXPECT_NEAR(s.camera.eye.z - s.camera.look_at.z, radius / std::sin(half), 1e-9);
    s.camera.width = 300;
    s.camera.height = 600;
    vkrt::frame_scene(s);
    const double half_across = std::atan(std::tan(half) * 0.5);
    EXPECT_NEAR(s.camera.eye.z - s.camera.look_at.z, radius / std::sin(half_across), 1e-9);
}

TEST(Gltf, PointLightsAndEmissionAreRead) {
    const std::string nodes = R"([{"mesh": 0, "children": [1, 2]},
                                   {"translation": [0, 3, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
                                   {"extensions": {"KHR_lights_punctual": {"light": 1}}}])";
    const std::string extra = R"(, "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 0.5, 0.25], "intensity": 20},
                                                         {"type": "spot", "intensity": 5, "spot": {}}]}})";
    const Scene s = vkrt::load_scene(write_gltf("lights", gltf_json("mesh.bin", nodes, extra)));
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].type, vkrt::LightType::Point);
    EXPECT_EQ(s.lights[0].position, dvec3(0, 3, 0));
    EXPECT_EQ(s.lights[0].color, dvec3(1, 0.5, 0.25));
    EXPECT_DOUBLE_EQ(s.lights[0].intensity, 20.0 / 683.0) << "candela to watts per steradian";
    EXPECT_EQ(s.lights[1].type, vkrt::LightType::Spot);
    EXPECT_DOUBLE_EQ(s.lights[1].intensity, 5.0 / 683.0);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    EXPECT_EQ(s.render.background, dvec3(0.05)) << "a dim sky beside the file's own lights";
}

// Spot and directional lights shine down their node's -z axis, turned by the node
// and its parents but neither scaled nor moved by them; a spot light stands at its
// node's origin; the cone keeps glTF's radians and defaults.
TEST(Gltf, SpotAndDirectionalLightsShineDownTheirNodesMinusZ) {
    const double h = std::sqrt(0.5);  // sin and cos of 45 degrees
    const std::string nodes = fmt::format(R"([{{"mesh": 0, "translation": [1, 0, 0], "children": [1, 2, 3]}},
        {{"translation": [0, 4, 0], "rotation": [{0}, 0, 0, {1}], "scale": [2, 2, 2],
          "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}},
        {{"translation": [5, 6, 7], "rotation": [0, {1}, 0, {1}], "extensions": {{"KHR_lights_punctual": {{"light": 1}}}}}},
        {{"matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 3, 0, 0, 0, 0, 1], "extensions": {{"KHR_lights_punctual": {{"light": 2}}}}}}])",
                                          -h, h);
    const std::string extra = R"(, "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "spot", "intensity": 7, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
            {"type": "directional", "color": [1, 0.9, 0.8], "intensity": 3},
            {"type": "spot", "spot": {"outerConeAngle": 1.5708}}]}})";
    const Scene s = vkrt::load_scene(write_gltf("directed", gltf_json("mesh.bin", nodes, extra)));
    ASSERT_EQ(s.lights.size(), 3u);
    const vkrt::Light& spot = s.lights[0];
    EXPECT_EQ(spot.type, vkrt::LightType::Spot);
    // Turned -90 degrees about x: -z becomes -y.
    EXPECT_NEAR(glm::length(spot.direction - dvec3(0, -1, 0)), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(spot.position - dvec3(1, 4, 0)), 0.0, 1e-15);
    EXPECT_EQ(spot.inner_angle, 0.2);
    EXPECT_EQ(spot.outer_angle, 0.5);
    EXPECT_DOUBLE_EQ(spot.intensity, 7.0 / 683.0);
    const vkrt::Light& sun = s.lights[1];
    EXPECT_EQ(sun.type, vkrt::LightType::Directional);
    // Turned 90 degrees about y: -z becomes -x.
    EXPECT_NEAR(glm::length(sun.direction - dvec3(-1, 0, 0)), 0.0, 1e-15);
    EXPECT_EQ(sun.color, dvec3(1, 0.9, 0.8));
    EXPECT_DOUBLE_EQ(sun.intensity, 3.0 / 683.0) << "lux to watts per square metre";
    // A matrix that stretches z: the direction stays unit. The inner angle's
    // default is 0; 1.5708 is pi/2 written short.
    EXPECT_EQ(s.lights[2].direction, dvec3(0, 0, -1));
    EXPECT_EQ(s.lights[2].inner_angle, 0.0);
    EXPECT_EQ(s.lights[2].outer_angle, M_PI / 2.0);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

// What is still not read: a light's range.
TEST(Gltf, LightRangesAreNamedAsIgnored) {
    const std::string nodes = R"([{"mesh": 0, "children": [1]}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}])";
    const std::string extra = R"(, "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "spot", "range": 10, "spot": {}}]}})";
    const Scene s = vkrt::load_scene(write_gltf("range", gltf_json("mesh.bin", nodes, extra)));
    EXPECT_EQ(s.lights.size(), 1u);
    EXPECT_TRUE(has_warning(s, "light ranges (lights reach everywhere) (1): ignored"));
}

TEST(Gltf, EmissiveStrengthScalesTheEmission) {
    std::string json = gltf_json("mesh.bin", kOneNode, R"(, "extensionsUsed": ["KHR_materials_emissive_strength"])");
    const std::string material = R"("metallicFactor": 0}})";
    json.replace(json.find(material), material.size(),
                 R"("metallicFactor": 0}, "emissiveFactor": [1, 0.5, 0], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}})");
    const Scene s = vkrt::load_scene(write_gltf("emissive", json));
    EXPECT_EQ(s.materials.at(s.triangles[0].material).emission, dvec3(4, 2, 0));
    // Emission is a detail of the model, not its lighting: the sky stays white.
    EXPECT_EQ(s.render.background, dvec3(1.0));
}

// alphaMode, alphaCutoff and the base colour's alpha become the material's coverage
// (kernel/alpha.glsl); OPAQUE keeps an alpha below 1 but ignores it.
TEST(Gltf, AlphaModeAndCutoffAreRead) {
    const std::string material = R"("metallicFactor": 0}})";
    for (const auto& [rest, mode, alpha, cutoff] :
         {std::tuple{R"("metallicFactor": 0}, "alphaMode": "MASK", "alphaCutoff": 0.3})", vkrt::AlphaMode::Mask, 0.5, 0.3},
          std::tuple{R"("metallicFactor": 0}, "alphaMode": "MASK"})", vkrt::AlphaMode::Mask, 0.5, 0.5},
          std::tuple{R"("metallicFactor": 0}, "alphaMode": "BLEND"})", vkrt::AlphaMode::Blend, 0.5, 0.5},
          std::tuple{R"("metallicFactor": 0}})", vkrt::AlphaMode::Opaque, 0.5, 0.5}}) {
        std::string json = gltf_json("mesh.bin", kOneNode);
        json.replace(json.find("[0.5, 0.5, 0.5, 1]"), 18, "[0.5, 0.5, 0.5, 0.5]");
        json.replace(json.find(material), material.size(), rest);
        const Scene s = vkrt::load_scene(write_gltf("alpha", json));
        const vkrt::Material& m = s.materials.at(s.triangles[0].material);
        EXPECT_EQ(m.alpha_mode, mode) << rest;
        EXPECT_EQ(m.alpha, alpha) << rest;
        EXPECT_EQ(m.alpha_cutoff, cutoff) << rest;
        EXPECT_FALSE(has_warning(s, "alpha")) << rest;
    }
}

// COLOR_0 as normalized unsigned bytes (VEC4) or floats (VEC3, alpha 1), per vertex,
// each triangle taking its corners' colours; out-of-range floats are clamped.
TEST(Gltf, VertexColoursAreRead) {
    std::string bytes = octahedron_bytes();
    for (int v = 0; v < 6; ++v) bytes += std::string{char(v * 51), char(255), char(0), char(128)};  // 24 bytes
    for (int v = 0; v < 6; ++v) {
        const float rgb[3] = {v * 0.2f, 1.5f, -0.5f};
        bytes.append(reinterpret_cast<const char*>(rgb), 12);  // 72 bytes
    }
    for (const auto& [accessor, alpha, clamped] : {std::tuple{R"({"bufferView": 3, "componentType": 5121, "normalized": true, "count": 6, "type": "VEC4"})", 128.0f / 255.0f, false},
                                                  std::tuple{R"({"bufferView": 4, "componentType": 5126, "count": 6, "type": "VEC3"})", 1.0f, true}}) {
        std::string json = gltf_json("mesh.bin", kOneNode);
        json.replace(json.find(R"("byteLength": 192)"), 17, R"("byteLength": 288)");
        json.replace(json.find(R"("NORMAL": 1})"), 12, R"("NORMAL": 1, "COLOR_0": 3})");
        const std::string views = R"({"buffer": 0, "byteOffset": 144, "byteLength": 48})";
        json.replace(json.find(views), views.size(), std::string(views) + R"(, {"buffer": 0, "byteOffset": 192, "byteLength": 24}, {"buffer": 0, "byteOffset": 216, "byteLength": 72})");
        const std::string last = R"("count": 24, "type": "SCALAR"})";
        json.replace(json.find(last), last.size(), last + ", " + accessor);
        const Scene s = vkrt::load_scene(write_gltf("colors", json, bytes));
        ASSERT_EQ(s.triangles.size(), 8u);
        // The first face is vertices 0, 2, 4.
        const auto& c = s.triangles[0].colors;
        ASSERT_TRUE(c.has_value());
        EXPECT_FLOAT_EQ((*c)[1].r, clamped ? 0.4f : 102.0f / 255.0f);
        EXPECT_FLOAT_EQ((*c)[1].g, 1.0f);
        EXPECT_FLOAT_EQ((*c)[1].b, 0.0f);
        EXPECT_FLOAT_EQ((*c)[1].a, alpha);
        EXPECT_FALSE(has_warning(s, "COLOR_0"));
    }
}

// TANGENT: unit xyz along +u, w the bitangent's sign; a mirroring node turns the
// tangent with the surface and flips the sign (glTF's bitangent is cross(n, t) w).
TEST(Gltf, TangentsAreReadAndMirrored) {
    std::string bytes = octahedron_bytes();
    for (int v = 0; v < 6; ++v) {
        const float t[4] = {0.0f, 0.0f, 2.0f, -1.0f};
        bytes.append(reinterpret_cast<const char*>(t), 16);  // 96 bytes
    }
    for (const bool mirrored : {false, true}) {
        std::string json = gltf_json("mesh.bin", mirrored ? R"([{"mesh": 0, "scale": [1, 1, -1]}])" : kOneNode);
        json.replace(json.find(R"("byteLength": 192)"), 17, R"("byteLength": 288)");
        json.replace(json.find(R"("NORMAL": 1})"), 12, R"("NORMAL": 1, "TANGENT": 3})");
        const std::string views = R"({"buffer": 0, "byteOffset": 144, "byteLength": 48})";
        json.replace(json.find(views), views.size(), std::string(views) + R"(, {"buffer": 0, "byteOffset": 192, "byteLength": 96})");
        const std::string last = R"("count": 24, "type": "SCALAR"})";
        json.replace(json.find(last), last.size(), last + R"(, {"bufferView": 3, "componentType": 5126, "count": 6, "type": "VEC4"})");
        const Scene s = vkrt::load_scene(write_gltf("tangents", json, bytes));
        ASSERT_EQ(s.triangles.size(), 8u);
        const auto& t = s.triangles[0].tangents;
        ASSERT_TRUE(t.has_value());
        for (const glm::vec4& v : *t) {
            EXPECT_EQ(glm::vec3(v), glm::vec3(0.0f, 0.0f, mirrored ? -1.0f : 1.0f)) << mirrored;
            EXPECT_EQ(v.w, mirrored ? 1.0f : -1.0f) << mirrored;
        }
        EXPECT_FALSE(has_warning(s, "TANGENT"));
    }
}

TEST(GltfErrors, AnUnknownAlphaModeIsNamed) {
    const std::string material = R"("metallicFactor": 0}})";
    std::string json = gltf_json("mesh.bin", kOneNode);
    json.replace(json.find(material), material.size(), R"("metallicFactor": 0}, "alphaMode": "CLIP"})");
    vkrt::test::expect_error_message(load_error(write_gltf("alpha_mode", json)), "",
                                     {"materials[0].alphaMode", "unknown alpha mode \"CLIP\"", "OPAQUE, MASK or BLEND"});
    json = gltf_json("mesh.bin", kOneNode);
    json.replace(json.find("[0.5, 0.5, 0.5, 1]"), 18, "[0.5, 0.5, 0.5, 1.5]");
    vkrt::test::expect_error_message(load_error(write_gltf("alpha_factor", json)), "",
                                     {"materials[0].pbrMetallicRoughness.baseColorFactor[3]", "from 0 to 1, got 1.5"});
}

TEST(Gltf, WhatIsNotRenderedIsNamedOnce) {
    std::string json = gltf_json("mesh.bin", kOneNode, R"(, "extensionsUsed": ["KHR_materials_anisotropy"])");
    json.replace(json.find(R"("metallicFactor": 0)"), 19, R"("metallicFactor": 1)");
    const Scene s = vkrt::load_scene(write_gltf("unsupported", json));
    EXPECT_TRUE(has_warning(s, "the extension KHR_materials_anisotropy is not supported"));
    EXPECT_EQ(s.triangles.size(), 8u);
}

// A JSON scene places a glTF file like a mesh: its triangles moved by the
// transform, its materials added, its camera not taken.
TEST(Gltf, AJsonSceneIncludesAFileWithATransform) {
    const std::string nodes = R"([{"mesh": 0, "children": [1]}, {"translation": [0, 0, 5], "camera": 0}])";
    const std::string cameras = R"(, "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "znear": 0.1}}])";
    const std::filesystem::path gltf = write_gltf("included", gltf_json("mesh.bin", nodes, cameras));
    const std::string json = R"({
      "camera": { "eye": [0, 0, 10], "look_at": [0, 0, 0] },
      "materials": { "m": { "diffuse": [1, 0, 0] } },
      "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 0.1, "material": "m" },
                   { "type": "gltf", "file": ")" + gltf.string() + R"(", "transform": { "scale": 2, "translate": [3, 0, 0] } } ] })";
    const Scene s = vkrt::test::scene_from_text("with_gltf", json);
    ASSERT_EQ(s.triangles.size(), 8u);
    EXPECT_EQ(s.triangles[0].vertices[0], dvec3(5, 0, 0));
    EXPECT_EQ(s.materials.at(s.triangles[0].material).metallic_roughness->base_color, dvec3(0.5));
    EXPECT_EQ(s.camera.eye, dvec3(0, 0, 10));
    EXPECT_EQ(s.render.mode, vkrt::RenderMode::Local) << "the scene's own settings";
}

// The metallic-roughness factors lie in [0, 1], as glTF defines them.
TEST(GltfErrors, MaterialFactorsOutOfRangeNameTheirElement) {
    const std::string material = R"("metallicFactor": 0}})";
    for (const auto& [factors, piece] :
         {std::pair{R"("metallicFactor": 0, "roughnessFactor": 1.5}})", "materials[0].pbrMetallicRoughness.roughnessFactor: expected a number from 0 to 1, got 1.5"},
          std::pair{R"("metallicFactor": -0.5}})", "materials[0].pbrMetallicRoughness.metallicFactor: expected a number from 0 to 1, got -0.5"}}) {
        std::string json = gltf_json("mesh.bin", kOneNode);
        json.replace(json.find(material), material.size(), factors);
        vkrt::test::expect_error_message(load_error(write_gltf("factors", json)), "", {piece});
    }
    std::string json = gltf_json("mesh.bin", kOneNode);
    json.replace(json.find("[0.5, 0.5, 0.5, 1]"), 18, "[2, 0.5, 0.5, 1]");
    vkrt::test::expect_error_message(load_error(write_gltf("base", json)), "",
                                     {"materials[0].pbrMetallicRoughness.baseColorFactor", "expected components from 0 to 1, got 2"});
}

TEST(GltfErrors, AnIncludedFilesErrorFollowsTheScenesPath) {
    const std::string json = R"({
      "camera": { "eye": [0, 0, 10], "look_at": [0, 0, 0] },
      "materials": { "m": { "diffuse": [1, 0, 0] } },
      "objects": [ { "type": "gltf", "file": "absent.glb" } ] })";
    try {
        vkrt::test::scene_from_text("absent_gltf", json);
        ADD_FAILURE() << "no error";
    } catch (const vkrt::SceneError& e) {
        vkrt::test::expect_error_message(e.what(), "", {"objects[0].file", "absent.glb"});
    }
}

// A file of one node whose one material is the JSON `material` (in place of kOneNode's
// plain grey dielectric), for the extensions' tests.
std::filesystem::path with_material(const std::string& name, const std::string& material) {
    const std::string plain = R"({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0}})";
    std::string json = gltf_json("mesh.bin", kOneNode);
    json.replace(json.find(plain), plain.size(), material);
    return write_gltf(name, json);
}

// Glass: KHR_materials_transmission's factor, KHR_materials_ior's index, and
// KHR_materials_volume's thickness, which makes the glass refract, and its
// attenuation; without a volume it is a thin wall, which absorbs nothing. What is
// not rendered is named.
TEST(Gltf, GlassExtensionsAreRead) {
    const Scene solid = vkrt::load_scene(with_material("glass_solid", R"({"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.75}, "KHR_materials_ior": {"ior": 1.33},
                       "KHR_materials_volume": {"thicknessFactor": 0.1, "attenuationDistance": 2, "attenuationColor": [1, 0.5, 0.25]}}})"));
    ASSERT_TRUE(solid.materials[0].metallic_roughness.has_value());
    EXPECT_DOUBLE_EQ(solid.materials[0].metallic_roughness->transmission, 0.75);
    EXPECT_FALSE(solid.materials[0].metallic_roughness->thin);
    EXPECT_DOUBLE_EQ(solid.materials[0].metallic_roughness->attenuation_distance, 2.0);
    EXPECT_EQ(solid.materials[0].metallic_roughness->attenuation_color, glm::dvec3(1.0, 0.5, 0.25));
    EXPECT_TRUE(solid.materials[0].metallic_roughness->absorbs());
    EXPECT_DOUBLE_EQ(solid.materials[0].ior, 1.33);
    EXPECT_TRUE(solid.warnings.empty()) << solid.warnings.front();

    const Scene thin = vkrt::load_scene(with_material("glass_thin", R"({"pbrMetallicRoughness": {"roughnessFactor": 0.4},
        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                       "KHR_materials_volume": {"thicknessFactor": 0, "attenuationDistance": 2, "attenuationColor": [1, 0.5, 0.5]}}})"));
    EXPECT_TRUE(thin.materials[0].metallic_roughness->thin);
    EXPECT_FALSE(thin.materials[0].metallic_roughness->absorbs());
    EXPECT_DOUBLE_EQ(thin.materials[0].ior, 1.5);
    EXPECT_DOUBLE_EQ(thin.materials[0].metallic_roughness->roughness, 0.4);  // rough glass
    EXPECT_TRUE(thin.warnings.empty()) << thin.warnings.front();

    vkrt::test::expect_error_message(
        load_error(with_material("glass_texture", R"({"extensions": {"KHR_materials_transmission": {"transmissionTexture": {"index": 0}}}})")), "",
                                     {"KHR_materials_transmission.transmissionTexture.index", "texture 0 does not exist"});
    vkrt::test::expect_error_message(load_error(with_material("glass_ior", R"({"extensions": {"KHR_materials_ior": {"ior": 0.5}}})")), "",
                                     {"materials[0].extensions.KHR_materials_ior.ior", "from 1 to 1000, got 0.5"});
    for (const auto& [volume, piece] :
         {std::pair{R"("attenuationDistance": 0)", "KHR_materials_volume.attenuationDistance: expected a number above 0"},
          std::pair{R"("attenuationColor": [1, 2, 1])", "KHR_materials_volume.attenuationColor[1]"},
          std::pair{R"("attenuationColor": [1, 1])", "KHR_materials_volume.attenuationColor: expected 3 numbers from 0 to 1"}}) {
        const std::string material = fmt::format(R"({{"extensions": {{"KHR_materials_transmission": {{"transmissionFactor": 1}},
                                     "KHR_materials_volume": {{"thicknessFactor": 1, {}}}}}}})", volume);
        vkrt::test::expect_error_message(load_error(with_material("glass_volume", material)), "", {piece});
    }
}

// KHR_materials_clearcoat's factors make the material's clear coat; a factor out of
// range, or a texture the file lacks, is refused (gltf_texcoord_test reads its
// textures, the coat's normal map among them).
TEST(Gltf, ClearcoatIsRead) {
    const Scene s = vkrt::load_scene(with_material("clearcoat", R"({"pbrMetallicRoughness": {"metallicFactor": 0},
        "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 0.75, "clearcoatRoughnessFactor": 0.25}}})"));
    ASSERT_TRUE(s.materials[0].metallic_roughness.has_value());
    EXPECT_DOUBLE_EQ(s.materials[0].metallic_roughness->clearcoat, 0.75);
    EXPECT_DOUBLE_EQ(s.materials[0].metallic_roughness->clearcoat_roughness, 0.25);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();

    vkrt::test::expect_error_message(load_error(with_material("clearcoat_normal", R"({"extensions": {"KHR_materials_clearcoat":
        {"clearcoatFactor": 1, "clearcoatNormalTexture": {"index": 0}}}})")), "",
                                     {"KHR_materials_clearcoat.clearcoatNormalTexture.index", "texture 0 does not exist"});
    vkrt::test::expect_error_message(load_error(with_material("clearcoat_normal_scale", R"({"extensions": {"KHR_materials_clearcoat":
        {"clearcoatFactor": 1, "clearcoatNormalTexture": {"index": 0, "scale": "big"}}}})")), "",
                                     {"KHR_materials_clearcoat.clearcoatNormalTexture.scale", "expected a number"});

    vkrt::test::expect_error_message(load_error(with_material("clearcoat_texture", R"({"extensions": {"KHR_materials_clearcoat":
        {"clearcoatFactor": 1, "clearcoatRoughnessTexture": {"index": 0}}}})")), "",
                                     {"KHR_materials_clearcoat.clearcoatRoughnessTexture.index", "texture 0 does not exist"});

    vkrt::test::expect_error_message(
        load_error(with_material("clearcoat_range", R"({"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 2}}})")), "",
                                     {"materials[0].extensions.KHR_materials_clearcoat.clearcoatFactor", "from 0 to 1, got 2"});
}

// KHR_materials_sheen's factors make the material's sheen; a colour out of range is
// refused (gltf_texcoord_test reads its textures).
TEST(Gltf, SheenIsRead) {
    const Scene s = vkrt::load_scene(with_material("sheen", R"({"pbrMetallicRoughness": {"metallicFactor": 0},
        "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 0.5, 0.25], "sheenRoughnessFactor": 0.75}}})"));
    ASSERT_TRUE(s.materials[0].metallic_roughness.has_value());
    EXPECT_EQ(s.materials[0].metallic_roughness->sheen_color, dvec3(1, 0.5, 0.25));
    EXPECT_DOUBLE_EQ(s.materials[0].metallic_roughness->sheen_roughness, 0.75);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();

    vkrt::test::expect_error_message(
        load_error(with_material("sheen_range", R"({"extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 2, 1]}}})")), "",
                                     {"materials[0].extensions.KHR_materials_sheen.sheenColorFactor[1]", "from 0 to 1, got 2"});
}

// KHR_materials_specular's factors make the dielectric's specular layer, on glass too;
// a factor out of range, or a texture the file lacks, is refused (gltf_texcoord_test
// reads its textures).
TEST(Gltf, SpecularIsRead) {
    const Scene s = vkrt::load_scene(with_material("specular", R"({"pbrMetallicRoughness": {"metallicFactor": 0},
        "extensions": {"KHR_materials_specular": {"specularFactor": 0.25, "specularColorFactor": [2, 1, 0.5]}}})"));
    ASSERT_TRUE(s.materials[0].metallic_roughness.has_value());
    EXPECT_DOUBLE_EQ(s.materials[0].metallic_roughness->specular, 0.25);
    EXPECT_EQ(s.materials[0].metallic_roughness->specular_color, dvec3(2, 1, 0.5));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();

    vkrt::test::expect_error_message(load_error(with_material("specular_texture", R"({"extensions": {"KHR_materials_specular":
        {"specularColorTexture": {"index": 0}}}})")), "",
                                     {"KHR_materials_specular.specularColorTexture.index", "texture 0 does not exist"});

    const Scene glass = vkrt::load_scene(with_material("specular_glass", R"({"extensions": {
        "KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_specular": {"specularFactor": 0.5}}})"));
    EXPECT_TRUE(glass.warnings.empty()) << glass.warnings.front();
    EXPECT_DOUBLE_EQ(glass.materials[0].metallic_roughness->specular, 0.5);

    vkrt::test::expect_error_message(load_error(with_material("specular_range",
        R"({"extensions": {"KHR_materials_specular": {"specularColorFactor": [1, -2, 1]}}})")), "",
                                     {"materials[0].extensions.KHR_materials_specular.specularColorFactor", "got -2"});
}

// ------------------------------------------------------------------ bad files

TEST(GltfErrors, AnIndexOutOfRangeNamesTheAccessor) {
    std::string bin = octahedron_bytes();
    bin[144 + 2 * 5] = 9;  // index 5 becomes 9, of 6 vertices
    const std::string message = load_error(write_gltf("index", gltf_json("mesh.bin", kOneNode), bin));
    vkrt::test::expect_error_message(message, "", {"meshes[0].primitives[0].indices", "index 9", "out of range", "6 vertices"});
}

// Every vertex attribute holds one value per position; a count that differs names
// the attribute and both counts.
TEST(GltfErrors, AnAttributeWithTooFewValuesIsNamed) {
    std::string json = gltf_json("mesh.bin", kOneNode);
    const std::string normals = R"({"bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC3"})";
    json.replace(json.find(normals), normals.size(), R"({"bufferView": 1, "componentType": 5126, "count": 5, "type": "VEC3"})");
    const std::string message = load_error(write_gltf("normal_count", json));
    vkrt::test::expect_error_message(message, "", {"meshes[0].primitives[0].attributes.NORMAL", "5 normals for 6 positions"});
}

TEST(GltfErrors, AnAccessorBeyondItsBufferViewIsRefused) {
    const std::string accessor = R"({"bufferView": 2, "componentType": 5123, "count": 30, "type": "SCALAR"})";
    const std::string message = load_error(write_gltf("range", gltf_json("mesh.bin", kOneNode, "", accessor)));
    vkrt::test::expect_error_message(message, "", {"meshes[0].primitives[0].indices", "accessors[2]", "does not fit", "bufferViews[2]"});
}

TEST(GltfErrors, AMissingBufferFileIsNamed) {
    const std::string message = load_error(write_gltf("missing", gltf_json("absent.bin", kOneNode)));
    vkrt::test::expect_error_message(message, "", {"missing.gltf", "absent.bin"});
}

TEST(GltfErrors, AMissingImageFileIsNamed) {
    std::string json = gltf_json("mesh.bin", kOneNode, R"(, "images": [{"uri": "absent.png"}], "textures": [{"source": 0}])");
    json.replace(json.find(R"("metallicFactor": 0)"), 19, R"("metallicFactor": 0, "baseColorTexture": {"index": 0})");
    vkrt::test::expect_error_message(load_error(write_gltf("image", json)), "", {"image.gltf", "absent.png"});
}

// A URI may name a directory or a FIFO: tinygltf's own reader would take a
// directory's end offset (2^63 - 1 on ext4) for its size and wait on a FIFO.
TEST(GltfErrors, ABufferThatIsADirectoryIsRefused) {
    const std::string message = load_error(write_gltf("dir_buffer", gltf_json(".", kOneNode)));
    vkrt::test::expect_error_message(message, "", {"dir_buffer.gltf", "not a regular file"});
}

TEST(GltfErrors, ABufferThatIsAFifoIsRefused) {
    const std::filesystem::path file = write_gltf("fifo_buffer", gltf_json("pipe.bin", kOneNode));
    ASSERT_EQ(::mkfifo((file.parent_path() / "pipe.bin").c_str(), 0600), 0);
    vkrt::test::expect_error_message(load_error(file), "", {"fifo_buffer.gltf", "pipe.bin", "not a regular file"});
}

TEST(GltfErrors, AnImageThatIsADirectoryIsRefused) {
    std::string json = gltf_json("mesh.bin", kOneNode, R"(, "images": [{"uri": "."}], "textures": [{"source": 0}])");
    json.replace(json.find(R"("metallicFactor": 0)"), 19, R"("metallicFactor": 0, "baseColorTexture": {"index": 0})");
    vkrt::test::expect_error_message(load_error(write_gltf("dir_image", json)), "",
                                     {"dir_image.gltf", "images[0].uri", "is not a regular file"});
}

TEST(GltfErrors, MalformedJsonIsRefused) {
    const std::string message = load_error(write_gltf("malformed", gltf_json("mesh.bin", kOneNode).substr(0, 200)));
    vkrt::test::expect_error_message(message, "", {"malformed.gltf", "not a readable glTF"});
}

TEST(GltfErrors, ATruncatedGlbIsRefused) {
    const std::filesystem::path whole = write_glb("whole", gltf_json("", kOneNode), octahedron_bytes());
    std::ifstream in(whole, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::filesystem::path cut = whole.parent_path() / "cut.glb";
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() - 40);
    vkrt::test::expect_error_message(load_error(cut), "", {"cut.glb", "not a readable glTF binary"});
}

TEST(GltfErrors, AMissingNodeOrMeshIsNamed) {
    vkrt::test::expect_error_message(load_error(write_gltf("mesh", gltf_json("mesh.bin", R"([{"mesh": 3}])"))), "",
                                     {"nodes[0].mesh", "mesh 3 does not exist"});
    vkrt::test::expect_error_message(load_error(write_gltf("cycle", gltf_json("mesh.bin", R"([{"mesh": 0, "children": [0]}])"))), "",
                                     {"nodes[0]"});
}

// Forty nodes that each list the next one twice would be placed 2^40 times.
TEST(GltfErrors, AHierarchyThatMultipliesItsNodesIsRefused) {
    std::string nodes = "[";
    for (int i = 0; i < 40; ++i) nodes += fmt::format(R"({{"children": [{0}, {0}]}}, )", i + 1);
    nodes += R"({"mesh": 0}])";
    vkrt::test::expect_error_message(load_error(write_gltf("doubling", gltf_json("mesh.bin", nodes))), "",
                                     {"doubling.gltf", "more than 100000 nodes"});
}

// Binary or JSON is told by the file's first bytes, not its name.
TEST(Gltf, ABinaryFileUnderAnotherNameStillLoads) {
    const std::filesystem::path glb = write_glb("renamed", gltf_json("", kOneNode), octahedron_bytes());
    std::filesystem::copy_file(glb, glb.parent_path() / "model.gltf");
    EXPECT_EQ(vkrt::load_scene(glb.parent_path() / "model.gltf").triangles.size(), 8u);
}

// A glTF with one light, of the given JSON, on a child of the mesh's node, which has
// the given extra members (a transform).
std::string one_light(const std::string& light, const std::string& node = "") {
    const std::string nodes = R"([{"mesh": 0, "children": [1]}, {)" + node + (node.empty() ? "" : ", ") +
                              R"("extensions": {"KHR_lights_punctual": {"light": 0}}}])";
    return gltf_json("mesh.bin", nodes, R"(, "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [)" + light + "]}}");
}

TEST(GltfErrors, BadSpotAndDirectionalLightsAreNamed) {
    using vkrt::test::expect_error_message;
    expect_error_message(load_error(write_gltf("wide", one_light(R"({"type": "spot", "spot": {"outerConeAngle": 2}})"))), "",
                         {"extensions.KHR_lights_punctual.lights[0].spot.outerConeAngle", "at most pi/2", "got 2"});
    expect_error_message(load_error(write_gltf("shut", one_light(R"({"type": "spot", "spot": {"outerConeAngle": 0}})"))), "",
                         {"lights[0].spot.outerConeAngle", "above 0", "got 0"});
    expect_error_message(load_error(write_gltf("inverted", one_light(R"({"type": "spot", "spot": {"innerConeAngle": 0.6, "outerConeAngle": 0.4}})"))), "",
                         {"lights[0].spot.innerConeAngle", "below outerConeAngle (0.4)", "got 0.6"});
    expect_error_message(load_error(write_gltf("equal", one_light(R"({"type": "spot", "spot": {"innerConeAngle": 0.4, "outerConeAngle": 0.4}})"))), "",
                         {"lights[0].spot.innerConeAngle", "got 0.4"});
    expect_error_message(load_error(write_gltf("negative", one_light(R"({"type": "spot", "spot": {"innerConeAngle": -0.1}})"))), "",
                         {"lights[0].spot.innerConeAngle", "got -0.1"});
    expect_error_message(load_error(write_gltf("flat_sun", one_light(R"({"type": "directional"})", R"("scale": [1, 1, 0])"))), "",
                         {"nodes[1]", "flattens its directional light's direction"});
    expect_error_message(load_error(write_gltf("dark_sun", one_light(R"({"type": "directional", "intensity": -1})"))), "",
                         {"lights[0].intensity", "expected a number >= 0"});
}

TEST(GltfErrors, AFlatteningTransformIsRefused) {
    const std::string message = load_error(write_gltf("flat", gltf_json("mesh.bin", R"([{"scale": [1, 0, 1], "mesh": 0}])")));
    vkrt::test::expect_error_message(message, "", {"nodes[0]", "determinant 0"});
}

// ------------------------------------------------------------------ rendering

// Under a uniform sky of radiance 1, a convex flat-shaded diffuse object of albedo 0.5 sees
// nothing but sky above every point: each bounce keeps half the light and the next
// ray leaves, so every pixel on it is exactly 0.5, on both backends. The file's
// material is made Lambertian after loading: glTF's has a Fresnel term, whose share
// depends on the view (kernel/microfacet_test.cpp has the white furnace for it).
TEST(GltfRender, AConvexGreyObjectUnderAWhiteSkyIsItsAlbedo) {
    // Flat, without NORMAL: interpolated normals would send some bounces below the
    // facets, which end there (the energy smooth shading loses on a coarse mesh).
    std::string json = gltf_json("mesh.bin", kOneNode);
    json.replace(json.find(R"("POSITION": 0, "NORMAL": 1)"), 26, R"("POSITION": 0)");
    Scene s = vkrt::load_scene(write_gltf("sky", json));
    ASSERT_FALSE(s.triangles[0].normals.has_value());
    for (vkrt::Material& m : s.materials) {
        m.metallic_roughness.reset();
        m.diffuse = dvec3(0.5);
    }
    s.camera.width = 48;
    s.camera.height = 36;
    s.render.spp = 4;
    for (const bool vulkan : {false, true}) {
        const vkrt::RenderOutcome out = vulkan ? vkrt::test::render_vulkan(s) : vkrt::test::render_cpu(s);
        std::size_t object = 0;
        for (std::uint32_t y = 0; y < out.image.height; ++y) {
            for (std::uint32_t x = 0; x < out.image.width; ++x) {
                const float v = out.image.pixel(x, y)[0];
                if (v < 0.99f) {
                    ++object;
                    // Pixels on the silhouette mix object and sky.
                    EXPECT_GE(v, 0.5f - 1e-5f) << (vulkan ? "vulkan" : "cpu") << " pixel " << x << ", " << y;
                }
            }
        }
        // The middle is all object.
        EXPECT_NEAR(out.image.pixel(24, 18)[0], 0.5f, 1e-5f);
        EXPECT_GT(object, 100u);
    }
}

}  // namespace

// Normal maps (shaders/kernel/normal_map.glsl, decode_normal_map in
// host/scene/texture_image.cpp): exact values through the reference kernel (a flat
// map and scale 0 leave images bit for bit, a tilted map gives the Lambert value of
// its tilted normal), the tangent frame's orientation, both backends, glTF's
// normalTexture, and bad input.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include "flatten/flat_scene.hpp"
#include "image/image.hpp"
#include "image/image_files.hpp"
#include "kernel/kernel.hpp"
#include "scene/load_scene.hpp"
#include "scene/texture_image.hpp"
#include "mapped_triangle.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using kernel::Kernel;
using kernel::uvec4;
using kernel::vec2;
using kernel::vec3;
using kernel::vec4;

// A w x h float image of one colour, or of `at(x, y)`.
template <class Texel>
std::filesystem::path write_map(const std::string& name, std::uint32_t w, std::uint32_t h, Texel at) {
    Image img(w, h);
    for (std::uint32_t y = 0; y < h; ++y) {
        for (std::uint32_t x = 0; x < w; ++x) {
            const glm::vec3 c = at(x, y);
            for (int k = 0; k < 3; ++k) img.pixel(x, y)[k] = c[k];
        }
    }
    const std::filesystem::path file = test::temp_dir("normal_map_" + name) / (name + ".exr");
    write_image(img, file);
    return file;
}

std::filesystem::path constant_map(const std::string& name, glm::vec3 c) {
    return write_map(name, 2, 2, [&](std::uint32_t, std::uint32_t) { return c; });
}

// A quad facing the camera at +z (its front face), a directional light arriving
// from `toward` (the unit vector toward it), in local or global mode. The quad's
// texture coordinates run +u along +x and +v along +y, so the image's up is -y.
std::string quad_scene(const std::string& mode, const std::string& material, glm::dvec3 toward) {
    const glm::dvec3 d = -toward;
    return R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 30, "width": 16, "height": 16 },
      "render": { "mode": ")" + mode + R"(", "spp": 4, )" + (mode == "global" ? R"("max_bounces": 1, )" : "") +
           R"("background": [0, 0, 0] },
      "lights": [ { "type": "directional", "direction": [)" + std::to_string(d.x) + ", " + std::to_string(d.y) + ", " +
           std::to_string(d.z) + R"(], "intensity": 1 } ],
      "materials": { "m": )" + material + R"( },
      "objects": [ { "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "m" } ]
    })";
}

std::string with_map(const std::filesystem::path& map, const std::string& extra = "") {
    return R"({ "diffuse": [0.5, 0.5, 0.5], "normal_map": ")" + map.string() + "\"" + extra + " }";
}

void expect_bit_identical(const Image& a, const Image& b, const char* what) {
    ASSERT_EQ(a.width, b.width);
    for (std::uint32_t y = 0; y < a.height; ++y) {
        for (std::uint32_t x = 0; x < a.width; ++x) {
            for (int c = 0; c < 3; ++c) ASSERT_EQ(a.pixel(x, y)[c], b.pixel(x, y)[c]) << what << " at " << x << "," << y;
        }
    }
}

// A map of (0.5, 0.5, 1) decodes to (0, 0, 1) exactly, and scale 0 flattens any map:
// both shade with the interpolated normal itself, so the images are those without a
// map, bit for bit, in both modes.
TEST(NormalMap, FlatMapAndScaleZeroLeaveTheImageBitIdentical) {
    const auto flat = constant_map("flat", glm::vec3(0.5f, 0.5f, 1.0f));
    const auto tilted = constant_map("tilted_for_scale_0", glm::vec3(0.9f, 0.2f, 0.7f));
    for (const std::string mode : {"local", "global"}) {
        SCOPED_TRACE(mode);
        const glm::dvec3 toward = glm::normalize(glm::dvec3(1, 0.5, 1));
        const Scene plain = test::scene_from_text("plain_" + mode, quad_scene(mode, R"({ "diffuse": [0.5, 0.5, 0.5] })", toward));
        const Scene mapped = test::scene_from_text("flat_" + mode, quad_scene(mode, with_map(flat), toward));
        const Scene scaled = test::scene_from_text("scale0_" + mode, quad_scene(mode, with_map(tilted, R"(, "normal_scale": 0)"), toward));
        EXPECT_TRUE(flatten_scene(mapped).features.has(Feature::HAS_NORMAL_MAPS));
        EXPECT_FALSE(flatten_scene(plain).features.has(Feature::HAS_NORMAL_MAPS));
        const Image reference = test::render_cpu(plain).image;
        expect_bit_identical(test::render_cpu(mapped).image, reference, "flat map");
        expect_bit_identical(test::render_cpu(scaled).image, reference, "scale 0");
        EXPECT_GT(reference.pixel(8, 8)[0], 0.0f);
    }
}

// Spheres have no texture coordinates: a normal-mapped material on a sphere alone,
// beside a triangle of another material, leaves the feature off.
TEST(NormalMap, OnlyATrianglesMaterialTurnsTheFeatureOn) {
    const auto flat = constant_map("flat_on_sphere", glm::vec3(0.5f, 0.5f, 1.0f));
    const Scene scene = test::scene_from_text("sphere_map", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
      "materials": { "bumpy": )" + with_map(flat) + R"(, "plain": { "diffuse": [1, 1, 1] } },
      "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": "bumpy" },
                   { "type": "quad", "corner": [-1, -1, -1], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "plain" } ]
    })");
    EXPECT_FALSE(flatten_scene(scene).features.has(Feature::HAS_NORMAL_MAPS));
}

// A constant map tilts the whole quad's normal: under a directional light the
// quad shows the Lambert value of the tilted normal, E kd diffuse cos in local mode
// and diffuse / pi E cos in global mode. (0.75, 0.5, 1) decodes to (0.5, 0, 1): the
// normal (1, 0, 2) / sqrt 5, toward +u = +x. (0.5, 0.75, 1) tilts up the image,
// which on this quad is -y. Light from (1, 0, 1) / sqrt 2 meets (1, 0, 2) / sqrt 5
// at cos = 3 / sqrt 10, and from the other side at 1 / sqrt 10.
TEST(NormalMap, ATiltedMapGivesTheLambertValueOfTheTiltedNormal) {
    const auto along_u = constant_map("along_u", glm::vec3(0.75f, 0.5f, 1.0f));
    const auto up_image = constant_map("up_image", glm::vec3(0.5f, 0.75f, 1.0f));
    struct Case {
        const char* name;
        std::filesystem::path map;
        glm::dvec3 toward;
        double cosine;
    };
    const double s2 = std::sqrt(2.0);
    const Case cases[] = {
        {"tilt +x, light +x", along_u, glm::dvec3(1, 0, 1) / s2, 3.0 / std::sqrt(10.0)},
        {"tilt +x, light -x", along_u, glm::dvec3(-1, 0, 1) / s2, 1.0 / std::sqrt(10.0)},
        {"tilt up the image (-y), light -y", up_image, glm::dvec3(0, -1, 1) / s2, 3.0 / std::sqrt(10.0)},
        {"tilt up the image (-y), light +y", up_image, glm::dvec3(0, 1, 1) / s2, 1.0 / std::sqrt(10.0)},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const Scene local = test::scene_from_text("tilted_local", quad_scene("local", with_map(c.map), c.toward));
        const Scene global = test::scene_from_text("tilted_global", quad_scene("global", with_map(c.map), c.toward));
        const Image a = test::render_cpu(local).image;
        const Image b = test::render_cpu(global).image;
        for (std::uint32_t y = 4; y < 12; y += 3) {
            for (std::uint32_t x = 4; x < 12; x += 3) {
                EXPECT_NEAR(a.pixel(x, y)[0], 0.5 * c.cosine, 1e-6) << x << "," << y;
                EXPECT_NEAR(b.pixel(x, y)[0], 0.5 / std::numbers::pi * c.cosine, 1e-6) << x << "," << y;
            }
        }
    }
}

// The tangent follows the coordinates the map is read at: a quarter turn of the
// texture transform turns the tilt with it. Rotated by 90 degrees, u' = v
// (texture_transform): +u' runs along +y on this quad, and so does the (0.5, 0, 1)
// tilt of along_u.
TEST(NormalMap, TheTangentFollowsTheTextureTransform) {
    const auto along_u = constant_map("along_u_turned", glm::vec3(0.75f, 0.5f, 1.0f));
    const glm::dvec3 toward = glm::dvec3(0, 1, 1) / std::sqrt(2.0);
    const Scene scene = test::scene_from_text(
        "turned", quad_scene("local", with_map(along_u, R"(, "texture_transform": { "rotation": 90 })"), toward));
    const Image image = test::render_cpu(scene).image;
    EXPECT_NEAR(image.pixel(8, 8)[0], 0.5 * 3.0 / std::sqrt(10.0), 1e-6);
}

// A triangle's own tangents (glTF's TANGENT; "tangents" in a scene file) orient the
// frame instead of the texture coordinates: the triangle (-1, -1), (1, -1), (-1, 1)
// at z = 0 has +u along +x and +v along +y, so up the image is -y, and the frame an
// exporter writes for it, t = +x with w = -1 (bitangent -cross(n, t) = -y), shades as
// the derived one. A tangent along +y turns the along-u tilt toward +y; w = +1 turns
// the up-the-image tilt toward +y.
TEST(NormalMap, TheTrianglesOwnTangentsOrientTheFrame) {
    const auto along_u = constant_map("along_u_given", glm::vec3(0.75f, 0.5f, 1.0f));
    const auto up_image = constant_map("up_image_given", glm::vec3(0.5f, 0.75f, 1.0f));
    const double s2 = std::sqrt(2.0);
    struct Case {
        const char* name;
        std::filesystem::path map;
        const char* tangents;  // "" for none
        glm::dvec3 toward;     // the light that meets the tilted normal at cos 3 / sqrt 10
    };
    const Case cases[] = {
        {"derived, along u", along_u, "", glm::dvec3(1, 0, 1) / s2},
        {"derived, up the image", up_image, "", glm::dvec3(0, -1, 1) / s2},
        {"+x, w -1, along u", along_u, "[1, 0, 0, -1]", glm::dvec3(1, 0, 1) / s2},
        {"+x, w -1, up the image", up_image, "[1, 0, 0, -1]", glm::dvec3(0, -1, 1) / s2},
        {"+y, along u", along_u, "[0, 2, 0, -1]", glm::dvec3(0, 1, 1) / s2},
        {"+x, w +1, up the image", up_image, "[1, 0, 0, 1]", glm::dvec3(0, 1, 1) / s2},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        std::string text = quad_scene("local", with_map(c.map), c.toward);
        const std::string quad =
            R"({ "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "m" })";
        const std::string tangents = *c.tangents ? fmt::format(R"(, "tangents": [{0}, {0}, {0}])", c.tangents) : "";
        text.replace(text.find(quad), quad.size(),
                     R"({ "type": "triangle", "vertices": [[-1, -1, 0], [1, -1, 0], [-1, 1, 0]])" + tangents +
                         R"(, "material": "m" })");
        const Scene scene = test::scene_from_text("given_tangents", text);
        EXPECT_EQ(flatten_scene(scene).features.has(Feature::HAS_TANGENTS), *c.tangents != '\0');
        const Image image = test::render_cpu(scene).image;
        // Pixels of the lower left half (image rows run down, -y).
        for (const auto& [x, y] : {std::pair{2u, 13u}, std::pair{4u, 12u}, std::pair{3u, 10u}}) {
            EXPECT_NEAR(image.pixel(x, y)[0], 0.5 * 3.0 / std::sqrt(10.0), 1e-5) << x << "," << y;
        }
    }
}

// The kernel function itself: zero texture-coordinate area keeps the normal; a
// normal bent away from the viewer is brought back toward it.
TEST(NormalMapKernel, ZeroTextureAreaKeepsTheNormal) {
    const vec3 tilt(0.5f, 0.0f, 1.0f);
    test::MappedTriangle same(tilt, {vec2(0.3f, 0.3f), vec2(0.3f, 0.3f), vec2(0.3f, 0.3f)});
    EXPECT_EQ(same.normal(vec3(0, 0, 1)), vec3(0, 0, 1));
    test::MappedTriangle line(tilt, {vec2(0.0f, 0.0f), vec2(1.0f, 1.0f), vec2(2.0f, 2.0f)});
    EXPECT_EQ(line.normal(vec3(0, 0, 1)), vec3(0, 0, 1));
    // Coordinates along the edges: the tilt goes to +x, a unit vector.
    test::MappedTriangle plain(tilt, {vec2(0.0f, 0.0f), vec2(1.0f, 0.0f), vec2(0.0f, 1.0f)});
    const vec3 n = plain.normal(vec3(0, 0, 1));
    EXPECT_NEAR(n.x, 1.0f / std::sqrt(5.0f), 1e-6f);
    EXPECT_NEAR(n.y, 0.0f, 1e-6f);
    EXPECT_NEAR(n.z, 2.0f / std::sqrt(5.0f), 1e-6f);
    // Mirrored coordinates (v along -y) flip the bitangent: "up the image" stays -v.
    test::MappedTriangle up(vec3(0.0f, 0.5f, 1.0f), {vec2(0.0f, 0.0f), vec2(1.0f, 0.0f), vec2(0.0f, 1.0f)});
    test::MappedTriangle up_mirrored(vec3(0.0f, 0.5f, 1.0f), {vec2(0.0f, 1.0f), vec2(1.0f, 1.0f), vec2(0.0f, 0.0f)});
    EXPECT_LT(up.normal(vec3(0, 0, 1)).y, -0.4f);
    EXPECT_GT(up_mirrored.normal(vec3(0, 0, 1)).y, 0.4f);
}

TEST(NormalMapKernel, ANormalBentAwayFromTheViewerIsBroughtBack) {
    // Tilted almost into the plane toward +x, seen from -x at a grazing angle.
    test::MappedTriangle steep(vec3(20.0f, 0.0f, 1.0f), {vec2(0.0f, 0.0f), vec2(1.0f, 0.0f), vec2(0.0f, 1.0f)});
    const vec3 wo = glm::normalize(vec3(-1.0f, 0.0f, 0.2f));
    const vec3 n = steep.normal(wo);
    // Its component along wo replaced by MIN_MAPPED_COSINE: 0.01 / |n - (n.wo) wo + 0.01 wo|.
    const float c = -0.969563f;  // the mapped normal's cosine with wo before
    EXPECT_NEAR(glm::dot(n, wo), 0.01f / std::sqrt(1.0f - c * c + 0.0001f), 1e-4f);
    EXPECT_GT(glm::dot(n, wo), 0.0f);
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
    EXPECT_GT(n.z, 0.0f) << "above the geometric surface";
}

// A bumpy map (a sine ridge along u) on both backends: the same image within the
// texture's half-float arithmetic, which both share.
TEST(NormalMapRender, BothBackendsAgree) {
    const auto ridges = write_map("ridges", 16, 4, [](std::uint32_t x, std::uint32_t) {
        const float s = std::sin(float(x) * 0.785398f);
        return glm::vec3(0.5f + 0.4f * s, 0.5f, 1.0f);
    });
    const glm::dvec3 toward = glm::normalize(glm::dvec3(1, 0.3, 1));
    for (const std::string mode : {"local", "global"}) {
        SCOPED_TRACE(mode);
        const Scene scene = test::scene_from_text("ridges_" + mode, quad_scene(mode, with_map(ridges), toward));
        const RenderOutcome cpu = test::render_cpu(scene);
        const RenderOutcome gpu = test::render_vulkan(scene);
        const float diff = test::max_abs_difference(cpu.image, gpu.image);
        EXPECT_LE(diff, 1e-5f);
        std::printf("%s: largest difference %.3g\n", mode.c_str(), diff);
        // The ridges show: columns differ.
        EXPECT_GT(std::abs(cpu.image.pixel(5, 8)[0] - cpu.image.pixel(9, 8)[0]), 0.01f);
    }
}

// A glTF quad (front +z, the image upright: v down = -y) with an 8-bit normal map
// of one texel value (128, 191, 255), scale 0.5, and a TANGENT attribute of the
// frame the coordinates give (t = +x, w = +1: bitangent +y, up the image).
std::filesystem::path normal_mapped_gltf(const std::string& name) {
    const std::filesystem::path dir = test::temp_dir("normal_map_gltf");
    Image img(2, 2);
    for (std::uint32_t y = 0; y < 2; ++y) {
        for (std::uint32_t x = 0; x < 2; ++x) {
            float* p = img.pixel(x, y);
            // PNG files are written sRGB-encoded: these become the bytes 128, 191, 255.
            p[0] = float(srgb_to_linear(128.0 / 255.0));
            p[1] = float(srgb_to_linear(191.0 / 255.0));
            p[2] = 1.0f;
        }
    }
    write_image(img, dir / (name + ".png"));
    const float positions[12] = {-1, 1, 0, 1, 1, 0, 1, -1, 0, -1, -1, 0};
    const float uvs[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    const float tangents[16] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
    const std::uint16_t indices[6] = {0, 2, 1, 0, 3, 2};
    std::ofstream bin(dir / (name + ".bin"), std::ios::binary);
    bin.write(reinterpret_cast<const char*>(positions), sizeof positions);
    bin.write(reinterpret_cast<const char*>(uvs), sizeof uvs);
    bin.write(reinterpret_cast<const char*>(tangents), sizeof tangents);
    bin.write(reinterpret_cast<const char*>(indices), sizeof indices);
    bin.close();
    const std::filesystem::path file = dir / (name + ".gltf");
    std::ofstream(file) << R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1, "TANGENT": 2}, "indices": 3, "material": 0}]}],
      "materials": [{"pbrMetallicRoughness": {"metallicFactor": 0}, "normalTexture": {"index": 0, "scale": 0.5}}],
      "textures": [{"source": 0}],
      "images": [{"uri": ")" + name + R"(.png"}],
      "buffers": [{"byteLength": 156, "uri": ")" + name + R"(.bin"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                      {"buffer": 0, "byteOffset": 80, "byteLength": 64}, {"buffer": 0, "byteOffset": 144, "byteLength": 12}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC4"},
                    {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]
    })";
    return file;
}

// glTF's normalTexture: read linear (no sRGB curve), decoded with its scale, +y up
// the image. Under a light from (0, 1, 1) / sqrt 2 the quad, lit in local mode by
// its diffuse lobe (base colour 1), shows the cosine with n = unit(0, y, 1), y =
// (2 * 191 / 255 - 1) * 0.5, x = (2 * 128 / 255 - 1) * 0.5 (the 8-bit "flat").
TEST(NormalMapGltf, NormalTextureIsReadWithItsScaleAndGreenUp) {
    Scene scene = load_scene(normal_mapped_gltf("bumped"));
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    const Material& m = scene.materials.at(0);
    ASSERT_TRUE(m.normal_map.has_value());
    const TextureImage& t = scene.textures.at(*m.normal_map);
    // Kept as the file's bytes, decoded by the kernel with the texture's scale.
    EXPECT_EQ(t.format, TexelFormat::Rgba8);
    EXPECT_FALSE(t.srgb);
    EXPECT_EQ(t.normal_scale, 0.5);
    const glm::vec4 c = texel_value(t, scene.texels.words(), 0);
    EXPECT_EQ(c.r, 128.0f / 255.0f);
    EXPECT_EQ(c.g, 191.0f / 255.0f);
    EXPECT_EQ(c.b, 1.0f);
    const double x = (2.0 * 128.0 / 255.0 - 1.0) * 0.5, y = (2.0 * 191.0 / 255.0 - 1.0) * 0.5;
    scene.render.mode = RenderMode::Local;
    test::view_quad_head_on(scene, 16, 4, 0.0);
    Light light;
    light.type = LightType::Directional;
    light.direction = -glm::dvec3(0, 1, 1) / std::sqrt(2.0);
    scene.lights.push_back(light);
    const glm::dvec3 n = glm::normalize(glm::dvec3(x, y, 1.0));
    const double expected = glm::dot(n, glm::dvec3(0, 1, 1) / std::sqrt(2.0));
    const Image image = test::render_cpu(scene).image;
    // Half-float texels: a few parts in 10^4.
    EXPECT_NEAR(image.pixel(8, 8)[0], expected, 1e-3);
    EXPECT_GT(expected, 1.0 / std::sqrt(2.0) + 0.1) << "tilted toward the light, up the image";
}

TEST(NormalMapErrors, EachNamesTheMaterialAndTheFile) {
    const std::filesystem::path dir = test::temp_dir("normal_map_errors");
    const auto error_of = [&](const std::string& material) {
        return test::scene_error_of("bad_normal_map", quad_scene("local", material, glm::dvec3(0, 0, 1)));
    };
    const std::string absent = (dir / "absent.png").string();
    test::expect_error_message(error_of(R"({"normal_map": ")" + absent + R"("})"), "",
                               {"materials.m.normal_map", "absent.png", "no such file"});
    std::ofstream(dir / "garbage.png") << "not a PNG at all";
    test::expect_error_message(error_of(R"({"normal_map": ")" + (dir / "garbage.png").string() + R"("})"), "",
                               {"materials.m.normal_map", "garbage.png", "cannot read it as an image"});
    test::expect_error_message(error_of(R"({"normal_scale": 2})"), "",
                               {"materials.m.normal_scale", "needs a \"normal_map\""});
    const auto flat = constant_map("flat_for_errors", glm::vec3(0.5f, 0.5f, 1.0f));
    test::expect_error_message(error_of(R"({"normal_map": ")" + flat.string() + R"(", "normal_scale": "big"})"), "",
                               {"materials.m.normal_scale", "expected a number"});
    test::expect_error_message(error_of(R"({"normal_map": ")" + flat.string() + R"(", "normal_scale": 1e9})"), "",
                               {"materials.m.normal_scale", "expected a number from -1e6 to 1e6"});
}

}  // namespace
}  // namespace vkrt

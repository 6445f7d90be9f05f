// The JSON scene loader, in process: valid files give the exact values (defaults
// included), and every class of bad input gives a SceneError that names the file,
// the JSON path and what was wrong (docs/architecture.md, principle 5).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <string_view>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "scene/json_scene_loader.hpp"
#include "scene/limits.hpp"
#include "scene/scene_error.hpp"

namespace {

namespace fs = std::filesystem;
using vkrt::dvec3;
using vkrt::Scene;
using vkrt::SceneError;

// A valid scene whose sections can be replaced one at a time; an empty string
// leaves that section out of the file. Name the one a test changes:
// Parts{.objects = "[]"}.
struct Parts {
    std::string camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0]})";
    std::string render = "";
    std::string materials = R"({"chalk": {"diffuse": [0.8, 0.8, 0.8]}, "glass": {}})";
    std::string lights = "";
    std::string objects = R"([{"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "chalk"}])";

    std::string text() const {
        std::string out = "{";
        auto add = [&out](std::string_view key, const std::string& value) {
            if (value.empty()) return;
            out += fmt::format("{}\"{}\": {}", out.size() > 1 ? ", " : "", key, value);
        };
        add("camera", camera);
        add("render", render);
        add("materials", materials);
        add("lights", lights);
        add("objects", objects);
        return out + "}";
    }
};

void expect_vec(const dvec3& actual, const dvec3& expected) {
    EXPECT_DOUBLE_EQ(actual.x, expected.x);
    EXPECT_DOUBLE_EQ(actual.y, expected.y);
    EXPECT_DOUBLE_EQ(actual.z, expected.z);
}

class SceneLoaderTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / fmt::format("vkrt_scene_loader_{}_{}", ::getpid(), info->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path write(const std::string& text, const std::string& name = "scene.json") {
        const fs::path file = dir_ / name;
        std::ofstream(file, std::ios::binary) << text;
        return file;
    }

    Scene load(const std::string& text) { return vkrt::load_json_scene(write(text)); }

    // Loads text that must be refused; returns the message after checking that it
    // starts with the file name and contains every expected piece.
    std::string expect_error(const std::string& text, std::initializer_list<std::string_view> pieces) {
        const fs::path file = write(text);
        try {
            vkrt::load_json_scene(file);
        } catch (const SceneError& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.rfind(file.string() + ":", 0), 0u) << message;
            for (std::string_view piece : pieces) {
                EXPECT_NE(message.find(piece), std::string::npos) << "missing '" << piece << "' in: " << message;
            }
            EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
            return message;
        }
        ADD_FAILURE() << "no SceneError for: " << text;
        return {};
    }

    std::string expect_error(const Parts& parts, std::initializer_list<std::string_view> pieces) {
        return expect_error(parts.text(), pieces);
    }

    fs::path dir_;
};

// ---- valid scenes -------------------------------------------------------------

TEST_F(SceneLoaderTest, ReadsEveryFieldOfAFullScene) {
    const Scene s = load(R"({
      // comments are allowed, both kinds
      "camera": { "eye": [1, 2, 3], "look_at": [0, 1, 0], "up": [0, 0, 2], "fov": 55.5,
                  "width": 640, "height": 480 },
      "render": { "mode": "local", "aa": 3, "jitter": true, "shadows": false, "max_depth": 7,
                  "min_weight": 0.25, "corners": true, "ambient": [0.1, 0.2, 0.3], "background": [0.4, 0.5, 0.6], "seed": 4294967295,
                  "spp": 16, "loop_budget": 1000, "light_samples": 0 },
      /* zeta comes first in the file, so it is material 0 whatever the alphabet says */
      "materials": {
        "zeta": { "diffuse": [0.8, 0.7, 0.6], "kd": 0.9, "specular": [1, 1, 0.5], "ks": 0.25,
                  "shininess": 50, "reflect": [0.5, 0.25, 0], "transmit": [0, 0.75, 1], "ior": 1.33,
                  "fresnel": false, "emission": [2, 3, 4] },
        "alpha": {}
      },
      "lights": [ { "type": "point", "position": [0, 1.9, 0], "color": [1, 0.5, 0.25], "intensity": 2.5 } ],
      "objects": [
        { "type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "alpha" },
        { "type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
          "normals": [[0, 0, 2], [3, 0, 4], [0, 0, 0.5]], "material": "zeta" }
      ]
    })");

    EXPECT_EQ(s.source, dir_ / "scene.json");
    expect_vec(s.camera.eye, {1, 2, 3});
    expect_vec(s.camera.look_at, {0, 1, 0});
    expect_vec(s.camera.up, {0, 0, 2});
    EXPECT_DOUBLE_EQ(s.camera.fov, 55.5);
    EXPECT_EQ(s.camera.width, 640u);
    EXPECT_EQ(s.camera.height, 480u);

    EXPECT_EQ(s.render.mode, vkrt::RenderMode::Local);
    EXPECT_EQ(s.render.aa, 3u);
    EXPECT_TRUE(s.render.jitter);
    EXPECT_FALSE(s.render.shadows);
    EXPECT_EQ(s.render.max_depth, 7u);
    EXPECT_DOUBLE_EQ(s.render.min_weight, 0.25);
    EXPECT_TRUE(s.render.corners);
    expect_vec(s.render.ambient, {0.1, 0.2, 0.3});
    expect_vec(s.render.background, {0.4, 0.5, 0.6});
    EXPECT_EQ(s.render.seed, 4294967295u);
    EXPECT_EQ(s.render.spp, 16u);
    EXPECT_EQ(s.render.samples_per_pixel(), 16u);
    EXPECT_EQ(s.render.loop_budget, 1000u);
    EXPECT_EQ(s.render.light_samples, 0u);

    ASSERT_EQ(s.materials.size(), 2u);
    const auto& zeta = s.materials[0];
    EXPECT_EQ(zeta.name, "zeta");
    expect_vec(zeta.diffuse, {0.8, 0.7, 0.6});
    EXPECT_DOUBLE_EQ(zeta.kd, 0.9);
    expect_vec(zeta.specular, {1, 1, 0.5});
    EXPECT_DOUBLE_EQ(zeta.ks, 0.25);
    EXPECT_DOUBLE_EQ(zeta.shininess, 50);
    expect_vec(zeta.reflect, {0.5, 0.25, 0});
    expect_vec(zeta.transmit, {0, 0.75, 1});
    EXPECT_DOUBLE_EQ(zeta.ior, 1.33);
    EXPECT_FALSE(zeta.fresnel);
    EXPECT_TRUE(s.materials[1].fresnel);
    expect_vec(zeta.emission, {2, 3, 4});
    EXPECT_EQ(s.materials[1].name, "alpha");

    ASSERT_EQ(s.lights.size(), 1u);
    expect_vec(s.lights[0].position, {0, 1.9, 0});
    expect_vec(s.lights[0].color, {1, 0.5, 0.25});
    EXPECT_DOUBLE_EQ(s.lights[0].intensity, 2.5);

    ASSERT_EQ(s.spheres.size(), 1u);
    expect_vec(s.spheres[0].center, {0, 1, 0});
    EXPECT_DOUBLE_EQ(s.spheres[0].radius, 0.5);
    EXPECT_EQ(s.spheres[0].material, 1u);  // alpha: second in the file

    ASSERT_EQ(s.triangles.size(), 1u);
    const auto& t = s.triangles[0];
    expect_vec(t.vertices[0], {0, 0, 0});
    expect_vec(t.vertices[1], {1, 0, 0});
    expect_vec(t.vertices[2], {0, 1, 0});
    EXPECT_EQ(t.material, 0u);
    ASSERT_TRUE(t.normals.has_value());
    expect_vec((*t.normals)[0], {0, 0, 1});  // normalized by the loader
    expect_vec((*t.normals)[1], {0.6, 0, 0.8});
    expect_vec((*t.normals)[2], {0, 0, 1});
}

TEST_F(SceneLoaderTest, FillsDefaults) {
    const Scene s = load(R"({"camera": {"eye": [0, 1, 3], "look_at": [0, 1, 0]},
                             "materials": {"plain": {}}, "objects": []})");
    expect_vec(s.camera.up, {0, 1, 0});
    EXPECT_DOUBLE_EQ(s.camera.fov, 40.0);
    EXPECT_EQ(s.camera.width, 400u);
    EXPECT_EQ(s.camera.height, 300u);

    EXPECT_EQ(s.render.mode, vkrt::RenderMode::Local);
    EXPECT_EQ(s.render.aa, 1u);
    EXPECT_FALSE(s.render.jitter);
    EXPECT_TRUE(s.render.shadows);
    EXPECT_EQ(s.render.max_depth, 5u);
    EXPECT_DOUBLE_EQ(s.render.min_weight, 1e-3);
    EXPECT_FALSE(s.render.corners);
    expect_vec(s.render.ambient, {0, 0, 0});
    expect_vec(s.render.background, {0, 0, 0});
    EXPECT_EQ(s.render.seed, 0u);
    EXPECT_EQ(s.render.spp, 0u);
    EXPECT_EQ(s.render.loop_budget, 0u);
    EXPECT_EQ(s.render.light_samples, 16u);

    ASSERT_EQ(s.materials.size(), 1u);
    const auto& m = s.materials[0];
    EXPECT_EQ(m.name, "plain");
    expect_vec(m.diffuse, {0, 0, 0});
    EXPECT_DOUBLE_EQ(m.kd, 1.0);
    expect_vec(m.specular, {0, 0, 0});
    EXPECT_DOUBLE_EQ(m.ks, 0.0);
    EXPECT_DOUBLE_EQ(m.shininess, 20.0);
    expect_vec(m.reflect, {0, 0, 0});
    expect_vec(m.transmit, {0, 0, 0});
    EXPECT_DOUBLE_EQ(m.ior, 1.5);
    expect_vec(m.emission, {0, 0, 0});

    EXPECT_TRUE(s.lights.empty());
    EXPECT_TRUE(s.spheres.empty());
    EXPECT_TRUE(s.triangles.empty());
}

TEST_F(SceneLoaderTest, SamplesPerPixelDefaultsToAaSquared) {
    const Scene s = load(Parts{.render = R"({"aa": 4})"}.text());
    EXPECT_EQ(s.render.spp, 0u);
    EXPECT_EQ(s.render.samples_per_pixel(), 16u);
}

TEST_F(SceneLoaderTest, GridSettings) {
    EXPECT_EQ(load(Parts{}.text()).render.grid.mode, vkrt::GridMode::Auto);
    EXPECT_EQ(load(Parts{.render = R"({"grid": "off"})"}.text()).render.grid.mode, vkrt::GridMode::Off);
    EXPECT_EQ(load(Parts{.render = R"({"grid": "on"})"}.text()).render.grid.mode, vkrt::GridMode::On);
    EXPECT_EQ(load(Parts{.render = R"({"grid": "auto"})"}.text()).render.grid.mode, vkrt::GridMode::Auto);
    EXPECT_EQ(load(Parts{.render = R"({"grid": "uniform"})"}.text()).render.grid.mode, vkrt::GridMode::Uniform);
    const Scene s = load(Parts{.render = R"({"grid": {"resolution": [3, 4, 5]}})"}.text());
    EXPECT_EQ(s.render.grid.mode, vkrt::GridMode::On);
    EXPECT_EQ(s.render.grid.resolution, (std::array<std::uint32_t, 3>{3, 4, 5}));

    expect_error(Parts{.render = R"({"grid": "fast"})"}, {"render.grid", "unknown grid mode 'fast'", "\"uniform\""});
    expect_error(Parts{.render = R"({"grid": 3})"}, {"render.grid", "expected \"auto\""});
    expect_error(Parts{.render = R"({"grid": {"resolution": [3, 4]}})"}, {"render.grid.resolution", "3 whole numbers"});
    expect_error(Parts{.render = R"({"grid": {"resolution": [0, 4, 4]}})"}, {"render.grid.resolution[0]"});
    expect_error(Parts{.render = R"({"grid": {"resolution": [4, 4, 70000]}})"}, {"render.grid.resolution[2]", "65536"});
    expect_error(Parts{.render = R"({"grid": {"cells": [4, 4, 4]}})"}, {"render.grid", "unknown field 'cells'"});
}

TEST_F(SceneLoaderTest, LightDefaults) {
    const Scene s = load(Parts{.lights = R"([{"type": "point", "position": [1, 2, 3]}])"}.text());
    ASSERT_EQ(s.lights.size(), 1u);
    expect_vec(s.lights[0].position, {1, 2, 3});
    expect_vec(s.lights[0].color, {1, 1, 1});
    EXPECT_DOUBLE_EQ(s.lights[0].intensity, 1.0);
}

// Directions are made unit; angles are degrees in the file, radians in the scene.
TEST_F(SceneLoaderTest, SpotAndDirectionalLights) {
    const Scene s = load(Parts{.lights = R"([
        {"type": "spot", "position": [1, 2, 3], "direction": [0, -2, 0], "inner_angle": 10, "outer_angle": 30,
         "color": [1, 0.5, 0.25], "intensity": 4},
        {"type": "directional", "direction": [3, 0, -4], "intensity": 0.5},
        {"type": "spot", "position": [0, 0, 0], "direction": [0, 0, -1e-3]}])"}.text());
    ASSERT_EQ(s.lights.size(), 3u);
    const vkrt::Light& spot = s.lights[0];
    EXPECT_EQ(spot.type, vkrt::LightType::Spot);
    expect_vec(spot.position, {1, 2, 3});
    expect_vec(spot.direction, {0, -1, 0});
    EXPECT_DOUBLE_EQ(spot.inner_angle, M_PI / 18.0);
    EXPECT_DOUBLE_EQ(spot.outer_angle, M_PI / 6.0);
    expect_vec(spot.color, {1, 0.5, 0.25});
    EXPECT_DOUBLE_EQ(spot.intensity, 4.0);
    const vkrt::Light& sun = s.lights[1];
    EXPECT_EQ(sun.type, vkrt::LightType::Directional);
    expect_vec(sun.direction, {0.6, 0, -0.8});
    expect_vec(sun.color, {1, 1, 1});
    EXPECT_DOUBLE_EQ(sun.intensity, 0.5);
    // The cone's defaults: 0 and 45 degrees.
    EXPECT_DOUBLE_EQ(s.lights[2].inner_angle, 0.0);
    EXPECT_DOUBLE_EQ(s.lights[2].outer_angle, M_PI / 4.0);
    expect_vec(s.lights[2].direction, {0, 0, -1});
    const Scene points = load(Parts{.lights = R"([{"type": "point", "position": [1, 2, 3]}])"}.text());
    EXPECT_EQ(points.lights[0].type, vkrt::LightType::Point);
}

TEST_F(SceneLoaderTest, SpotAndDirectionalLightErrors) {
    const std::string spot = R"("type": "spot", "position": [0, 0, 0])";
    auto lights = [](const std::string& fields) { return Parts{.lights = "[{" + fields + "}]"}; };
    expect_error(lights(spot), {": lights[0].direction: required field is missing"});
    expect_error(lights(R"("type": "directional")"), {": lights[0].direction: required field is missing"});
    expect_error(lights(R"("type": "directional", "direction": [0, 0, 0])"),
                 {": lights[0].direction: expected a non-zero vector", "got [0, 0, 0]"});
    expect_error(lights(spot + R"(, "direction": [0, 0, 0])"), {": lights[0].direction: expected a non-zero vector"});
    expect_error(lights(R"("type": "directional", "direction": [0, 1e999, 0])"), {": lights[0].direction[1]"});
    expect_error(lights(R"("type": "directional", "direction": [0, -1])"), {": lights[0].direction"});
    expect_error(lights(spot + R"(, "direction": [0, -1, 0], "inner_angle": 30, "outer_angle": 30)"),
                 {": lights[0].inner_angle: expected an angle in degrees below outer_angle (30), got 30"});
    expect_error(lights(spot + R"(, "direction": [0, -1, 0], "inner_angle": 40, "outer_angle": 20)"),
                 {": lights[0].inner_angle: expected an angle in degrees below outer_angle (20), got 40"});
    expect_error(lights(spot + R"(, "direction": [0, -1, 0], "inner_angle": 50)"),
                 {": lights[0].inner_angle: expected an angle in degrees below outer_angle (45, its default), got 50"});
    expect_error(lights(spot + R"(, "direction": [0, -1, 0], "inner_angle": -1)"),
                 {": lights[0].inner_angle: expected a number >= 0, got -1"});
    expect_error(lights(spot + R"(, "direction": [0, -1, 0], "outer_angle": 91)"),
                 {": lights[0].outer_angle: expected an angle in degrees above 0 and at most 90, got 91"});
    expect_error(lights(spot + R"(, "direction": [0, -1, 0], "outer_angle": 0)"),
                 {": lights[0].outer_angle: expected an angle in degrees above 0 and at most 90, got 0"});
    expect_error(lights(spot + R"(, "direction": [0, -1, 0], "outer_angle": "wide")"), {": lights[0].outer_angle"});
    // Each kind takes its own fields only.
    expect_error(lights(R"("type": "point", "position": [0, 0, 0], "direction": [0, -1, 0])"),
                 {": lights[0]: unknown field 'direction'"});
    expect_error(lights(R"("type": "directional", "direction": [0, -1, 0], "position": [0, 0, 0])"),
                 {": lights[0]: unknown field 'position'"});
    expect_error(lights(R"("type": "directional", "direction": [0, -1, 0], "outer_angle": 20)"),
                 {": lights[0]: unknown field 'outer_angle'"});
    expect_error(lights(spot + R"(, "direction": [0, -1, 0], "angle": 20)"),
                 {": lights[0]: unknown field 'angle'", "inner_angle", "outer_angle"});
    expect_error(lights(R"("type": "directional", "direction": [0, -1, 0], "intensity": -1)"),
                 {": lights[0].intensity: expected a number >= 0, got -1"});
}

TEST_F(SceneLoaderTest, QuadBecomesOneParallelogramFacingCrossOfEdges) {
    const Scene s = load(Parts{.objects = R"([{"type": "quad", "corner": [1, 2, 3], "edge1": [2, 0, 0],
                                           "edge2": [0, 0, -4], "material": "glass"}])"}
                             .text());
    ASSERT_EQ(s.triangles.size(), 1u);
    const auto& q = s.triangles[0];
    EXPECT_TRUE(q.parallelogram);
    expect_vec(q.vertices[0], {1, 2, 3});   // corner
    expect_vec(q.vertices[1], {3, 2, 3});   // corner + e1
    expect_vec(q.vertices[2], {3, 2, -1});  // corner + e1 + e2
    EXPECT_FALSE(q.normals.has_value());
    EXPECT_EQ(q.material, 1u);
    // cross((2,0,0), (0,0,-4)) = (0,8,0): the front faces +y.
    const dvec3 n = glm::cross(q.vertices[1] - q.vertices[0], q.vertices[2] - q.vertices[0]);
    EXPECT_GT(n.y, 0.0);
    EXPECT_DOUBLE_EQ(n.x, 0.0);
    EXPECT_DOUBLE_EQ(n.z, 0.0);
}

TEST_F(SceneLoaderTest, AcceptsWholeNumbersWrittenAsFloats) {
    const Scene s = load(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "width": 64.0, "height": 4.8e1})"}.text());
    EXPECT_EQ(s.camera.width, 64u);
    EXPECT_EQ(s.camera.height, 48u);
}

TEST_F(SceneLoaderTest, AcceptsZeroReflectAndTransmit) {
    const Scene s = load(Parts{.materials = R"({"chalk": {"reflect": [0, 0, 0], "transmit": [0, 0, 0]}})"}.text());
    ASSERT_EQ(s.materials.size(), 1u);
    expect_vec(s.materials[0].reflect, {0, 0, 0});
}

TEST_F(SceneLoaderTest, AcceptsLargestImage) {
    const Scene s = load(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "width": 8192, "height": 4096})"}.text());
    EXPECT_EQ(std::uint64_t(s.camera.width) * s.camera.height, vkrt::limits::kMaxImagePixels);
    // Corner rays add a row and a column: the same image is then too large.
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "width": 8192, "height": 4096})",
                       .render = R"({"corners": true})"},
                 {": render.corners: image of 8192x4096 pixels traces 8193x4097 corner rays (render.corners), more "
                  "than the limit of 33554432"});
    load(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "width": 8191, "height": 4095})",
               .render = R"({"corners": true})"}.text());
}

// ---- files and syntax ---------------------------------------------------------

// Vectors of tiny but non-zero length are valid directions: their lengths must not
// underflow into "zero vector" errors or NaN normals.
TEST_F(SceneLoaderTest, TinyVectorsAreDirectionsNotZero) {
    const Scene s = load(R"({"camera": {"eye": [1e-300, 0, 3], "look_at": [0, 0, 0], "up": [0, 1e-300, 0]},
        "materials": {"m": {}},
        "objects": [{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                     "normals": [[0, 0, 1e-300], [0, 0, 2], [3e-200, 0, 4e-200]], "material": "m"}]})");
    EXPECT_EQ(s.camera.up.y, 1e-300);
    const auto& n = *s.triangles[0].normals;
    expect_vec(n[0], {0, 0, 1});
    expect_vec(n[1], {0, 0, 1});
    expect_vec(n[2], {0.6, 0, 0.8});
}

TEST_F(SceneLoaderTest, MissingFile) {
    const fs::path file = dir_ / "nope.json";
    try {
        vkrt::load_json_scene(file);
        ADD_FAILURE() << "no error";
    } catch (const SceneError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(file.string() + ": cannot open scene file (", 0), 0u) << message;
        EXPECT_NE(message.find("No such file"), std::string::npos) << message;
    }
}

TEST_F(SceneLoaderTest, DirectoryInsteadOfFile) {
    try {
        vkrt::load_json_scene(dir_);
        ADD_FAILURE() << "no error";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(dir_.string() + ": cannot open scene file", 0), 0u) << e.what();
    }
}

TEST_F(SceneLoaderTest, MalformedJsonGivesLineAndColumn) {
    const std::string file = (dir_ / "scene.json").string();
    // The stray comma is line 3, column 31.
    std::string m = expect_error("{\n  // a comment\n  \"camera\": {\"eye\": [0, 1, 3],, \"look_at\": [0, 1, 0]}\n}",
                                 {"invalid JSON"});
    EXPECT_EQ(m.rfind(file + ":3:31: invalid JSON: ", 0), 0u) << m;
    m = expect_error("{\"camera\": {", {"invalid JSON", "end of input"});
    EXPECT_EQ(m.rfind(file + ":1:13: ", 0), 0u) << m;
    m = expect_error("", {"invalid JSON"});
    EXPECT_EQ(m.rfind(file + ":1:1: ", 0), 0u) << m;
    // Columns count characters, not UTF-8 bytes.
    m = expect_error("{\"é\": x}", {"invalid JSON"});
    EXPECT_EQ(m.rfind(file + ":1:7: ", 0), 0u) << m;
    expect_error("{} /* unterminated", {"invalid JSON", "comment"});
}

TEST_F(SceneLoaderTest, TopLevelMustBeAnObject) {
    expect_error("[1, 2]", {"expected a JSON object at the top level", "got an array of 2 elements"});
}

TEST_F(SceneLoaderTest, DuplicateKey) {
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "fov": 30, "fov": 60})"},
                 {": camera: ", "'fov'", "more than once"});
}

// Paths are built only for messages; they must still name the right element.
TEST_F(SceneLoaderTest, DuplicateKeyDeepInAnArrayNamesItsPath) {
    expect_error(Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "chalk"},
                                     {"type": "sphere", "center": [0, 0, 0], "radius": 1, "radius": 2}])"},
                 {": objects[1]: ", "'radius'", "more than once"});
}

// Past a few members an object's keys are looked up in a set: the last key of
// many, repeating the first, must still be caught, and a repeat of one added
// after the set was made.
TEST_F(SceneLoaderTest, DuplicateKeyInALargeObject) {
    auto many = [](int n, const std::string& last) {
        std::string m = R"({"chalk": {"diffuse": [0.8, 0.8, 0.8]})";
        for (int i = 0; i < n; ++i) m += fmt::format(R"(, "m{}": {{}})", i);
        return m + fmt::format(R"(, "{}": {{}}}})", last);
    };
    expect_error(Parts{.materials = many(40, "chalk")}, {": materials: ", "'chalk'", "more than once"});
    expect_error(Parts{.materials = many(40, "m30")}, {": materials: ", "'m30'", "more than once"});
    EXPECT_NO_THROW(load(Parts{.materials = many(40, "m40")}.text()));
}

// Paths come from the document's parents: values after a closed container, and
// keys that need quoting, are named as an editor would find them.
TEST_F(SceneLoaderTest, PathsAfterNestedContainers) {
    expect_error(Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "chalk"},
                                      {"type": "sphere", "center": [0, [1], 0], "radius": 1, "material": "chalk"}])"},
                 {": objects[1].center[1]: expected a number, got an array of 1 element"});
    expect_error(Parts{.materials = R"({"my glass": {"diffuse": [1, 1, 1]}, "x": {"diffuse": [1, -1, 1]}})"},
                 {": materials.x.diffuse[1]: expected a number >= 0, got -1"});
    expect_error(Parts{.materials = R"({"my glass": {"diffuse": [1, 1, true]}})"},
                 {": materials[\"my glass\"].diffuse[2]: expected a number, got a boolean (true)"});
    expect_error(Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 1e999]}])"},
                 {": objects[0].center[2]: expected a finite number, got 1e999 (too large for a double)"});
}

TEST_F(SceneLoaderTest, AbsurdNesting) {
    expect_error(Parts{.objects = std::string(200, '[') + std::string(200, ']')}, {"objects[0]", "nesting"});
}

// ---- missing and unknown fields -----------------------------------------------

TEST_F(SceneLoaderTest, MissingRequiredFields) {
    Parts no_camera;
    no_camera.camera.clear();
    expect_error(no_camera, {": camera: required field is missing"});
    Parts no_materials;
    no_materials.materials.clear();
    expect_error(no_materials, {": materials: required field is missing"});
    Parts no_objects;
    no_objects.objects.clear();
    expect_error(no_objects, {": objects: required field is missing"});
    expect_error(Parts{.camera = R"({"look_at": [0, 1, 0]})"}, {": camera.eye: required field is missing"});
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3]})"}, {": camera.look_at: required field is missing"});
    expect_error(Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 0], "material": "chalk"}])"},
                 {": objects[0].radius: required field is missing"});
    expect_error(Parts{.objects = R"([{"center": [0, 0, 0], "radius": 1, "material": "chalk"}])"},
                 {": objects[0].type: required field is missing"});
    expect_error(Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1}])"},
                 {": objects[0].material: required field is missing"});
    expect_error(Parts{.lights = R"([{"type": "point"}])"}, {": lights[0].position: required field is missing"});
    expect_error(Parts{.lights = R"([{"position": [0, 0, 0]}])"}, {": lights[0].type: required field is missing"});
}

TEST_F(SceneLoaderTest, UnknownFieldsAreErrors) {
    const std::string m = expect_error(
        Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 0], "radus": 1, "material": "chalk"}])"}, {});
    EXPECT_NE(m.find(": objects[0]: unknown field 'radus' (expected one of: center, radius, material, type)"),
              std::string::npos)
        << m;
    Parts top;
    top.lights = "[]";
    expect_error(top.text().replace(0, 1, "{\"objcts\": [], "), {"unknown field 'objcts'", "objects"});
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "fvo": 30})"},
                 {": camera: unknown field 'fvo'", "fov"});
    expect_error(Parts{.render = R"({"shadow": false})"}, {": render: unknown field 'shadow'", "shadows"});
    expect_error(Parts{.materials = R"({"m": {"difuse": [1, 1, 1]}})"}, {": materials.m: unknown field 'difuse'"});
    expect_error(Parts{.lights = R"([{"type": "point", "position": [0, 0, 0], "colour": [1, 1, 1]}])"},
                 {": lights[0]: unknown field 'colour'"});
    expect_error(Parts{.objects = R"([{"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0],
                                   "normals": [], "material": "chalk"}])"},
                 {": objects[0]: unknown field 'normals'"});
}

// ---- types ------------------------------------------------------------------------

TEST_F(SceneLoaderTest, WrongTypes) {
    expect_error(Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 0], "radius": "1", "material": "chalk"}])"},
                 {": objects[0].radius: expected a number, got a string"});
    expect_error(Parts{.camera = R"([0, 1, 3])"}, {": camera: expected an object, got an array"});
    expect_error(Parts{.camera = R"({"eye": [0, 1], "look_at": [0, 1, 0]})"},
                 {": camera.eye: expected an array of 3 numbers, got an array of 2 elements"});
    expect_error(Parts{.camera = R"({"eye": [0, null, 3], "look_at": [0, 1, 0]})"},
                 {": camera.eye[1]: expected a number, got null"});
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "width": 2.5})"},
                 {": camera.width: expected a whole number, got 2.5"});
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "height": "300"})"},
                 {": camera.height: expected a whole number, got a string"});
    expect_error(Parts{.render = R"({"jitter": "yes"})"}, {": render.jitter: expected true or false, got a string"});
    expect_error(Parts{.render = R"({"mode": 1})"}, {": render.mode: expected a string, got a number (1)"});
    expect_error(Parts{.materials = "[]"}, {": materials: expected an object, got an array"});
    expect_error(Parts{.materials = R"({"m": 1})"}, {": materials.m: expected an object, got a number"});
    expect_error(Parts{.objects = "{}"}, {": objects: expected an array, got an object"});
    expect_error(Parts{.lights = R"({"type": "point"})"}, {": lights: expected an array, got an object"});
    expect_error(Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": 3}])"},
                 {": objects[0].material: expected a string, got a number"});
    expect_error(Parts{.objects = R"([{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0]], "material": "chalk"}])"},
                 {": objects[0].vertices: expected an array of 3 points, got an array of 2 elements"});
    expect_error(Parts{.objects = R"([{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], 7], "material": "chalk"}])"},
                 {": objects[0].vertices[2]: expected an array of 3 numbers, got a number"});
}

TEST_F(SceneLoaderTest, KeysThatAreNotIdentifiersAreQuotedInPaths) {
    expect_error(Parts{.materials = R"({"my glass": {"kd": -1}})"},
                 {": materials[\"my glass\"].kd: expected a number >= 0, got -1"});
}

// ---- numbers ------------------------------------------------------------------------

TEST_F(SceneLoaderTest, InfiniteNumbersAreRefusedWithTheirPath) {
    expect_error(Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1e999, "material": "chalk"}])"},
                 {": objects[0].radius: expected a finite number", "1e999"});
    expect_error(Parts{.objects = R"([{"type": "sphere", "center": [0, -1e999, 0], "radius": 1, "material": "chalk"}])"},
                 {": objects[0].center[1]: expected a finite number", "-1e999"});
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "fov": 1e400})"},
                 {": camera.fov: expected a finite number"});
}

TEST_F(SceneLoaderTest, HugeMagnitudesAreRefused) {
    expect_error(Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1e30, "material": "chalk"}])"},
                 {": objects[0].radius: expected a number of magnitude at most"});
}

TEST_F(SceneLoaderTest, RadiusMustBePositive) {
    expect_error(Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 0], "radius": -1, "material": "chalk"}])"},
                 {": objects[0].radius: expected a number > 0, got -1"});
    expect_error(Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 0], "radius": 0, "material": "chalk"}])"},
                 {": objects[0].radius: expected a number > 0, got 0"});
}

TEST_F(SceneLoaderTest, FieldOfViewIsStrictlyInsideZeroTo180) {
    for (const char* fov : {"0", "180", "-5", "200"}) {
        expect_error(Parts{.camera = fmt::format(R"({{"eye": [0, 1, 3], "look_at": [0, 1, 0], "fov": {}}})", fov)},
                     {": camera.fov: expected a number strictly between 0 and 180, got"});
    }
}

TEST_F(SceneLoaderTest, ALensHasARadiusAndAFocusDistance) {
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "lens_radius": -0.1})"},
                 {": camera.lens_radius: expected a number >= 0, got -0.1"});
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "lens_radius": 0.1, "focus_distance": 0})"},
                 {": camera.focus_distance: expected a number > 0, got 0"});
}

TEST_F(SceneLoaderTest, ImageSizeLimits) {
    const std::string side = std::to_string(vkrt::limits::kMaxImageSide);
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "width": 0})"},
                 {": camera.width: expected a whole number in [1, " + side + "], got 0"});
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "height": 0})"},
                 {": camera.height: expected a whole number in [1, "});
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "width": 100000})"},
                 {": camera.width: expected a whole number in [1, " + side + "], got 100000"});
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "width": -3})"},
                 {": camera.width: expected a whole number", "got -3"});
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "width": 30000, "height": 30000})"},
                 {": camera: image of 30000x30000 pixels is larger than the limit of " +
                  std::to_string(vkrt::limits::kMaxImagePixels) + " pixels"});
}

TEST_F(SceneLoaderTest, RenderRanges) {
    expect_error(Parts{.render = R"({"aa": 0})"}, {": render.aa: expected a whole number in [1, 64], got 0"});
    expect_error(Parts{.render = R"({"aa": 65})"}, {": render.aa: expected a whole number in [1, 64], got 65"});
    expect_error(Parts{.render = R"({"max_depth": 65})"}, {": render.max_depth: expected a whole number in [0, 64]"});
    expect_error(Parts{.render = R"({"min_weight": -0.1})"}, {": render.min_weight: expected a number >= 0, got -0.1"});
    expect_error(Parts{.render = R"({"min_weight": 2})"}, {": render.min_weight: expected a number from 0 to 1, got 2"});
    expect_error(Parts{.render = R"({"corners": 1})"}, {": render.corners: expected true or false"});
    expect_error(Parts{.render = R"({"spp": 0})"}, {": render.spp: expected a whole number in [1, "});
    expect_error(Parts{.render = R"({"loop_budget": 65001})"},
                 {": render.loop_budget: expected a whole number in [1, 65000], got 65001"});
    expect_error(Parts{.render = R"({"light_samples": -1})"},
                 {": render.light_samples: expected a whole number in [0, 1024], got -1"});
    expect_error(Parts{.render = R"({"light_samples": 1025})"},
                 {": render.light_samples: expected a whole number in [0, 1024], got 1025"});
    expect_error(Parts{.render = R"({"light_samples": 1.5})"}, {": render.light_samples: expected a whole number"});
    expect_error(Parts{.render = R"({"seed": -1})"}, {": render.seed: expected a whole number in [0, 4294967295], got -1"});
    expect_error(Parts{.render = R"({"seed": 4294967296})"}, {": render.seed: expected a whole number in [0, 4294967295]"});
    expect_error(Parts{.render = R"({"ambient": [0, -0.5, 0]})"}, {": render.ambient[1]: expected a number >= 0, got -0.5"});
    expect_error(Parts{.render = R"({"background": [0, 0]})"}, {": render.background: expected an array of 3 numbers"});
}

TEST_F(SceneLoaderTest, MaterialRanges) {
    expect_error(Parts{.materials = R"({"m": {"diffuse": [0.5, -0.1, 0]}})"},
                 {": materials.m.diffuse[1]: expected a number >= 0, got -0.1"});
    expect_error(Parts{.materials = R"({"m": {"emission": [0, 0, -1]}})"}, {": materials.m.emission[2]: expected a number >= 0"});
    expect_error(Parts{.materials = R"({"m": {"kd": -1}})"}, {": materials.m.kd: expected a number >= 0, got -1"});
    expect_error(Parts{.materials = R"({"m": {"ks": -0.5}})"}, {": materials.m.ks: expected a number >= 0"});
    expect_error(Parts{.materials = R"({"m": {"shininess": -2}})"}, {": materials.m.shininess: expected a number >= 0"});
    expect_error(Parts{.materials = R"({"m": {"ior": 0}})"}, {": materials.m.ior: expected a number > 0, got 0"});
}

TEST_F(SceneLoaderTest, MetallicRoughnessMaterials) {
    const Scene s = load(Parts{.render = R"({"mode": "global"})",
                               .materials = R"({"gold": {"base_color": [1, 0.8, 0.3], "metallic": 1, "roughness": 0.25,
                                                         "emission": [0, 0, 1]},
                                                "plastic": {"roughness": 0.5}, "chalk": {}})"}
                             .text());
    ASSERT_EQ(s.materials.size(), 3u);
    ASSERT_TRUE(s.materials[0].metallic_roughness.has_value());
    expect_vec(s.materials[0].metallic_roughness->base_color, {1, 0.8, 0.3});
    EXPECT_DOUBLE_EQ(s.materials[0].metallic_roughness->metallic, 1.0);
    EXPECT_DOUBLE_EQ(s.materials[0].metallic_roughness->roughness, 0.25);
    expect_vec(s.materials[0].emission, {0, 0, 1});
    // The defaults: a white dielectric.
    ASSERT_TRUE(s.materials[1].metallic_roughness.has_value());
    expect_vec(s.materials[1].metallic_roughness->base_color, {1, 1, 1});
    EXPECT_DOUBLE_EQ(s.materials[1].metallic_roughness->metallic, 0.0);
    EXPECT_DOUBLE_EQ(s.materials[1].metallic_roughness->roughness, 0.5);
    EXPECT_TRUE(s.warnings.empty());
    EXPECT_FALSE(load(Parts{}.text()).materials[0].metallic_roughness.has_value()) << "Phong by default";
    EXPECT_FALSE(s.materials[1].metallic_roughness->has_specular());
    // glTF's KHR_materials_specular, by its factors' names.
    const Scene specular = load(Parts{.materials = R"({"chalk": {"specular_factor": 0.5, "specular_color": [2, 1, 0]}})"}.text());
    ASSERT_TRUE(specular.materials[0].metallic_roughness.has_value());
    EXPECT_DOUBLE_EQ(specular.materials[0].metallic_roughness->specular, 0.5);
    expect_vec(specular.materials[0].metallic_roughness->specular_color, {2, 1, 0});
    EXPECT_TRUE(specular.materials[0].metallic_roughness->has_specular());

    expect_error(Parts{.materials = R"({"m": {"metallic": 1, "diffuse": [1, 1, 1]}})"},
                 {": materials.m.diffuse: a metallic-roughness material (base_color, metallic, roughness, transmission) has no Phong fields"});
    expect_error(Parts{.materials = R"({"m": {"transmission": 1.5}})"},
                 {": materials.m.transmission: expected a number between 0 and 1, got 1.5"});
    expect_error(Parts{.materials = R"({"m": {"transmission": 1, "ior": 0}})"},
                 {": materials.m.ior: expected a number > 0, got 0"});
    expect_error(Parts{.materials = R"({"m": {"sheen_roughness": 0.5}})"},
                 {": materials.m.sheen_roughness: a sheen's roughness needs \"sheen_color\""});
    expect_error(Parts{.materials = R"({"m": {"sheen_color": [1, 2, 1]}})"},
                 {": materials.m.sheen_color[1]: expected a number between 0 and 1, got 2"});
    expect_error(Parts{.materials = R"({"m": {"base_color": [1, 1, 1], "clearcoat_roughness_texture": "c.png"}})"},
                 {": materials.m.clearcoat_roughness_texture: a clear coat roughness texture needs \"clearcoat\""});
    expect_error(Parts{.materials = R"({"m": {"roughness": 1, "sheen_color_texture": "s.png"}})"},
                 {": materials.m.sheen_color_texture: a sheen colour texture needs \"sheen_color\""});
    expect_error(Parts{.materials = R"({"m": {"specular_color": [1, 1, 1], "specular_texture": "s.png"}})"},
                 {": materials.m.specular_texture: a specular texture needs \"specular_factor\""});
    expect_error(Parts{.materials = R"({"m": {"specular_factor": 1, "specular_color_texture": "s.png"}})"},
                 {": materials.m.specular_color_texture: a specular colour texture needs \"specular_color\""});
    expect_error(Parts{.materials = R"({"m": {"specular_factor": 2}})"},
                 {": materials.m.specular_factor: expected a number between 0 and 1, got 2"});
    expect_error(Parts{.materials = R"({"m": {"specular_color": [1, -1, 1]}})"},
                 {": materials.m.specular_color[1]: expected a number >= 0, got -1"});
    expect_error(Parts{.materials = R"({"m": {"specular_color": [1, 1, 1], "specular": [1, 1, 1]}})"},
                 {": materials.m.specular: a metallic-roughness material (base_color, metallic, roughness, transmission) has no Phong fields"});
    expect_error(Parts{.materials = R"({"m": {"clearcoat": 1.5}})"},
                 {": materials.m.clearcoat: expected a number between 0 and 1, got 1.5"});
    expect_error(Parts{.materials = R"({"m": {"clearcoat_roughness": 0.5}})"},
                 {": materials.m.clearcoat_roughness: a clear coat's roughness needs \"clearcoat\""});
    expect_error(Parts{.materials = R"({"m": {"attenuation_distance": 1}})"},
                 {": materials.m.attenuation_distance: attenuation is inside a solid"});
    expect_error(Parts{.materials = R"({"m": {"roughness": 1.5}})"},
                 {": materials.m.roughness: expected a number between 0 and 1, got 1.5"});
    expect_error(Parts{.materials = R"({"m": {"metallic": -0.1}})"},
                 {": materials.m.metallic: expected a number between 0 and 1, got -0.1"});
    expect_error(Parts{.materials = R"({"m": {"base_color": [1, 2, 0]}})"},
                 {": materials.m.base_color[1]: expected a number between 0 and 1, got 2"});
}

// Local mode and the paper's estimator shade the diffuse lobe alone, and say so.
TEST_F(SceneLoaderTest, MetallicRoughnessOutsideThePathEstimatorIsWarnedOf) {
    const std::string materials = R"({"gold": {"metallic": 1}, "chalk": {"diffuse": [1, 1, 1]}, "plastic": {"roughness": 0}})";
    const Scene local = load(Parts{.materials = materials}.text());
    ASSERT_EQ(local.warnings.size(), 1u);
    EXPECT_NE(local.warnings[0].find("materials 'gold', 'plastic' shaded by the diffuse lobe alone: local mode"),
              std::string::npos)
        << local.warnings[0];
    const Scene paper = load(Parts{.render = R"({"mode": "global", "estimator": "paper"})", .materials = materials}.text());
    ASSERT_EQ(paper.warnings.size(), 1u);
    EXPECT_NE(paper.warnings[0].find("the paper estimator"), std::string::npos) << paper.warnings[0];
}

TEST_F(SceneLoaderTest, LightRanges) {
    expect_error(Parts{.lights = R"([{"type": "point", "position": [0, 0, 0], "intensity": -1}])"},
                 {": lights[0].intensity: expected a number >= 0, got -1"});
    expect_error(Parts{.lights = R"([{"type": "point", "position": [0, 0, 0], "color": [1, -1, 1]}])"},
                 {": lights[0].color[1]: expected a number >= 0"});
}

// ---- camera geometry ------------------------------------------------------------

TEST_F(SceneLoaderTest, CameraGeometry) {
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "up": [0, 0, 0]})"},
                 {": camera.up: expected a non-zero vector, got [0, 0, 0]"});
    expect_error(Parts{.camera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "up": [0, 0, -2]})"},
                 {": camera.up: ", "parallel to the view direction"});
    expect_error(Parts{.camera = R"({"eye": [0, 5, 0], "look_at": [0, 1, 0]})"},
                 {": camera.up: the default up [0, 1, 0] is parallel"});
    expect_error(Parts{.camera = R"({"eye": [1, 2, 3], "look_at": [1, 2, 3]})"},
                 {": camera.look_at: look_at must differ from eye"});
}

// ---- references and geometry of objects ------------------------------------------

TEST_F(SceneLoaderTest, UnknownMaterial) {
    expect_error(
        Parts{.objects = R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "chalk"},
                         {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glass"},
                         {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "chalk2"}])"},
        {": objects[2].material: unknown material 'chalk2' (defined: chalk, glass)"});
    expect_error(Parts{.materials = "{}"}, {": objects[0].material: unknown material 'chalk' (no materials are defined)"});
}

TEST_F(SceneLoaderTest, UnknownTypes) {
    expect_error(Parts{.objects = R"([{"type": "cube", "material": "chalk"}])"},
                 {": objects[0].type: unknown object type 'cube' (expected one of: sphere, triangle, ring, cylinder, quad, mesh, gltf, instance, random_spheres, sphereflake, torus_knot)"});
    expect_error(Parts{.lights = R"([{"type": "sun", "direction": [0, -1, 0]}])"},
                 {": lights[0].type: unknown light type 'sun' (expected one of: point, spot, directional)"});
}

// Exporters write triangles of zero area and zero vertex normals: one warning each,
// counting them, naming the first.
TEST_F(SceneLoaderTest, ZeroAreaTrianglesAreDroppedWithOneWarning) {
    const Scene s = load(Parts{.objects = R"([
        {"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "material": "chalk"},
        {"type": "triangle", "vertices": [[0, 0, 0], [1, 1, 1], [2, 2, 2]], "material": "chalk"},
        {"type": "triangle", "vertices": [[0.1, 0.2, 0.3], [0.2, 0.4, 0.6], [0.3, 0.6, 0.9]], "material": "chalk"},
        {"type": "triangle", "vertices": [[1, 1, 1], [1, 1, 1], [0, 1, 0]], "material": "chalk"}])"}
                             .text());
    ASSERT_EQ(s.triangles.size(), 1u);
    expect_vec(s.triangles[0].vertices[1], {1, 0, 0});
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("skipped 3 triangles of zero area"), std::string::npos) << s.warnings[0];
    EXPECT_NE(s.warnings[0].find("the first at objects[1].vertices"), std::string::npos) << s.warnings[0];
}

TEST_F(SceneLoaderTest, ZeroVertexNormalsFallBackToTheFaceNormalWithOneWarning) {
    const Scene s = load(Parts{.objects = R"([
        {"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "normals": [[0, 0, 2], [0, 0, 0], [0, 1, 1]],
         "material": "chalk"},
        {"type": "triangle", "vertices": [[0, 0, 0], [0, 1, 0], [1, 0, 0]], "normals": [[0, 0, 0], [0, 0, 0], [0, 0, 0]],
         "material": "chalk"},
        {"type": "triangle", "vertices": [[0, 0, 0], [1, 1, 1], [2, 2, 2]], "normals": [[0, 0, 0], [0, 0, 1], [0, 0, 1]],
         "material": "chalk"}])"}
                             .text());
    ASSERT_EQ(s.triangles.size(), 2u);
    ASSERT_TRUE(s.triangles[0].normals.has_value());
    expect_vec((*s.triangles[0].normals)[0], {0, 0, 1});
    expect_vec((*s.triangles[0].normals)[1], {0, 0, 1});  // the face's
    EXPECT_NEAR((*s.triangles[0].normals)[2].y, std::sqrt(0.5), 1e-12);
    for (const dvec3& n : *s.triangles[1].normals) expect_vec(n, {0, 0, -1});  // wound the other way
    // The third, of zero area, is dropped: its zero normal is not counted.
    ASSERT_EQ(s.warnings.size(), 2u);
    EXPECT_NE(s.warnings[0].find("skipped 1 triangle of zero area"), std::string::npos) << s.warnings[0];
    EXPECT_NE(s.warnings[1].find("2 triangles with a zero vertex normal"), std::string::npos) << s.warnings[1];
    EXPECT_NE(s.warnings[1].find("the first at objects[0].normals[1]"), std::string::npos) << s.warnings[1];
}

TEST_F(SceneLoaderTest, DegenerateGeometry) {
    expect_error(Parts{.objects = R"([{"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [-2, 0, 0], "material": "chalk"}])"},
                 {": objects[0].edge2: ", "parallel"});
    expect_error(Parts{.objects = R"([{"type": "quad", "corner": [0, 0, 0], "edge1": [0, 0, 0], "edge2": [0, 1, 0], "material": "chalk"}])"},
                 {": objects[0].edge1: expected a non-zero vector"});
}

// ---- rings and cylinders ------------------------------------------------------------

TEST_F(SceneLoaderTest, RingValuesDefaultsAndNormalizedNormal) {
    const Scene s = load(Parts{.objects = R"([
        {"type": "ring", "center": [1, 2, 3], "normal": [0, 3, 4], "inner": 0.5, "outer": 2, "material": "glass"},
        {"type": "ring", "center": [0, 0, 0], "normal": [0, 0, -7], "outer": 1, "material": "chalk"}])"}
                             .text());
    ASSERT_EQ(s.rings.size(), 2u);
    expect_vec(s.rings[0].center, {1, 2, 3});
    expect_vec(s.rings[0].normal, {0, 0.6, 0.8});  // normalized by the loader
    EXPECT_DOUBLE_EQ(s.rings[0].inner, 0.5);
    EXPECT_DOUBLE_EQ(s.rings[0].outer, 2.0);
    EXPECT_EQ(s.rings[0].material, 1u);
    expect_vec(s.rings[1].normal, {0, 0, -1});
    EXPECT_DOUBLE_EQ(s.rings[1].inner, 0.0);  // default: a disc
    EXPECT_EQ(s.rings[1].material, 0u);
}

TEST_F(SceneLoaderTest, CylinderValuesAndDefaults) {
    const Scene s = load(Parts{.objects = R"([
        {"type": "cylinder", "base": [1, 2, 3], "top": [1, 5, 3], "radius": 0.25, "capped": true, "material": "glass"},
        {"type": "cylinder", "base": [0, 0, 0], "top": [-1, 0, 0], "radius": 2, "material": "chalk"}])"}
                             .text());
    ASSERT_EQ(s.cylinders.size(), 2u);
    expect_vec(s.cylinders[0].base, {1, 2, 3});
    expect_vec(s.cylinders[0].top, {1, 5, 3});
    EXPECT_DOUBLE_EQ(s.cylinders[0].radius, 0.25);
    EXPECT_TRUE(s.cylinders[0].capped);
    EXPECT_EQ(s.cylinders[0].material, 1u);
    expect_vec(s.cylinders[1].top, {-1, 0, 0});
    EXPECT_FALSE(s.cylinders[1].capped);  // default: open
}

TEST_F(SceneLoaderTest, BadRingsAndCylinders) {
    auto ring = [](const std::string& fields) {
        return Parts{.objects = R"([{"type": "ring", "material": "chalk", )" + fields + "}]"}.text();
    };
    auto cylinder = [](const std::string& fields) {
        return Parts{.objects = R"([{"type": "cylinder", "material": "chalk", )" + fields + "}]"}.text();
    };
    expect_error(ring(R"("normal": [0, 1, 0], "outer": 1)"), {": objects[0].center: required field is missing"});
    expect_error(ring(R"("center": [0, 0, 0], "outer": 1)"), {": objects[0].normal: required field is missing"});
    expect_error(ring(R"("center": [0, 0, 0], "normal": [0, 1, 0])"), {": objects[0].outer: required field is missing"});
    expect_error(ring(R"("center": [0, 0, 0], "normal": [0, 0, 0], "outer": 1)"),
                 {": objects[0].normal: expected a non-zero vector, got [0, 0, 0]"});
    expect_error(ring(R"("center": [0, 0, 0], "normal": [0, 1, 0], "outer": 0)"),
                 {": objects[0].outer: expected a number > 0, got 0"});
    expect_error(ring(R"("center": [0, 0, 0], "normal": [0, 1, 0], "inner": -0.5, "outer": 1)"),
                 {": objects[0].inner: expected a number >= 0, got -0.5"});
    expect_error(ring(R"("center": [0, 0, 0], "normal": [0, 1, 0], "inner": 2, "outer": 1)"),
                 {": objects[0].inner: expected inner < outer, got inner 2 and outer 1"});
    expect_error(ring(R"("center": [0, 0, 0], "normal": [0, 1, 0], "inner": 1, "outer": 1)"),
                 {": objects[0].inner: expected inner < outer, got inner 1 and outer 1"});
    expect_error(ring(R"("center": [0, 0, 0], "normal": [0, 1, 0], "outer": 1, "radius": 1)"),
                 {": objects[0]: unknown field 'radius' (expected one of: center, normal, inner, outer, material, type)"});

    expect_error(cylinder(R"("top": [0, 1, 0], "radius": 1)"), {": objects[0].base: required field is missing"});
    expect_error(cylinder(R"("base": [0, 0, 0], "radius": 1)"), {": objects[0].top: required field is missing"});
    expect_error(cylinder(R"("base": [0, 0, 0], "top": [0, 1, 0])"), {": objects[0].radius: required field is missing"});
    expect_error(cylinder(R"("base": [0, 0, 0], "top": [0, 1, 0], "radius": -1)"),
                 {": objects[0].radius: expected a number > 0, got -1"});
    expect_error(cylinder(R"("base": [1, 2, 3], "top": [1, 2, 3], "radius": 1)"),
                 {": objects[0].top: top must differ from base (both are [1, 2, 3])"});
    expect_error(cylinder(R"("base": [1000000, 0, 0], "top": [1000000.001, 0, 0], "radius": 1)"),
                 {": objects[0].top: top [1000000.001, 0, 0] and base [1000000, 0, 0] round to the same "
                  "single-precision point, so the cylinder has no axis"});
    expect_error(cylinder(R"("base": [0, 0, 0], "top": [0, 1, 0], "radius": 1, "capped": 1)"),
                 {": objects[0].capped: expected true or false, got a number (1)"});
    expect_error(cylinder(R"("base": [0, 0, 0], "top": [0, 1, 0], "radius": 1, "caps": true)"),
                 {": objects[0]: unknown field 'caps' (expected one of: base, top, radius, capped, material, type)"});
}

// ---- not supported yet ------------------------------------------------------------

TEST_F(SceneLoaderTest, GlobalModeFieldsAndTheirMistakes) {
    expect_error(Parts{.render = R"({"mode": "fast"})"}, {": render.mode: unknown mode 'fast'", "\"global\""});
    expect_error(Parts{.render = R"({"nee": false})"}, {": render.nee: only used in global mode"});
    expect_error(Parts{.render = R"({"mode": "local", "max_bounces": 2})"}, {": render.max_bounces: only used"});
    expect_error(Parts{.render = R"({"mode": "global", "estimator": "bdpt"})"},
                 {": render.estimator: unknown estimator 'bdpt'"});
    expect_error(Parts{.render = R"({"mode": "global", "hemisphere": "sphere"})"},
                 {": render.hemisphere: unknown hemisphere 'sphere'", "\"cosine\""});
    expect_error(Parts{.render = R"({"mode": "global", "estimator": "paper", "nee": true})"},
                 {": render.nee: the paper estimator has no next-event estimation"});
    expect_error(Parts{.render = R"({"mode": "global", "max_bounces": 1001})"}, {": render.max_bounces: "});
    expect_error(Parts{.render = R"({"sampler": "halton"})"},
                 {": render.sampler: unknown sampler 'halton'", "\"sobol\" or \"hash\""});
    EXPECT_EQ(load(Parts{.render = R"({"sampler": "hash"})"}.text()).render.sampler, vkrt::Sampler::Hash);

    const vkrt::Scene path = load(Parts{.render = R"({"mode": "global"})"}.text());
    EXPECT_EQ(path.render.mode, vkrt::RenderMode::Global);
    EXPECT_EQ(path.render.estimator, vkrt::Estimator::Path);
    EXPECT_EQ(path.render.hemisphere, vkrt::Hemisphere::Cosine);
    EXPECT_TRUE(path.render.nee);
    EXPECT_TRUE(path.render.jitter);
    EXPECT_EQ(path.render.max_bounces, 8u);
    EXPECT_EQ(path.render.sampler, vkrt::Sampler::Sobol);
    EXPECT_EQ(path.render.samples_per_pixel(), 16u);
    const vkrt::Scene paper = load(Parts{.render = R"({"mode": "global", "estimator": "paper", "max_bounces": 0,
                                                       "jitter": false, "spp": 3})"}.text());
    EXPECT_EQ(paper.render.hemisphere, vkrt::Hemisphere::Angles);
    EXPECT_FALSE(paper.render.nee);
    EXPECT_FALSE(paper.render.jitter);
    EXPECT_EQ(paper.render.max_bounces, 0u);
    EXPECT_EQ(paper.render.samples_per_pixel(), 3u);
}

TEST_F(SceneLoaderTest, AreaLightsAreObjectsNotLightEntries) {
    expect_error(Parts{.lights = R"([{"type": "area", "position": [0, 0, 0]}])"},
                 {": lights[0].type: there is no \"area\" light type", "nonzero \"emission\""});
}

}  // namespace

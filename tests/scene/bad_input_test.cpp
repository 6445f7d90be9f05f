// Bad scene files through the real program: each must end with exit status 1 and
// exactly one "error: " line naming the file and the JSON path (or line:column),
// never a crash, a hang or an output image (docs/architecture.md, principle 5). The loader's
// own messages are tested value by value in loader_test.cpp; this test is
// about what a user at the command line sees.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
namespace test = vkrt::test;

struct BadInput {
    std::string name;                 // test name and scene file stem
    std::string text;                 // file contents; empty: the file is not created
    std::vector<std::string> pieces;  // each must appear in the error line
};

// gtest prints parameters on failure; the name says which case it was.
void PrintTo(const BadInput& input, std::ostream* os) { *os << input.name; }

// A valid scene with one piece replaced. Kept tiny so every case reads at a glance.
std::string scene(const std::string& camera, const std::string& objects,
                  const std::string& materials = R"({"chalk": {"diffuse": [0.8, 0.8, 0.8]}})") {
    return fmt::format(R"({{"camera": {}, "materials": {}, "objects": {}}})", camera, materials, objects);
}

const std::string kCamera = R"({"eye": [0, 1, 3], "look_at": [0, 1, 0], "width": 8, "height": 6})";
const std::string kSphere = R"([{"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "chalk"}])";

std::string camera_with(const std::string& extra) {
    return fmt::format(R"({{"eye": [0, 1, 3], "look_at": [0, 1, 0], {}}})", extra);
}

// The valid scene with a "render" object.
std::string scene_with_render(const std::string& render) {
    return fmt::format(R"({{"camera": {}, "render": {}, "materials": {{"chalk": {{"diffuse": [0.8, 0.8, 0.8]}}}},
                         "objects": {}}})", kCamera, render, kSphere);
}

// The valid scene with a "lights" array.
std::string with_lights(const std::string& lights) {
    return fmt::format(R"({{"camera": {}, "materials": {{"chalk": {{"diffuse": [0.8, 0.8, 0.8]}}}}, "lights": {},
                         "objects": {}}})", kCamera, lights, kSphere);
}

std::string sphere_with_radius(const std::string& radius) {
    return fmt::format(R"([{{"type": "sphere", "center": [0, 1, 0], "radius": {}, "material": "chalk"}}])", radius);
}

std::vector<BadInput> cases() {
    return {
        {"malformed_json", "{\n  \"camera\": {\"eye\": [0, 1, 3],, }\n}", {":2:", "invalid JSON"}},
        {"truncated_json", "{\"camera\": {\"eye\": [0, 1", {":1:", "invalid JSON"}},
        {"top_level_array", "[]", {"expected a JSON object"}},
        // JSON has no NaN literal; the parser must say where it stopped.
        {"nan_radius",
         scene(kCamera, "[\n  {\"type\": \"sphere\", \"center\": [0, 1, 0],\n   \"radius\": NaN, \"material\": \"chalk\"}]"),
         {":3:14:", "invalid JSON"}},
        {"missing_camera_eye", scene(R"({"look_at": [0, 1, 0]})", kSphere), {"camera.eye", "missing"}},
        {"missing_radius",
         scene(kCamera, R"([{"type": "sphere", "center": [0, 1, 0], "material": "chalk"}])"),
         {"objects[0].radius", "missing"}},
        {"fov_is_a_string", scene(camera_with(R"("fov": "wide")"), kSphere), {"camera.fov", "expected a number"}},
        {"objects_is_an_object", scene(kCamera, "{}"), {"objects", "expected an array"}},
        {"eye_has_two_numbers", scene(R"({"eye": [0, 1], "look_at": [0, 1, 0]})", kSphere),
         {"camera.eye", "3 numbers"}},
        {"width_is_fractional", scene(camera_with(R"("width": 2.5)"), kSphere), {"camera.width", "whole number"}},
        {"unknown_material",
         scene(kCamera, R"([{"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "chalk2"}])"),
         {"objects[0].material", "unknown material 'chalk2'", "chalk"}},
        {"negative_radius", scene(kCamera, sphere_with_radius("-1")), {"objects[0].radius", "> 0"}},
        {"zero_radius", scene(kCamera, sphere_with_radius("0")), {"objects[0].radius", "> 0"}},
        {"infinite_radius", scene(kCamera, sphere_with_radius("1e999")), {"objects[0].radius", "finite"}},
        {"infinite_eye", scene(R"({"eye": [-1e999, 1, 3], "look_at": [0, 1, 0]})", kSphere),
         {"camera.eye[0]", "finite"}},
        {"zero_up", scene(camera_with(R"("up": [0, 0, 0])"), kSphere), {"camera.up", "non-zero"}},
        {"fov_zero", scene(camera_with(R"("fov": 0)"), kSphere), {"camera.fov", "between 0 and 180"}},
        {"fov_180", scene(camera_with(R"("fov": 180)"), kSphere), {"camera.fov", "between 0 and 180"}},
        {"fov_negative", scene(camera_with(R"("fov": -5)"), kSphere), {"camera.fov", "between 0 and 180"}},
        {"fov_200", scene(camera_with(R"("fov": 200)"), kSphere), {"camera.fov", "between 0 and 180"}},
        {"width_zero", scene(camera_with(R"("width": 0)"), kSphere), {"camera.width", "got 0"}},
        {"height_zero", scene(camera_with(R"("height": 0)"), kSphere), {"camera.height", "got 0"}},
        {"width_100000", scene(camera_with(R"("width": 100000)"), kSphere), {"camera.width", "got 100000"}},
        {"image_30000_squared", scene(camera_with(R"("width": 30000, "height": 30000)"), kSphere),
         {"camera: image of 30000x30000 pixels"}},
        {"unknown_field",
         scene(kCamera, R"([{"type": "sphere", "center": [0, 1, 0], "radus": 0.5, "material": "chalk"}])"),
         {"objects[0]", "unknown field 'radus'", "radius"}},
        {"reflect_negative",
         scene(kCamera, kSphere, R"({"chalk": {"reflect": [1, -1, 1]}})"),
         {"materials.chalk.reflect", "-1"}},
        {"fresnel_not_boolean",
         scene(kCamera, kSphere, R"({"chalk": {"transmit": [1, 1, 1], "fresnel": "yes"}})"),
         {"materials.chalk.fresnel", "expected true or false"}},
        {"spot_outer_not_beyond_inner",
         with_lights(R"([{"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0], "inner_angle": 30,
                          "outer_angle": 20}])"),
         {"lights[0].inner_angle", "below outer_angle (20)", "got 30"}},
        {"spot_outer_beyond_90",
         with_lights(R"([{"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0], "outer_angle": 120}])"),
         {"lights[0].outer_angle", "at most 90", "got 120"}},
        {"directional_zero_direction", with_lights(R"([{"type": "directional", "direction": [0, 0, 0]}])"),
         {"lights[0].direction", "non-zero"}},
        {"directional_without_direction", with_lights(R"([{"type": "directional", "intensity": 2}])"),
         {"lights[0].direction", "missing"}},
        {"file_does_not_exist", "", {"cannot open scene file"}},
        {"unknown_object_type", scene(kCamera, R"([{"type": "cube", "material": "chalk"}])"),
         {"objects[0].type", "unknown object type 'cube'", "torus_knot"}},
        {"ring_inner_beyond_outer",
         scene(kCamera, R"([{"type": "ring", "center": [0, 1, 0], "normal": [0, 0, 1], "inner": 1, "outer": 0.5,
                             "material": "chalk"}])"),
         {"objects[0].inner", "expected inner < outer, got inner 1 and outer 0.5"}},
        {"ring_zero_normal",
         scene(kCamera, R"([{"type": "ring", "center": [0, 1, 0], "normal": [0, 0, 0], "outer": 1, "material": "chalk"}])"),
         {"objects[0].normal", "non-zero"}},
        {"cylinder_no_axis",
         scene(kCamera, R"([{"type": "cylinder", "base": [0, 1, 0], "top": [0, 1, 0], "radius": 1, "material": "chalk"}])"),
         {"objects[0].top", "top must differ from base"}},
        {"cylinder_zero_radius",
         scene(kCamera, R"([{"type": "cylinder", "base": [0, 0, 0], "top": [0, 1, 0], "radius": 0, "material": "chalk"}])"),
         {"objects[0].radius", "expected a number > 0, got 0"}},
        {"mesh_file_missing", scene(kCamera, R"([{"type": "mesh", "file": "no-such.obj", "material": "chalk"}])"),
         {"objects[0].file", "no-such.obj: cannot open mesh file", "No such file"}},
        {"random_spheres_none",
         scene(kCamera, R"([{"type": "random_spheres", "count": 0, "min": [0, 0, 0], "max": [1, 1, 1],
                             "radius": [0.1, 0.2], "materials": ["chalk"]}])"),
         {"objects[0].count", "got 0"}},
        {"torus_knot_too_many_triangles",
         scene(kCamera, R"([{"type": "torus_knot", "segments": [100000, 1000], "material": "chalk"}])"),
         {"objects[0].segments", "more than the limit"}},
        {"light_samples_negative", scene_with_render(R"({"light_samples": -1})"),
         {"render.light_samples", "whole number in [0, 1024]", "got -1"}},
        {"light_samples_fractional", scene_with_render(R"({"light_samples": 2.5})"),
         {"render.light_samples", "whole number", "got 2.5"}},
        {"light_samples_text", scene_with_render(R"({"light_samples": "many"})"),
         {"render.light_samples", "expected a whole number"}},
        {"transform_zero_scale",
         scene(kCamera, R"([{"type": "torus_knot", "material": "chalk", "transform": {"scale": [1, 0, 1]}}])"),
         {"objects[0].transform.scale[1]", "non-zero"}},
        // Coverage (alpha.glsl): a mode by name, an opacity and a cutoff only where the
        // mode uses them, and only on shapes with texture coordinates.
        {"alpha_mode_unknown", scene(kCamera, kSphere, R"({"chalk": {"diffuse": [1, 1, 1], "alpha_mode": "clip"}})"),
         {"materials.chalk.alpha_mode", "unknown alpha mode 'clip'", "\"mask\""}},
        {"alpha_without_mode", scene(kCamera, kSphere, R"({"chalk": {"diffuse": [1, 1, 1], "alpha": 0.5}})"),
         {"materials.chalk.alpha", "needs \"alpha_mode\""}},
        {"alpha_above_one",
         scene(kCamera, kSphere, R"({"chalk": {"diffuse": [1, 1, 1], "alpha_mode": "blend", "alpha": 1.5}})"),
         {"materials.chalk.alpha", "between 0 and 1", "1.5"}},
        {"alpha_cutoff_without_mask",
         scene(kCamera, kSphere, R"({"chalk": {"diffuse": [1, 1, 1], "alpha_mode": "blend", "alpha_cutoff": 0.5}})"),
         {"materials.chalk.alpha_cutoff", "needs \"alpha_mode\": \"mask\""}},
        {"triangle_colors_two",
         scene(kCamera, R"([{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                             "colors": [[1, 0, 0], [0, 1, 0]], "material": "chalk"}])"),
         {"objects[0].colors", "3 colours"}},
        {"triangle_color_above_one",
         scene(kCamera, R"([{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                             "colors": [[1, 0, 0], [0, 1, 0], [0, 0, 2]], "material": "chalk"}])"),
         {"objects[0].colors[2]", "2"}},
        {"triangle_tangent_sign",
         scene(kCamera, R"([{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                             "tangents": [[1, 0, 0, 1], [1, 0, 0, 1], [1, 0, 0, 0.5]], "material": "chalk"}])"),
         {"objects[0].tangents[2][3]", "1 or -1", "0.5"}},
        {"triangle_tangent_zero",
         scene(kCamera, R"([{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                             "tangents": [[0, 0, 0, 1], [1, 0, 0, 1], [1, 0, 0, 1]], "material": "chalk"}])"),
         {"objects[0].tangents[0]", "non-zero tangent"}},
        {"alpha_on_a_sphere", scene(kCamera, kSphere, R"({"chalk": {"diffuse": [1, 1, 1], "alpha_mode": "mask"}})"),
         {"objects[0].material", "'chalk'", "triangles, quads and meshes only"}},
    };
}

// A parameterised test with a fresh directory of its own, named for the case.
template <class Case>
class CaseDirTest : public ::testing::TestWithParam<Case> {
protected:
    void SetUp() override { dir_ = test::temp_dir("case_" + this->GetParam().name); }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path dir_;
};

using BadInputTest = CaseDirTest<BadInput>;

TEST_P(BadInputTest, FailsWithOneClearError) {
    const BadInput& input = GetParam();
    ASSERT_TRUE(fs::exists(VKRT_EXE)) << "program not built: " << VKRT_EXE;

    const fs::path file = dir_ / (input.name + ".json");
    if (!input.text.empty()) std::ofstream(file, std::ios::binary) << input.text;
    const fs::path out = dir_ / "out.png";
    const test::ProgramRun run = test::run_vkrt(fmt::format("render {} -o {} --backend cpu", test::shell_quote(file.string()),
                                         test::shell_quote(out.string())), dir_);
    const std::string line = test::expect_one_error(run, input.pieces);
    EXPECT_NE(line.find(file.filename().string()), std::string::npos) << "no file name in: " << line;
    EXPECT_FALSE(fs::exists(out)) << "an output image was written despite the error";
}

INSTANTIATE_TEST_SUITE_P(Scenes, BadInputTest, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<BadInput>& p) { return p.param.name; });

}  // namespace

namespace {

// Mistakes on the command line: the same contract as mistakes in a scene file.
struct BadOption {
    std::string name;
    std::string args;  // after the program name; SCENE and OUT are replaced
    std::vector<std::string> pieces;
};

void PrintTo(const BadOption& option, std::ostream* os) { *os << option.name; }

using BadOptionTest = CaseDirTest<BadOption>;

TEST_P(BadOptionTest, FailsWithOneClearError) {
    std::string args = GetParam().args;
    const fs::path scene = fs::path(VKRT_SOURCE_DIR) / "scenes" / "default.json";
    const fs::path out = dir_ / "out.png";
    for (auto [key, value] : {std::pair{std::string("SCENE"), scene.string()}, std::pair{std::string("OUT"), out.string()}}) {
        for (std::size_t at = args.find(key); at != std::string::npos; at = args.find(key)) {
            args.replace(at, key.size(), test::shell_quote(value));
        }
    }
    test::expect_one_error(test::run_vkrt(args, dir_), GetParam().pieces);
    EXPECT_FALSE(fs::exists(out)) << "an output image was written despite the error";
}

std::vector<BadOption> option_cases() {
    return {
        {"no_command", "", {"subcommand"}},
        {"unknown_command", "draw SCENE", {"draw"}},
        {"missing_scene", "render", {"scene is required"}},
        {"unknown_backend", "render SCENE -o OUT --backend gpu", {"--backend", "gpu"}},
        {"width_zero", "render SCENE -o OUT --width 0", {"--width", "whole number from 1", "'0'"}},
        {"width_text", "render SCENE -o OUT --width abc", {"--width", "'abc'"}},
        {"width_huge", "render SCENE -o OUT --width 40000", {"--width", "32768"}},
        {"spp_fraction", "render SCENE -o OUT --spp 2.5", {"--spp", "'2.5'"}},
        {"spp_too_many", "render SCENE -o OUT --spp 100000", {"--spp", "65536"}},
        {"time_zero", "render SCENE -o OUT --time 0", {"--time", "above 0", "'0'"}},
        {"time_text", "render SCENE -o OUT --time soon", {"--time", "'soon'"}},
        {"time_infinite", "render SCENE -o OUT --time inf", {"--time", "'inf'"}},
        {"seed_negative", "render SCENE -o OUT --seed -1", {"--seed", "'-1'"}},
        {"background_text", "render SCENE -o OUT --background 1,x,1", {"--background", "R,G,B", "'1,x,1'"}},
        {"background_two", "render SCENE -o OUT --background 1,1", {"--background", "three (R,G,B), got 2"}},
        {"bounces_too_many", "render SCENE -o OUT --bounces 1001", {"--bounces", "1000", "'1001'"}},
        {"sampler_unknown", "render SCENE -o OUT --sampler halton", {"--sampler", "halton"}},
        {"image_too_large", "render SCENE -o OUT --width 32768 --height 32768", {"--width/--height", "limit"}},
        {"unknown_option", "render SCENE -o OUT --fast", {"--fast"}},
        {"unknown_format", "render SCENE -o OUT.xyz", {".xyz", "unknown image format"}},
        {"no_such_directory", "render SCENE -o /nonexistent/dir/out.png", {"no directory /nonexistent/dir"}},
        {"unknown_device", "render SCENE -o OUT --device no-such-gpu", {"no-such-gpu", "available"}},
        {"scene_format", "render OUT", {"unknown scene format '.png'"}},
        {"compare_threshold", "compare OUT OUT --threshold -1", {"--threshold", ">= 0"}},
        {"devices_extra", "devices extra", {"extra"}},
        {"serve_port_too_big", "render SCENE -o OUT --serve 70000", {"--serve", "'70000'", "0 to 65535"}},
        {"serve_port_text", "render SCENE -o OUT --serve localhost", {"--serve", "[ADDRESS:]PORT"}},
        {"serve_no_address", "render SCENE -o OUT --serve :8080", {"--serve", "no address"}},
        {"serve_foreign_address", "render SCENE -o OUT --serve 203.0.113.7:0", {"203.0.113.7", "cannot listen"}},
        {"converge_serve_port", "converge SCENE --csv OUT.csv --serve 1:2:x", {"--serve", "'1:2:x'"}},
        {"checkpoint_zero", "render SCENE -o OUT --checkpoint 0", {"--checkpoint", "above 0"}},
        {"reference_8bit", "render SCENE -o OUT --reference ref.png", {"--reference ref.png", ".exr or .hdr"}},
        {"reference_missing", "render SCENE -o OUT --reference /nonexistent/ref.exr", {"ref.exr", "no such file"}},
    };
}

INSTANTIATE_TEST_SUITE_P(CommandLine, BadOptionTest, ::testing::ValuesIn(option_cases()),
                         [](const ::testing::TestParamInfo<BadOption>& p) { return p.param.name; });

}  // namespace

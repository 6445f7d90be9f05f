// Input is validated in double before it becomes float (the numerical-stability
// suite, docs/numerics.md). Rather than one
// hand-written case per field (scene/bad_input_test.cpp has those for the messages a user
// sees), this walks EVERY number of two scenes that use every field of the format
// and replaces it, one at a time, by values that must never reach the kernel:
// infinities (a JSON literal like 1e999 overflows the double), and finite doubles
// beyond float's range (1e39 would become inf in the kernel, 3.5e38 too). Each must
// be refused with a SceneError naming that number's path. A field added to the
// loader without validation fails here as soon as the scene below uses it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "scene/load_scene.hpp"
#include "scene/scene_error.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// Every numeric field of the local-mode format, each with a valid value.
const char* const kLocalScene = R"({
  "camera": {"eye": [0, 1, 5], "look_at": [0, 0.5, 0], "up": [0, 1, 0.1], "fov": 45, "width": 16, "height": 12},
  "render": {"aa": 2, "max_depth": 4, "min_weight": 0.01, "ambient": [0.1, 0.1, 0.1],
             "background": [0.2, 0.3, 0.4], "seed": 7, "spp": 4, "light_samples": 2, "loop_budget": 4000,
             "grid": {"resolution": [4, 4, 4]}},
  "materials": {
    "m": {"diffuse": [0.8, 0.5, 0.3], "kd": 0.9, "specular": [1, 1, 1], "ks": 0.5, "shininess": 30,
          "reflect": [0.1, 0.1, 0.1], "transmit": [0.2, 0.2, 0.2], "ior": 1.4},
    "lamp": {"emission": [2, 2, 2]}
  },
  "lights": [{"type": "point", "position": [3, 4, 3], "color": [1, 0.9, 0.8], "intensity": 0.7}],
  "objects": [
    {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "m"},
    {"type": "sphere", "center": [0, 3, 0], "radius": 0.2, "material": "lamp"},
    {"type": "triangle", "vertices": [[1, 0, 0], [2, 0, 0], [1.5, 1, 0]],
     "normals": [[0, 0, 1], [0.1, 0, 1], [0, 0.1, 1]], "material": "m"},
    {"type": "quad", "corner": [-2, 0, -2], "edge1": [0, 0, 4], "edge2": [4, 0, 0], "material": "m"},
    {"type": "ring", "center": [-1, 1, 0], "normal": [0, 1, 0], "inner": 0.1, "outer": 0.3, "material": "m"},
    {"type": "cylinder", "base": [1, 0, 1], "top": [1, 1, 1], "radius": 0.1, "capped": true, "material": "m"},
    {"type": "random_spheres", "count": 3, "seed": 2, "min": [-1, 0, -1], "max": [1, 1, 1], "radius": [0.01, 0.02],
     "materials": ["m"]},
    {"type": "sphereflake", "center": [2, 1, -1], "radius": 0.2, "axis": [0, 1, 0], "levels": 1, "ratio": 0.3,
     "material": "m"},
    {"type": "torus_knot", "p": 2, "q": 3, "radius": 0.5, "tube": 0.1, "segments": [12, 4], "material": "m",
     "transform": {"scale": [0.5, 0.5, 0.5], "rotate": [[0, 1, 0], 30], "translate": [-2, 1, -1]}},
    {"type": "mesh", "file": "tetra.obj", "material": "m",
     "transform": {"scale": 0.5, "translate": [0, 0, -1]}}
  ]
})";

// The fields only global mode reads.
const char* const kGlobalScene = R"({
  "camera": {"eye": [0, 1, 5], "look_at": [0, 0.5, 0], "width": 16, "height": 12},
  "render": {"mode": "global", "estimator": "path", "hemisphere": "cosine", "nee": true, "max_bounces": 3,
             "spp": 2, "seed": 3, "background": [0.1, 0.1, 0.1]},
  "materials": {"m": {"diffuse": [0.5, 0.5, 0.5], "emission": [0.5, 0.5, 0.5]}},
  "objects": [{"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "m"}]
})";

const char* const kTetraObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

// A number of the document and the path the loader's messages use for it.
struct Leaf {
    Json::json_pointer pointer;
    std::string path;  // "objects[3].center[1]"
};

void collect_leaves(const Json& j, const Json::json_pointer& pointer, const std::string& path,
                    std::vector<Leaf>& out) {
    if (j.is_number()) {
        out.push_back({pointer, path});
    } else if (j.is_object()) {
        for (const auto& [key, value] : j.items()) {
            collect_leaves(value, pointer / key, path.empty() ? key : path + "." + key, out);
        }
    } else if (j.is_array()) {
        for (std::size_t i = 0; i < j.size(); ++i) {
            collect_leaves(j[i], pointer / i, fmt::format("{}[{}]", path, i), out);
        }
    }
}

// The scene with one number replaced by `literal` (text, so that 1e999 can be written).
std::string with_literal(const Json& scene, const Json::json_pointer& at, const std::string& literal) {
    Json copy = scene;
    const std::string marker = "@@replace-me@@";
    copy[at] = marker;
    std::string text = copy.dump();
    text.replace(text.find('"' + marker + '"'), marker.size() + 2, literal);
    return text;
}

class InputSweep : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::temp_dir("input_sweep");
        std::ofstream(dir_ / "tetra.obj") << kTetraObj;
    }
    void TearDown() override { fs::remove_all(dir_); }

    // The loader's verdict on `file`: empty when it loads.
    static std::string load_error_of(const fs::path& file) {
        try {
            load_scene(file);
        } catch (const SceneError& e) {
            return e.what();
        }
        return {};
    }

    // The loader's verdict on `text` as the file `name` (its extension picks the format).
    std::string load_error(const std::string& text, const std::string& name = "scene.json") {
        const fs::path file = dir_ / name;
        std::ofstream(file, std::ios::trunc) << text;
        return load_error_of(file);
    }

    // Every number of `scene` replaced by each literal in turn: refused, naming it.
    void sweep(const char* scene_text, const std::vector<std::string>& literals) {
        ASSERT_EQ(load_error(scene_text), "") << "the sweep's base scene must load";
        const Json scene = Json::parse(scene_text);
        std::vector<Leaf> leaves;
        collect_leaves(scene, Json::json_pointer(), "", leaves);
        ASSERT_GT(leaves.size(), 20u);
        for (const Leaf& leaf : leaves) {
            for (const std::string& literal : literals) {
                const std::string error = load_error(with_literal(scene, leaf.pointer, literal));
                EXPECT_NE(error, "") << leaf.path << " = " << literal << " was accepted";
                // The path as the reader prints it: an element of a vector is named
                // by its index ("camera.eye[0]"), a field by its key.
                EXPECT_NE(error.find(leaf.path + ":"), std::string::npos)
                    << leaf.path << " = " << literal << " refused without naming it: " << error;
            }
        }
    }

    fs::path dir_;
};

const std::vector<std::string> kNonFinite = {"1e999", "-1e999"};
// Finite doubles that would overflow float on the way to the kernel.
const std::vector<std::string> kBeyondFloat = {"1e39", "-3.5e38"};

// NFF and OBJ are read by tokens: every number token of a file using every line kind,
// replaced by words strtod would happily turn into non-finite or float-overflowing
// values, must be refused naming the file and the line.
const char* const kNff =
    "v\nfrom 0 1 5\nat 0 0.5 0\nup 0 1 0\nangle 45\nhither 0.1\nresolution 16 12\n"
    "b 0.1 0.2 0.3\nl 3 4 3 1 1 1\nf 0.8 0.5 0.3 0.7 0.3 20 0.2 1.4\n"
    "s 0 0.5 0 0.5\nc\n1 0 1 0.1\n1 1 1 0.1\n"
    "p 3\n-2 0 -2\n2 0 -2\n0 0 2\n"
    "pp 3\n1 0 0 0 0 1\n2 0 0 0 0 1\n1.5 1 0 0 0 1\n";

const std::vector<std::string> kBadWords = {"nan", "inf", "-inf", "1e999", "1e39"};

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::size_t start = 0;
    for (std::size_t nl = text.find('\n'); nl != std::string::npos; nl = text.find('\n', start)) {
        lines.push_back(text.substr(start, nl - start));
        start = nl + 1;
    }
    return lines;
}

// For each line and each of its numeric words (every word after a line's keyword,
// and every word of the vertex lines of `p`, `pp` and `c`), the text with that word
// replaced by `word`, and the 1-based line number.
template <typename F>
void for_each_number_word(const std::string& text, const std::string& word, F&& check) {
    const std::vector<std::string> lines = split_lines(text);
    for (std::size_t l = 0; l < lines.size(); ++l) {
        std::vector<std::string> words;
        for (std::size_t i = 0; i < lines[l].size();) {
            const std::size_t end = std::min(lines[l].find(' ', i), lines[l].size());
            words.push_back(lines[l].substr(i, end - i));
            i = end + 1;
        }
        const bool keyword = !words.empty() && std::isalpha(static_cast<unsigned char>(words[0][0]));
        for (std::size_t w = keyword ? 1 : 0; w < words.size(); ++w) {
            std::string changed;
            for (std::size_t k = 0; k < lines.size(); ++k) {
                std::string line = lines[k];
                if (k == l) {
                    std::vector<std::string> copy = words;
                    copy[w] = word;
                    line = fmt::format("{}", fmt::join(copy, " "));
                }
                changed += line + "\n";
            }
            check(changed, l + 1, lines[l]);
        }
    }
}

TEST_F(InputSweep, EveryNumberOfAnNffFileRefusesNonFiniteWords) {
    const auto error_of = [&](const std::string& text) { return load_error(text, "scene.nff"); };
    ASSERT_EQ(error_of(kNff), "") << "the sweep's base file must load";
    std::size_t checked = 0;
    for (const std::string& word : kBadWords) {
        for_each_number_word(kNff, word, [&](const std::string& text, std::size_t line, const std::string& was) {
            const std::string error = error_of(text);
            EXPECT_NE(error.find(fmt::format("scene.nff:{}:", line)), std::string::npos)
                << "line " << line << " '" << was << "' with a word made " << word << ": " << error;
            ++checked;
        });
    }
    EXPECT_GT(checked, 200u);
}

TEST_F(InputSweep, EveryNumberOfAnObjFileRefusesNonFiniteWords) {
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvn 1 0 0\nvn 0 1 0\nvn 1 1 1\n"
                            "f 1//1 3//3 2//2\nf 1//1 2//2 4//4\nf 1//1 4//4 3//3\nf 2//2 3//3 4//4\n";
    const fs::path scene = dir_ / "mesh.json";
    std::ofstream(scene) << R"({"camera": {"eye": [0, 1, 5], "look_at": [0, 0, 0], "width": 8, "height": 6},
      "materials": {"m": {}}, "objects": [{"type": "mesh", "file": "tetra.obj", "material": "m"}]})";
    std::size_t checked = 0;
    for (const std::string& word : kBadWords) {
        for_each_number_word(obj, word, [&](const std::string& text, std::size_t line, const std::string& was) {
            if (was[0] == 'f') return;  // face indices: not numbers the kernel sees
            std::ofstream(dir_ / "tetra.obj", std::ios::trunc) << text;
            const std::string error = load_error_of(scene);
            EXPECT_NE(error.find(fmt::format("tetra.obj:{}:", line)), std::string::npos)
                << "line " << line << " '" << was << "' with a word made " << word << ": " << error;
            ++checked;
        });
    }
    EXPECT_EQ(checked, kBadWords.size() * 8 * 3);
}

TEST_F(InputSweep, EveryNumberOfTheLocalFormatRefusesInfinity) { sweep(kLocalScene, kNonFinite); }
TEST_F(InputSweep, EveryNumberOfTheLocalFormatRefusesValuesBeyondFloat) { sweep(kLocalScene, kBeyondFloat); }
TEST_F(InputSweep, EveryNumberOfTheGlobalFormatRefusesInfinity) { sweep(kGlobalScene, kNonFinite); }
TEST_F(InputSweep, EveryNumberOfTheGlobalFormatRefusesValuesBeyondFloat) { sweep(kGlobalScene, kBeyondFloat); }

}  // namespace
}  // namespace vkrt

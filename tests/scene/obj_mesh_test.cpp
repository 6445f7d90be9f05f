// "mesh" objects: OBJ files read field by field (positions, fan triangulation,
// transform, winding, file and angle-weighted normals), every kind of malformed
// file refused with its line named, and the real teapot and bunny loaded.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <numbers>
#include <utility>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "image/image.hpp"
#include "scene/json_scene_loader.hpp"
#include "scene/obj_mesh.hpp"
#include "scene/scene_error.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;
namespace fs = std::filesystem;

void expect_vec(const dvec3& actual, const dvec3& expected, double tolerance = 0.0) {
    if (tolerance == 0.0) {
        EXPECT_DOUBLE_EQ(actual.x, expected.x);
        EXPECT_DOUBLE_EQ(actual.y, expected.y);
        EXPECT_DOUBLE_EQ(actual.z, expected.z);
    } else {
        EXPECT_NEAR(actual.x, expected.x, tolerance);
        EXPECT_NEAR(actual.y, expected.y, tolerance);
        EXPECT_NEAR(actual.z, expected.z, tolerance);
    }
}

dvec3 geometric_normal(const Triangle& t) {
    return glm::normalize(glm::cross(t.vertices[1] - t.vertices[0], t.vertices[2] - t.vertices[0]));
}

// Vertex 1 at the origin is shared by three faces: two with a 90-degree corner
// there (normals +z and +x), one with a 45-degree corner (normal +y).
constexpr std::string_view kCorner = R"(# three faces around the origin
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
v 1 0 1
f 1 2 3
f 1 3 4
f 1 4 5
)";

class ObjMeshTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::temp_dir(std::string("obj_mesh_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path write(const std::string& name, std::string_view text) {
        const fs::path file = dir_ / name;
        std::ofstream(file, std::ios::binary) << text;
        return file;
    }

    // A scene whose objects are `objects` (a JSON array), with materials "a" and "b".
    fs::path scene(const std::string& objects) {
        return write("scene.json", fmt::format(R"({{"camera": {{"eye": [0, 0, 5], "look_at": [0, 0, 0]}},
            "materials": {{"a": {{}}, "b": {{}}}}, "objects": {}}})", objects));
    }

    // One mesh object reading `obj` (written as mesh.obj) with extra fields.
    Scene load_mesh(std::string_view obj, const std::string& fields = "") {
        write("mesh.obj", obj);
        return vkrt::load_json_scene(
            scene(fmt::format(R"([{{"type": "mesh", "file": "mesh.obj", "material": "b"{}}}])", fields)));
    }

    // A mesh scene that must be refused: one line, starting with the scene file,
    // holding every piece.
    std::string expect_error(std::string_view obj, const std::string& fields,
                             std::initializer_list<std::string_view> pieces) {
        write("mesh.obj", obj);
        const fs::path file =
            scene(fmt::format(R"([{{"type": "mesh", "file": "mesh.obj", "material": "b"{}}}])", fields));
        try {
            vkrt::load_json_scene(file);
        } catch (const SceneError& e) {
            const std::string message = e.what();
            test::expect_error_message(message, file.string() + ": objects[0]", pieces);
            return message;
        }
        ADD_FAILURE() << "no SceneError for:\n" << obj << "\nwith fields: " << fields;
        return {};
    }

    // The OBJ's own complaint, from load_obj directly.
    std::string obj_error(std::string_view obj) {
        const fs::path file = write("bad.obj", obj);
        try {
            vkrt::load_obj(file);
        } catch (const SceneError& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.rfind(file.string() + ":", 0), 0u) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
            return message;
        }
        ADD_FAILURE() << "no SceneError for:\n" << obj;
        return {};
    }

    fs::path dir_;
};

// ---- geometry -----------------------------------------------------------------

TEST_F(ObjMeshTest, ReadsPositionsAndTriangulatesPolygonsAsFans) {
    // A square as one quad face and a pentagon: fans from each face's first vertex.
    const Scene s = load_mesh(R"(v 0 0 0
v 2 0 0
v 2 2 0
v 0 2 0
v 5 0 0
v 6 1 0
v 6 2 0
v 5 3 0
v 4 1 0
f 1 2 3 4
f 5 6 7 8 9
)");
    ASSERT_EQ(s.triangles.size(), 5u);
    const dvec3 v[] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {5, 0, 0}, {6, 1, 0}, {6, 2, 0}, {5, 3, 0}, {4, 1, 0}};
    const int expected[5][3] = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}, {4, 7, 8}};
    for (int t = 0; t < 5; ++t) {
        for (int k = 0; k < 3; ++k) expect_vec(s.triangles[t].vertices[k], v[expected[t][k]]);
        EXPECT_FALSE(s.triangles[t].normals.has_value());  // smooth defaults to false
        EXPECT_EQ(s.triangles[t].material, 1u);              // "b"
        EXPECT_GT(geometric_normal(s.triangles[t]).z, 0.0);  // counter-clockwise seen from +z
    }
    EXPECT_TRUE(s.warnings.empty());
}

TEST_F(ObjMeshTest, ReadsEveryIndexFormCommentsColoursAndCrLf) {
    // v/t, v/t/n, v//n, negative (relative) indices, vertex colours, trailing
    // comments, CRLF line ends, statements that carry nothing we use.
    const Scene s = load_mesh(
        "mtllib does-not-exist.mtl\r\n"
        "o thing\r\ng part\r\ns 1\r\nusemtl nowhere\r\n"
        "v 0 0 0 1 0 0 # red\r\n"
        "v +1 0 0\r\n"
        "v 0 1. 0\r\n"
        "v .5 .5 1e0\r\n"
        "vt 0 0\r\nvt 1 0\r\nvt 0 1\r\n"
        "vn 0 0 1\r\n"
        "f 1/1 2/2 3/3\r\n"
        "f 1/1/1 2/2/1 3/3/1\r\n"
        "f 1//1 2//1 3//1\r\n"
        "f -4 -3 -1\r\n"
        "l 1 2\r\np 3\r\n",
        R"(, "smooth": true)");
    ASSERT_EQ(s.triangles.size(), 4u);
    for (int t = 0; t < 3; ++t) {
        expect_vec(s.triangles[t].vertices[0], {0, 0, 0});
        expect_vec(s.triangles[t].vertices[1], {1, 0, 0});
        expect_vec(s.triangles[t].vertices[2], {0, 1, 0});
    }
    expect_vec(s.triangles[3].vertices[2], {0.5, 0.5, 1});
}

TEST_F(ObjMeshTest, VertexColoursAreDecodedFromSrgb) {
    // "v x y z r g b": sRGB display colours, clamped; a vertex without one is white.
    const Scene s = load_mesh("v 0 0 0 1 0.5 0\nv 1 0 0 2 -1 0.04045\nv 0 1 0\nf 1 2 3\n");
    ASSERT_EQ(s.triangles.size(), 1u);
    ASSERT_TRUE(s.triangles[0].colors.has_value());
    const auto& c = *s.triangles[0].colors;
    EXPECT_FLOAT_EQ(c[0].r, 1.0f);
    EXPECT_FLOAT_EQ(c[0].g, float(std::pow((0.5 + 0.055) / 1.055, 2.4)));
    EXPECT_FLOAT_EQ(c[0].b, 0.0f);
    EXPECT_FLOAT_EQ(c[1].r, 1.0f);
    EXPECT_FLOAT_EQ(c[1].g, 0.0f);
    EXPECT_FLOAT_EQ(c[1].b, float(0.04045 / 12.92));
    EXPECT_EQ(c[2], glm::vec4(1.0f));
    EXPECT_FALSE(load_mesh("v 0 0 0 1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").triangles[0].colors.has_value());
}

TEST_F(ObjMeshTest, TransformScalesThenRotatesThenTranslates) {
    // (1, 1, 1) scaled by (2, 3, 4) is (2, 3, 4); turned 90 degrees about +z,
    // x -> y and y -> -x: (-3, 2, 4); moved by (10, 20, 30). Field order in the
    // file does not matter, and quarter turns are exact.
    const Scene s = load_mesh("v 1 1 1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                              R"(, "transform": {"translate": [10, 20, 30], "rotate": [[0, 0, 7], 90], "scale": [2, 3, 4]})");
    ASSERT_EQ(s.triangles.size(), 1u);
    const auto& v = s.triangles[0].vertices;
    EXPECT_EQ(v[0], dvec3(7, 22, 34));
    EXPECT_EQ(v[1], dvec3(10, 22, 30));
    EXPECT_EQ(v[2], dvec3(7, 20, 30));

    // A uniform scale as one number; an angle that is not a quarter turn.
    const Scene t = load_mesh("v 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n",
                              R"(, "transform": {"scale": 2, "rotate": [[1, 1, 1], 120]})");
    // 120 degrees about (1, 1, 1) cycles the axes: x -> y -> z -> x.
    expect_vec(t.triangles[0].vertices[0], {0, 2, 0}, 1e-15);
    expect_vec(t.triangles[0].vertices[1], {0, 0, 2}, 1e-15);
    expect_vec(t.triangles[0].vertices[2], {2, 0, 0}, 1e-15);
}

TEST_F(ObjMeshTest, AngleWeightedNormalsHaveTheExactExpectedValues) {
    const Scene s = load_mesh(kCorner, R"(, "smooth": true)");
    ASSERT_EQ(s.triangles.size(), 3u);
    for (const Triangle& t : s.triangles) ASSERT_TRUE(t.normals.has_value());
    const auto& a = *s.triangles[0].normals;  // corners 1 2 3
    const auto& b = *s.triangles[1].normals;  // corners 1 3 4
    const auto& c = *s.triangles[2].normals;  // corners 1 4 5
    // The origin: 90 degrees of +z, 90 of +x, 45 of +y -> (2, 1, 2) / 3. Weighting
    // by nothing would give (1, 1, 1) / sqrt 3.
    const dvec3 origin(2.0 / 3.0, 1.0 / 3.0, 2.0 / 3.0);
    expect_vec(a[0], origin, 1e-15);
    expect_vec(b[0], origin, 1e-15);
    expect_vec(c[0], origin, 1e-15);
    // Vertex 3: 45 degrees in each of the +z and +x faces.
    const double h = std::sqrt(0.5);
    expect_vec(a[2], {h, 0, h}, 1e-15);
    expect_vec(b[1], {h, 0, h}, 1e-15);
    // Vertex 4: 45 degrees in the +x face, 90 in the +y face -> (1, 2, 0) / sqrt 5.
    const double r5 = 1.0 / std::sqrt(5.0);
    expect_vec(b[2], {r5, 2 * r5, 0}, 1e-15);
    expect_vec(c[1], {r5, 2 * r5, 0}, 1e-15);
    // Vertices in one face only take that face's normal.
    expect_vec(a[1], {0, 0, 1}, 1e-15);
    expect_vec(c[2], {0, 1, 0}, 1e-15);
}

TEST_F(ObjMeshTest, NormalsAreComputedOnTheTransformedMesh) {
    // Stretching x by 3 changes the faces' angles and normals: the +x face stays
    // +x, the 45-degree corner of the +y face opens to atan(3). At the origin:
    // 90 of +z, 90 of +x, atan(3) of +y.
    const Scene s = load_mesh(kCorner, R"(, "smooth": true, "transform": {"scale": [3, 1, 1]})");
    const double quarter = std::numbers::pi / 2;
    const dvec3 sum = quarter * dvec3(0, 0, 1) + quarter * dvec3(1, 0, 0) + std::atan(3.0) * dvec3(0, 1, 0);
    expect_vec((*s.triangles[0].normals)[0], glm::normalize(sum), 1e-15);
}

TEST_F(ObjMeshTest, FileNormalsAreUsedNormalizedAndTransformedByTheInverseTranspose) {
    const std::string obj = R"(v 0 0 0
v 1 0 0
v 0 1 0
vn 0 0 2
vn 1 1 0
vn 0 3 4
f 1//1 2//2 3//3
f 1//1 2 3
)";
    const Scene s = load_mesh(obj, R"(, "smooth": true)");
    ASSERT_EQ(s.triangles.size(), 2u);
    const auto& n = *s.triangles[0].normals;
    const double h = std::sqrt(0.5);
    expect_vec(n[0], {0, 0, 1});
    expect_vec(n[1], {h, h, 0}, 1e-15);
    expect_vec(n[2], {0, 0.6, 0.8}, 1e-15);
    // A face without a normal at every corner gets computed ones: this flat
    // triangle's own normal, +z, everywhere.
    for (const dvec3& m : *s.triangles[1].normals) expect_vec(m, {0, 0, 1}, 1e-15);

    // Scaling y by 2 squashes normals in y: (1, 1, 0) becomes (1, 1/2, 0).
    const Scene t = load_mesh(obj, R"(, "smooth": true, "transform": {"scale": [1, 2, 1]})");
    expect_vec((*t.triangles[0].normals)[1], glm::normalize(dvec3(1, 0.5, 0)), 1e-15);
    // ... and rotation turns them: +z about +x by 90 degrees is -y.
    const Scene r = load_mesh(obj, R"(, "smooth": true, "transform": {"rotate": [[1, 0, 0], 90]})");
    expect_vec((*r.triangles[0].normals)[0], {0, -1, 0});

    // Without "smooth" the file's normals are not used.
    const Scene f = load_mesh(obj);
    EXPECT_FALSE(f.triangles[0].normals.has_value());
}

// Every triangle of a closed convex mesh around `centre` must face away from it.
void expect_outward(const Scene& s, const dvec3& centre) {
    ASSERT_FALSE(s.triangles.empty());
    for (const Triangle& t : s.triangles) {
        const dvec3 centroid = (t.vertices[0] + t.vertices[1] + t.vertices[2]) / 3.0;
        const dvec3 g = geometric_normal(t);
        EXPECT_GT(glm::dot(g, centroid - centre), 0.0);
        if (t.normals) {
            for (const dvec3& n : *t.normals) EXPECT_GT(glm::dot(n, g), 0.5);
        }
    }
}

TEST_F(ObjMeshTest, NegativeScaleKeepsFrontFacesOutward) {
    const std::string file = (test::source_dir() / "scenes" / "models" / "icosahedron.obj").string();
    write("mesh.obj", "");  // unused; the object names the shipped file
    for (const std::string scale : {"1", "[-1, 1, 1]", "[-1, -2, 1]", "[-1, -1, -1]", "-0.5"}) {
        SCOPED_TRACE(scale);
        const Scene s = vkrt::load_json_scene(scene(fmt::format(
            R"([{{"type": "mesh", "file": "{}", "material": "a", "smooth": true,
                  "transform": {{"scale": {}, "translate": [1, 2, 3]}}}}])", file, scale)));
        EXPECT_EQ(s.triangles.size(), 20u);
        expect_outward(s, {1, 2, 3});
    }
}

TEST_F(ObjMeshTest, ZeroAreaTrianglesAreSkippedWithAWarning) {
    const Scene s = load_mesh(R"(v 0 0 0
v 1 0 0
v 0 1 0
v 2 0 0
f 1 2 3
f 1 1 3
f 1 2 4
)",
                              R"(, "smooth": true)");
    ASSERT_EQ(s.triangles.size(), 1u);
    expect_vec(s.triangles[0].vertices[2], {0, 1, 0});
    // The skipped ones do not disturb the computed normals.
    for (const dvec3& n : *s.triangles[0].normals) expect_vec(n, {0, 0, 1});
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("scene.json: objects[0]: skipped 2 of 3 triangles that have zero area"),
              std::string::npos)
        << s.warnings[0];
}

TEST_F(ObjMeshTest, TheProgramPrintsTheWarning) {
    write("mesh.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 2\n");
    const fs::path file = scene(R"([{"type": "mesh", "file": "mesh.obj", "material": "a"}])");
    const test::ProgramRun run = test::run_vkrt(
        fmt::format("render {} -o {} --backend cpu --width 8 --height 6 -q", test::shell_quote(file.string()),
                    test::shell_quote((dir_ / "out.png").string())),
        dir_);
    EXPECT_EQ(run.code, 0) << run.stderr_text;
    EXPECT_NE(run.stderr_text.find("warning: "), std::string::npos) << run.stderr_text;
    EXPECT_NE(run.stderr_text.find("skipped 1 of 2 triangles"), std::string::npos) << run.stderr_text;
}

// ---- errors -------------------------------------------------------------------

TEST_F(ObjMeshTest, MissingFileNamesTheResolvedPathAndTheReason) {
    const fs::path file = scene(R"([{"type": "mesh", "file": "models/none.obj", "material": "a"}])");
    try {
        vkrt::load_json_scene(file);
        ADD_FAILURE() << "no error";
    } catch (const SceneError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(fmt::format("{}: objects[0].file: {}: cannot open mesh file (", file.string(),
                                            (dir_ / "models" / "none.obj").string()),
                                0),
                  0u)
            << message;
        EXPECT_NE(message.find("No such file"), std::string::npos) << message;
    }
    fs::create_directory(dir_ / "dir.obj");
    try {
        vkrt::load_json_scene(scene(R"([{"type": "mesh", "file": "dir.obj", "material": "a"}])"));
        ADD_FAILURE() << "no error for a directory";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("dir.obj: cannot open mesh file (read failed: Is a directory)"),
                  std::string::npos)
            << e.what();
    }
}

TEST_F(ObjMeshTest, MalformedNumbersAreRefusedWithTheirLine) {
    EXPECT_NE(obj_error("v 0 0 0\nv 1 abc 0\n").find(":2: expected a number, got 'abc'"), std::string::npos);
    EXPECT_NE(obj_error("v 1,5 0 0\n").find(":1: expected a number, got '1,5'"), std::string::npos);
    EXPECT_NE(obj_error("v 1e 0 0\n").find(":1: expected a number, got '1e'"), std::string::npos);
    EXPECT_NE(obj_error("v nan 0 0\n").find(":1: expected a finite number, got 'nan'"), std::string::npos);
    EXPECT_NE(obj_error("v 0 -inf 0\n").find(":1: expected a finite number, got '-inf'"), std::string::npos);
    EXPECT_NE(obj_error("\n\nv 0 0 1e999\n").find(":3: expected a finite number, got '1e999'"), std::string::npos);
    EXPECT_NE(obj_error("v 1e13 0 0\n").find(":1: expected a number of magnitude at most 1000000000000, got '1e13'"),
              std::string::npos);
    EXPECT_NE(obj_error("v 1 2\n").find(":1: expected 3 numbers after 'v', got 2"), std::string::npos);
    EXPECT_NE(obj_error("v 1 2 3\nvn 0 1\n").find(":2: expected 3 numbers after 'vn', got 2"), std::string::npos);
    EXPECT_NE(obj_error("v 1 2 3\nvn 0 nan 1\n").find(":2: expected a finite number, got 'nan'"), std::string::npos);
    // Extra numbers (w, colours) need not be used but must be numbers.
    EXPECT_NE(obj_error("v 1 2 3 x\n").find(":1: expected a number, got 'x'"), std::string::npos);
}

TEST_F(ObjMeshTest, ZeroTimesHugePowerIsZeroNotNaN) {
    // tinyobjloader computes "0e400" as 0 * 5^400 = NaN; the coordinate is 0.
    const fs::path file = write("z.obj", "v 0e400 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const vkrt::IndexedMesh mesh = vkrt::load_obj(file);
    ASSERT_EQ(mesh.positions.size(), 3u);
    EXPECT_EQ(mesh.positions[0], dvec3(0, 0, 0));
}

TEST_F(ObjMeshTest, BadFacesAreRefusedWithTheirLine) {
    const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
    EXPECT_NE(obj_error(v + "f 1 2 9\n").find(":5: a face refers to vertex 9, but the file has 4 vertices"),
              std::string::npos);
    EXPECT_NE(obj_error(v + "f 1 2 3\nf -1 -2 -9\n").find(":6: a face refers to vertex -4, but the file has 4 vertices"),
              std::string::npos);
    EXPECT_NE(obj_error(v + "vn 0 0 1\nf 1//1 2//1 3//2\n").find(":6: a face refers to normal 2, but the file has 1 normals"),
              std::string::npos);
    EXPECT_NE(obj_error(v + "f 1 2\n").find(":5: a face needs at least 3 vertices, got 2"), std::string::npos);
    std::string big = v + "f";
    for (int i = 0; i < 256; ++i) big += " 1";
    EXPECT_NE(obj_error(big + "\n").find(":5: a face of 256 vertices; at most 255 are supported"), std::string::npos);
    // Index 0 and words are tinyobjloader's to report; it names the line.
    std::string m = obj_error(v + "f 0 1 2\n");
    EXPECT_NE(m.find("Failed parse `f' line"), std::string::npos) << m;
    EXPECT_NE(m.find("line 5"), std::string::npos) << m;
    m = obj_error(v + "f 1 2 x\n");
    EXPECT_NE(m.find("line 5"), std::string::npos) << m;
    EXPECT_NE(obj_error(v + "# only vertices\n").find(": the file has no faces"), std::string::npos);
    EXPECT_NE(obj_error("").find(": the file has no faces"), std::string::npos);
}

TEST_F(ObjMeshTest, TextureCoordinatesAreCheckedAsPositionsAre) {
    const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const std::string f = "f 1/1 2/1 3/1\n";
    EXPECT_NE(obj_error(v + "vt abc 0\n" + f).find(":4: expected a number, got 'abc'"), std::string::npos);
    EXPECT_NE(obj_error(v + "vt 0 nan\n" + f).find(":4: expected a finite number, got 'nan'"), std::string::npos);
    EXPECT_NE(obj_error(v + "vt 1e40 0\n" + f).find(":4: expected a number of magnitude at most"), std::string::npos);
    EXPECT_NE(obj_error(v + "vt\n" + f).find(":4: expected 1 to 3 numbers after 'vt', got 0"), std::string::npos);
    EXPECT_NE(obj_error(v + "vt 0 0 0 0\n" + f).find(":4: expected 1 to 3 numbers after 'vt', got 4"),
              std::string::npos);
    // v defaults to 0 (turned to run down the image: 1); the numbers are kept at
    // float precision.
    const IndexedMesh mesh = load_obj(write("uv.obj", v + "vt 0.1\nvt 0.3 0.7 0\n" + f));
    ASSERT_EQ(mesh.uvs.size(), 2u);
    EXPECT_EQ(mesh.uvs[0], glm::dvec2(double(0.1f), 1.0));
    EXPECT_EQ(mesh.uvs[1], glm::dvec2(double(0.3f), 1.0 - double(0.7f)));
}

TEST_F(ObjMeshTest, FaceIndicesAreIntegersCountedFromOneOrFromTheEnd) {
    const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
    for (const char* face : {"f 1.5 2 3\n", "f 1abc 2 3\n", "f 1/1/1/1 2 3\n", "f 1/ 2 3\n", "f 1// 2 3\n",
                             "f /1 2 3\n", "f 1 -0 3\n", "f 1 +-2 3\n"}) {
        const std::string m = obj_error(v + "vt 0 0\nvn 0 0 1\n" + face);
        EXPECT_NE(m.find("Failed parse `f' line"), std::string::npos) << face << m;
        EXPECT_NE(m.find("line 7"), std::string::npos) << face << m;
    }
    // A relative index before the first element is out of range, also for normals.
    EXPECT_NE(
        obj_error(v + "vn 0 0 1\nf 1//-2 2 3\n").find(":6: a face refers to normal 0, but the file has 1 normals"),
        std::string::npos);
    EXPECT_NE(obj_error(v + "f 1 2 99999999999\n").find(":5: a face refers to vertex 99999999999"), std::string::npos);
    // A face may refer to a vertex of a later line and end in a comment; +1 is 1,
    // and -1 the last vertex read so far.
    const IndexedMesh mesh = load_obj(write("later.obj", "v 0 0 0\nf +1 2 -1 # 2 comes next\nv 1 0 0\nv 0 1 0\n"));
    ASSERT_EQ(mesh.faces.size(), 1u);
    EXPECT_EQ(mesh.faces[0].position, (std::array<std::uint32_t, 3>{0, 1, 0}));
}

TEST_F(ObjMeshTest, ObjErrorsComeAfterTheScenePathToTheFile) {
    const std::string m = expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "",
                                       {": objects[0].file: ", "mesh.obj:4: a face refers to vertex 4"});
    EXPECT_NE(m.find((dir_ / "mesh.obj").string()), std::string::npos) << m;
}

TEST_F(ObjMeshTest, BadObjectFieldsAreRefused) {
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    expect_error(tri, R"(, "smooth": "yes")", {"objects[0].smooth: expected true or false"});
    expect_error(tri, R"(, "colour": 1)", {"objects[0]: unknown field 'colour'", "transform"});
    expect_error(tri, R"(, "transform": {"scale": 0})", {"objects[0].transform.scale: expected a non-zero scale factor"});
    expect_error(tri, R"(, "transform": {"scale": [1, 0, 1]})", {"objects[0].transform.scale[1]: ", "non-zero"});
    expect_error(tri, R"(, "transform": {"scale": 1e-13})", {"transform.scale: ", "at least 1e-12"});
    expect_error(tri, R"(, "transform": {"scale": "big"})",
                 {"transform.scale: expected a number or an array of 3 numbers, got a string ('big')"});
    expect_error(tri, R"(, "transform": {"rotate": [[0, 0, 0], 30]})",
                 {"transform.rotate[0]: expected a non-zero rotation axis"});
    expect_error(tri, R"(, "transform": {"rotate": [0, 1, 0]})", {"transform.rotate: expected an array [[x, y, z], degrees]"});
    expect_error(tri, R"(, "transform": {"rotate": [[0, 1, 0], "30"]})", {"transform.rotate[1]: expected a number"});
    expect_error(tri, R"(, "transform": {"translate": [0, 1]})", {"transform.translate: expected an array of 3 numbers"});
    expect_error(tri, R"(, "transform": {"move": [0, 1, 0]})", {"transform: unknown field 'move'", "translate"});
    expect_error(tri, R"(, "transform": {"scale": 1e12, "translate": [0, 1, 0]})",
                 {"objects[0].transform: the transformed mesh has a vertex at [0, 1000000000001, 0]"});
    expect_error("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "", {"objects[0]: all 1 triangles of the mesh have zero area"});

    write("mesh.obj", tri);
    for (const auto& [objects, piece] : {
             std::pair{R"([{"type": "mesh", "material": "a"}])", "objects[0].file: required field is missing"},
             std::pair{R"([{"type": "mesh", "file": "", "material": "a"}])", "objects[0].file: expected a file name"},
             std::pair{R"([{"type": "mesh", "file": 3, "material": "a"}])", "objects[0].file: expected a string"},
             // Without "material" the OBJ's own materials are used; this one has none.
             std::pair{R"([{"type": "mesh", "file": "mesh.obj"}])", "the face has no material (no usemtl before it)"},
             std::pair{R"([{"type": "mesh", "file": "mesh.obj", "material": "c"}])", "unknown material 'c'"},
         }) {
        try {
            vkrt::load_json_scene(scene(objects));
            ADD_FAILURE() << "no error for " << objects;
        } catch (const SceneError& e) {
            EXPECT_NE(std::string(e.what()).find(piece), std::string::npos) << e.what();
        }
    }
}

// ---- real models ---------------------------------------------------------------

struct RealModel {
    const char* file;
    std::size_t faces;
    dvec3 lo, hi;  // bounding box, from scenes/models/README.md
};

void check_real_model(const RealModel& model, const fs::path& scene_file) {
    const fs::path obj = test::source_dir() / "scenes" / "models" / model.file;
    ASSERT_TRUE(fs::exists(obj)) << "not found: " << obj;
    std::ofstream(scene_file) << fmt::format(
        R"({{"camera": {{"eye": [0, 0, 5], "look_at": [0, 0, 0]}}, "materials": {{"m": {{}}}},
            "objects": [{{"type": "mesh", "file": "{}", "material": "m", "smooth": true}}]}})",
        obj.string());
    const Scene s = vkrt::load_json_scene(scene_file);

    // Every face is a triangle in these files; the skipped ones are reported.
    std::size_t skipped = 0;
    if (!s.warnings.empty()) {
        ASSERT_EQ(s.warnings.size(), 1u);
        const auto at = s.warnings[0].find("skipped ");
        ASSERT_NE(at, std::string::npos) << s.warnings[0];
        skipped = std::stoul(s.warnings[0].substr(at + 8));
        EXPECT_NE(s.warnings[0].find(fmt::format("of {} triangles", model.faces)), std::string::npos) << s.warnings[0];
    }
    EXPECT_EQ(s.triangles.size() + skipped, model.faces);
    EXPECT_LT(skipped, model.faces / 100);

    dvec3 lo(1e300), hi(-1e300);
    std::size_t agreeing = 0;
    for (const Triangle& t : s.triangles) {
        ASSERT_TRUE(t.normals.has_value());
        for (int k = 0; k < 3; ++k) {
            lo = glm::min(lo, t.vertices[k]);
            hi = glm::max(hi, t.vertices[k]);
            ASSERT_NEAR(glm::length((*t.normals)[k]), 1.0, 1e-12);
        }
        const dvec3 g = geometric_normal(t);
        if (glm::dot((*t.normals)[0], g) > 0 && glm::dot((*t.normals)[1], g) > 0 && glm::dot((*t.normals)[2], g) > 0) {
            ++agreeing;
        }
    }
    expect_vec(lo, model.lo, 1e-3);
    expect_vec(hi, model.hi, 1e-3);
    // Averaged normals lean away from a face only at sharp creases.
    EXPECT_GT(agreeing, s.triangles.size() * 95 / 100);
}

// ---- materials from MTL files -------------------------------------------------

// Two faces of a square, each with a material of the OBJ's MTL library.
constexpr std::string_view kTwoMaterials = R"(mtllib two.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
usemtl red
f 1 2 3
usemtl lamp
f 1 3 4
)";

constexpr std::string_view kTwoMtl = R"(newmtl red
Kd 0.8 0.1 0.05
Ks 0.5 0.5 0.5
Ns 64
newmtl lamp
Kd 0 0 0
Ke 4 3 2
)";

TEST_F(ObjMeshTest, MaterialsComeFromTheMtlFileWhenTheObjectGivesNone) {
    write("mesh.obj", kTwoMaterials);
    write("two.mtl", kTwoMtl);
    const Scene s = vkrt::load_json_scene(scene(R"([{"type": "mesh", "file": "mesh.obj"}])"));
    ASSERT_EQ(s.materials.size(), 4u);  // "a", "b", then the file's two
    const Material& red = s.materials[2];
    const Material& lamp = s.materials[3];
    EXPECT_EQ(red.name, "mesh.obj:red");
    expect_vec(red.diffuse, {0.8, 0.1, 0.05}, 1e-7);  // read as float by tinyobjloader
    expect_vec(red.specular, {0.5, 0.5, 0.5});
    EXPECT_EQ(red.ks, 1.0);
    EXPECT_EQ(red.shininess, 64.0);
    expect_vec(red.emission, {0, 0, 0});
    EXPECT_EQ(lamp.name, "mesh.obj:lamp");
    expect_vec(lamp.emission, {4, 3, 2});
    EXPECT_EQ(lamp.ks, 0.0);
    ASSERT_EQ(s.triangles.size(), 2u);
    EXPECT_EQ(s.triangles[0].material, 2u);
    EXPECT_EQ(s.triangles[1].material, 3u);
    EXPECT_TRUE(s.warnings.empty());
}

// A scene given by a relative path gives a relative OBJ path: its MTL file is
// beside it, in the working directory, not at the root.
TEST_F(ObjMeshTest, TheMtlFileOfARelativeObjPath) {
    write("mesh.obj", kTwoMaterials);
    write("two.mtl", kTwoMtl);
    struct InDirectory {  // back where it was, whatever the load does
        fs::path before = fs::current_path();
        explicit InDirectory(const fs::path& dir) { fs::current_path(dir); }
        ~InDirectory() { fs::current_path(before); }
    };
    std::vector<std::string> warnings;
    IndexedMesh mesh;
    {
        const InDirectory here(dir_);
        mesh = vkrt::load_obj_with_materials("mesh.obj", warnings);
    }
    ASSERT_EQ(mesh.materials.size(), 2u);
    EXPECT_EQ(mesh.materials[0].name, "red");
}

TEST_F(ObjMeshTest, TheObjectsMaterialOverridesTheMtlFile) {
    write("two.mtl", kTwoMtl);
    const Scene s = load_mesh(kTwoMaterials);  // "material": "b"
    EXPECT_EQ(s.materials.size(), 2u);
    for (const Triangle& t : s.triangles) EXPECT_EQ(t.material, 1u);
}

TEST_F(ObjMeshTest, WhatMaterialsAskForBeyondPhongIsAWarning) {
    write("mesh.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl wood\nf 1 2 3\n");
    write("t.mtl", "newmtl wood\nKd 0.5 0.3 0.1\nmap_Ks wood.png\nd 0.5\n");
    const Scene s = vkrt::load_json_scene(scene(R"([{"type": "mesh", "file": "mesh.obj"}])"));
    ASSERT_EQ(s.warnings.size(), 2u);
    EXPECT_NE(s.warnings[0].find("objects[0]: "), std::string::npos) << s.warnings[0];
    EXPECT_NE(s.warnings[0].find("material 'wood': textures are not supported yet; map_Ks 'wood.png' is ignored"),
              std::string::npos)
        << s.warnings[0];
    EXPECT_NE(s.warnings[1].find("transparency (d 0.5) is not supported"), std::string::npos) << s.warnings[1];
    expect_vec(s.materials.back().diffuse, {0.5, 0.3, 0.1}, 1e-7);
}

// map_Kd: the texture beside the OBJ, its -o and -s options as the transform, and
// each corner's vt with v turned to run down the image as vkrt's textures do.
TEST_F(ObjMeshTest, MapKdTexturesTheDiffuseColourAtTheFacesTextureCoordinates) {
    vkrt::Image img(2, 2);
    for (float& v : img.rgb) v = 0.25f;
    vkrt::write_image(img, dir_ / "wood.exr");
    write("mesh.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0.25 1\nusemtl wood\n"
                      "f 1/1 2/2 3/3\n");
    write("t.mtl", "newmtl wood\nKd 0.5 0.3 0.1\nmap_Kd -s 2 4 1 -o 0.5 0.25 0 wood.exr\n");
    const Scene s = vkrt::load_json_scene(scene(R"([{"type": "mesh", "file": "mesh.obj"}])"));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.textures[0].width, 2u);
    EXPECT_EQ(s.textures[0].format, TexelFormat::Half) << "a float file, kept float";
    EXPECT_EQ(texel_value(s.textures[0], s.texels.words(), 3), glm::vec4(0.25f, 0.25f, 0.25f, 1.0f)) << "read as it is";
    const Material& wood = s.materials.back();
    ASSERT_EQ(wood.texture, std::optional<std::uint32_t>(0u));
    const std::array<double, 6> expected = {2, 0, 0.5, 0, 4, 1.0 - 4.0 - 0.25};
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(wood.uv_transform[i], expected[i], 1e-6) << i;
    ASSERT_EQ(s.triangles.size(), 1u);
    ASSERT_TRUE(s.triangles[0].uvs.has_value());
    EXPECT_EQ((*s.triangles[0].uvs)[0], glm::dvec2(0, 1));
    EXPECT_EQ((*s.triangles[0].uvs)[1], glm::dvec2(1, 1));
    EXPECT_EQ((*s.triangles[0].uvs)[2], glm::dvec2(0.25, 0));
    // A missing texture file is an error naming the material.
    write("t.mtl", "newmtl wood\nmap_Kd absent.png\n");
    try {
        vkrt::load_json_scene(scene(R"([{"type": "mesh", "file": "mesh.obj"}])"));
        ADD_FAILURE() << "no error";
    } catch (const vkrt::SceneError& e) {
        test::expect_error_message(e.what(), "", {"objects[0].file", "material 'wood' map_Kd", "absent.png", "no such file"});
    }
}

TEST_F(ObjMeshTest, AFaceWithoutAMaterialIsAnErrorWhenTheObjectGivesNone) {
    const auto refused = [&](std::string_view obj, std::initializer_list<std::string_view> pieces) {
        write("mesh.obj", obj);
        const fs::path file = scene(R"([{"type": "mesh", "file": "mesh.obj"}])");
        try {
            vkrt::load_json_scene(file);
            ADD_FAILURE() << "no SceneError for:\n" << obj;
        } catch (const SceneError& e) {
            test::expect_error_message(e.what(), file.string() + ": objects[0].file", pieces);
        }
    };
    // No library at all: the first face says so.
    refused(kCorner, {"mesh.obj:7: the face has no material (no usemtl before it)", "give the mesh object a"});
    // A library that is not there, and a name it does not define: tinyobjloader's words.
    refused("mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n",
            {"mesh.obj:6: the face has no material", "missing.mtl"});
    write("two.mtl", kTwoMtl);
    refused("mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl blue\nf 1 2 3\n",
            {"mesh.obj:6: the face has no material", "blue"});
    // A negative colour is refused with the material named.
    const std::string uses_red = "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
    write("two.mtl", "newmtl red\nKd 0.5 -1 0\n");
    refused(uses_red, {"material 'red': Kd must be three finite numbers >= 0"});
    // The MTL's numbers are checked as the OBJ's are, with the MTL's line: a
    // typo or a missing component would otherwise read as 0.
    write("two.mtl", "newmtl red\nKd 0.8\n");
    refused(uses_red, {"two.mtl:2: expected 3 numbers after 'Kd', got 1"});
    write("two.mtl", "newmtl red\nKd 0.8 0.1 0.1\nNs abc\n");
    refused(uses_red, {"two.mtl:3: expected a number, got 'abc'"});
    write("two.mtl", "newmtl red\nKd nan 0 0\n");
    refused(uses_red, {"two.mtl:2: expected a finite number, got 'nan'"});
    write("two.mtl", "newmtl red\nKe 1e13 0 0\n");
    refused(uses_red, {"two.mtl:2: expected a number of magnitude at most 1000000000000, got '1e13'"});
    // The same numbers as the OBJ's are taken: a leading '+' is one.
    write("two.mtl", "newmtl red\nKd +0.8 0.1 0.1\n");
    std::vector<std::string> warnings;
    const IndexedMesh mesh = load_obj_with_materials(write("mesh.obj", uses_red), warnings);
    ASSERT_EQ(mesh.materials.size(), 1u);
    expect_vec(mesh.materials[0].diffuse, {0.8, 0.1, 0.1}, 1e-7);
}

TEST_F(ObjMeshTest, AUsemtlFindsTheMaterialsOfTheMtllibLinesBeforeIt) {
    write("two.mtl", kTwoMtl);
    write("more.mtl", "newmtl red\nKd 0 0 1\nnewmtl blue\nKd 0 0 1\n");
    std::vector<std::string> warnings;
    // A second library adds its materials; a name both define keeps the first's.
    const IndexedMesh mesh = load_obj_with_materials(
        write("mesh.obj", "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl lamp\nf 1 2 3\n"
                          "mtllib more.mtl\nusemtl blue\nf 1 2 3\nusemtl red\nf 1 2 3\n"),
        warnings);
    ASSERT_EQ(mesh.materials.size(), 4u);
    ASSERT_EQ(mesh.faces.size(), 3u);
    EXPECT_EQ(mesh.materials[mesh.faces[0].material].name, "lamp");
    EXPECT_EQ(mesh.materials[mesh.faces[1].material].name, "blue");
    EXPECT_EQ(mesh.faces[2].material, 0u);  // two.mtl's red
    ASSERT_EQ(warnings.size(), 1u);  // two libraries named, if on two lines
    EXPECT_NE(warnings[0].find("names 2 MTL files"), std::string::npos) << warnings[0];
    // Before its mtllib line a usemtl finds nothing.
    try {
        load_obj_with_materials(write("early.obj", "usemtl red\nmtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
                                warnings);
        ADD_FAILURE() << "no error";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("early.obj:6: the face has no material (usemtl 'red' is not defined in "
                                             "mtllib 'two.mtl')"),
                  std::string::npos)
            << e.what();
    }
}

TEST_F(ObjMeshTest, LoadsTheUtahTeapot) {
    check_real_model({"teapot.obj.gz", 6320, {-3.0, 0.0, -2.0}, {3.434, 3.15, 2.0}}, dir_ / "teapot.json");
}

TEST_F(ObjMeshTest, LoadsTheStanfordBunny) {
    check_real_model({"stanford-bunny.obj.gz", 69451, {-0.095, 0.033, -0.062}, {0.061, 0.187, 0.059}},
                     dir_ / "bunny.json");
}

}  // namespace

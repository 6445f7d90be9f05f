// The scene format's "transform" (host/scene/transform.cpp): rotations exact at
// quarter turns and right-handed, scale then rotate then translate, normals by a
// bounded multiple of the inverse transpose, mirroring, a glTF node's general
// matrix, and the refusals of maps that flatten space.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "scene/json_document.hpp"
#include "scene/scene_error.hpp"
#include "scene/transform.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;
using glm::dmat3;
using glm::dvec3;

const dvec3 kX{1, 0, 0}, kY{0, 1, 0}, kZ{0, 0, 1};

// The transform read from `text`, the value of "transform" in a file t.json.
Transform transform_of(const std::string& text) {
    const std::string file = "t.json";
    const json::Document doc = json::parse_document(file, R"({"transform": )" + text + "}");
    return read_transform(*json::Node(file, doc).find("transform"));
}

// The message read_transform refuses `text` with.
std::string refusal_of(const std::string& text) {
    try {
        transform_of(text);
    } catch (const SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << text << " was accepted";
    return {};
}

double largest_entry(const dmat3& m) {
    double most = 0.0;
    for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) most = std::max(most, std::abs(m[c][r]));
    }
    return most;
}

void expect_near(const dvec3& got, const dvec3& want, double tolerance) {
    EXPECT_LE(glm::length(got - want), tolerance) << "got (" << got.x << ", " << got.y << ", " << got.z
                                                  << "), want (" << want.x << ", " << want.y << ", " << want.z << ")";
}

TEST(Rotation, QuarterTurnsAreExactAndRightHanded) {
    // About z, x turns to y; about x, y to z; about y, z to x.
    EXPECT_EQ(rotation(kZ, 90.0) * kX, kY);
    EXPECT_EQ(rotation(kX, 90.0) * kY, kZ);
    EXPECT_EQ(rotation(kY, 90.0) * kZ, kX);
    EXPECT_EQ(rotation(kX, 180.0) * kY, -kY);
    // Every multiple of 90, either way round, is the same quarter turn as its rest.
    EXPECT_EQ(rotation(kZ, 450.0), rotation(kZ, 90.0));
    EXPECT_EQ(rotation(kZ, -270.0), rotation(kZ, 90.0));
    EXPECT_EQ(rotation(kZ, -90.0) * kY, kX);
    EXPECT_EQ(rotation(kZ, 360.0), dmat3(1.0));
    // The axis's length does not matter.
    EXPECT_EQ(rotation(dvec3(0, 0, 5), 90.0), rotation(kZ, 90.0));
    EXPECT_EQ(rotation(dvec3(0, 0, 1e-300), 90.0), rotation(kZ, 90.0));
}

TEST(Rotation, OtherAnglesFollowRodrigues) {
    const double c = std::sqrt(3.0) / 2.0;
    expect_near(rotation(kZ, 30.0) * kX, dvec3(c, 0.5, 0.0), 1e-15);
    // A third of a turn about the diagonal cycles the axes.
    expect_near(rotation(dvec3(1, 1, 1), 120.0) * kX, kY, 1e-15);
    expect_near(rotation(dvec3(1, 1, 1), 120.0) * kY, kZ, 1e-15);
    // Huge angles are reduced before the sine: a million turns and 30 degrees.
    expect_near(rotation(kZ, 360e6 + 30.0) * kX, dvec3(c, 0.5, 0.0), 1e-15);
    // Orthonormal with determinant 1.
    const dmat3 r = rotation(dvec3(0.3, -2.0, 0.7), 77.0);
    const dmat3 rtr = glm::transpose(r) * r;
    for (int i = 0; i < 3; ++i) expect_near(rtr[i], dmat3(1.0)[i], 1e-15);
    EXPECT_NEAR(glm::determinant(r), 1.0, 1e-15);
}

TEST(ReadTransform, ScalesThenRotatesThenTranslates) {
    const Transform t = transform_of(R"({"scale": 2, "rotate": [[0, 0, 1], 90], "translate": [1, 2, 3]})");
    // (1, 0, 0) scaled to (2, 0, 0), turned to (0, 2, 0), moved to (1, 4, 3).
    EXPECT_EQ(t.apply_point(kX), dvec3(1, 4, 3));
    EXPECT_EQ(t.apply_point(dvec3(0.0)), dvec3(1, 2, 3));
    EXPECT_EQ(t.apply_normal(kX), kY) << "normals turn and are not scaled";
    EXPECT_FALSE(t.mirrors);

    const Transform identity = transform_of("{}");
    EXPECT_EQ(identity.linear, dmat3(1.0));
    EXPECT_EQ(identity.translate, dvec3(0.0));
    EXPECT_EQ(identity.normal_matrix, dmat3(1.0));
}

TEST(ReadTransform, NormalsStayPerpendicularUnderUnevenScale) {
    // The plane x + y = 0, scaled by 2 along y, is the plane 2x + y = 0.
    const Transform t = transform_of(R"({"scale": [1, 2, 1]})");
    expect_near(t.apply_normal(dvec3(1, 1, 0)), dvec3(2, 1, 0) / std::sqrt(5.0), 1e-15);
    // Any positive multiple of the inverse transpose will do: this one's entries
    // are at most 1, even for the smallest scale allowed.
    const Transform tiny = transform_of(R"({"scale": [1e-12, 1, 1], "rotate": [[1, 2, 3], 40]})");
    EXPECT_LE(largest_entry(tiny.normal_matrix), 1.0);
    const dvec3 n = tiny.apply_normal(kX);
    EXPECT_NEAR(glm::length(n), 1.0, 1e-15);
    expect_near(n, rotation(dvec3(1, 2, 3), 40.0) * kX, 1e-12);
}

TEST(ReadTransform, AnOddNumberOfNegativeFactorsMirrors) {
    EXPECT_TRUE(transform_of(R"({"scale": [-1, 1, 1]})").mirrors);
    EXPECT_FALSE(transform_of(R"({"scale": [-1, -1, 1]})").mirrors);
    EXPECT_TRUE(transform_of(R"({"scale": -3})").mirrors);
    // The normal keeps pointing the way the surface faces, mirrored.
    EXPECT_EQ(transform_of(R"({"scale": [-1, 1, 1]})").apply_normal(kX), -kX);
}

TEST(ReadTransform, RefusesScalesAndAxesThatFlattenSpace) {
    test::expect_error_message(refusal_of(R"({"scale": 0})"), "t.json: transform.scale: ",
                               {"non-zero scale factor", "got 0"});
    test::expect_error_message(refusal_of(R"({"scale": [1, 1e-13, 1]})"), "t.json: transform.scale[1]: ",
                               {"at least 1e-12", "got 1e-13"});
    test::expect_error_message(refusal_of(R"({"rotate": [[0, 0, 0], 90]})"), "t.json: transform.rotate[0]: ",
                               {"non-zero rotation axis"});
    test::expect_error_message(refusal_of(R"({"rotate": [[0, 0, 1]]})"), "t.json: transform.rotate: ",
                               {"[[x, y, z], degrees]"});
    test::expect_error_message(refusal_of(R"({"skew": 1})"), "t.json: transform: ", {"unknown field 'skew'"});
}

TEST(AffineTransform, AnyInvertibleMapWithItsNormalMatrix) {
    // A shear: x' = x + y. The plane y = 0 stays put; the plane x = 0 becomes x = y.
    const dmat3 shear(dvec3(1, 0, 0), dvec3(1, 1, 0), dvec3(0, 0, 1));  // columns
    const std::optional<Transform> t = affine_transform(shear, dvec3(0, 0, 7));
    ASSERT_TRUE(t.has_value());
    EXPECT_EQ(t->apply_point(dvec3(1, 2, 3)), dvec3(3, 2, 10));
    EXPECT_EQ(t->apply_normal(kY), kY);
    expect_near(t->apply_normal(kX), dvec3(1, -1, 0) / std::sqrt(2.0), 1e-15);
    EXPECT_EQ(largest_entry(t->normal_matrix), 1.0);
    EXPECT_FALSE(t->mirrors);

    const std::optional<Transform> mirror = affine_transform(dmat3(dvec3(-2, 0, 0), kY, kZ), dvec3(0.0));
    ASSERT_TRUE(mirror.has_value());
    EXPECT_TRUE(mirror->mirrors);
    EXPECT_EQ(mirror->apply_normal(kX), -kX);
}

TEST(AffineTransform, NothingForAMapThatFlattensSpace) {
    EXPECT_FALSE(affine_transform(dmat3(kX, kY, kX + kY), dvec3(0.0)).has_value());
    EXPECT_FALSE(affine_transform(dmat3(0.0), dvec3(0.0)).has_value());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(affine_transform(dmat3(dvec3(nan, 0, 0), kY, kZ), dvec3(0.0)).has_value());
}

}  // namespace

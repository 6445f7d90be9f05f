#include "scene/transform.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <fmt/format.h>
#include <glm/geometric.hpp>

namespace vkrt {
namespace {

// Scale factors are bounded below as coordinates are bounded above: a smaller one
// is a typo, and it would take the inverse (for normals) past what a double holds.
constexpr double kMinScale = 1.0 / json::kMaxMagnitude;

double scale_factor(const json::Node& n) {
    const double s = n.number();
    // A zero factor flattens the object into a plane or a line: every triangle
    // would have zero area, which is a mistake, not a way to hide an object.
    if (std::abs(s) < kMinScale) {
        n.fail(fmt::format("expected a non-zero scale factor of magnitude at least {}, got {}", kMinScale, s));
    }
    return s;
}

glm::dvec3 read_scale(const json::Node& n) {
    if (n.is_number()) return glm::dvec3(scale_factor(n));
    const auto e = n.elements(3, "a number or an array of 3 numbers");
    return {scale_factor(e[0]), scale_factor(e[1]), scale_factor(e[2])};
}

// (sin, cos) of an angle in degrees, exact at multiples of 90.
std::pair<double, double> sin_cos_degrees(double degrees) {
    const double quarter = degrees / 90.0;
    if (quarter == std::floor(quarter) && std::abs(quarter) < 1e15) {
        static constexpr double kSin[4] = {0.0, 1.0, 0.0, -1.0};
        static constexpr double kCos[4] = {1.0, 0.0, -1.0, 0.0};
        const auto k = static_cast<long long>(quarter);
        const int i = static_cast<int>(((k % 4) + 4) % 4);
        return {kSin[i], kCos[i]};
    }
    // Reduce first: sin(1e9 degrees in radians) loses digits that the reduced
    // angle keeps.
    const double radians = std::fmod(degrees, 360.0) * (std::numbers::pi / 180.0);
    return {std::sin(radians), std::cos(radians)};
}

}  // namespace

glm::dmat3 rotation(const glm::dvec3& axis, double degrees) {
    const glm::dvec3 u = robust_normalize(axis);
    const auto [s, c] = sin_cos_degrees(degrees);
    const double t = 1.0 - c;
    // Rodrigues' formula; glm matrices are column-major, m[column][row].
    glm::dmat3 m;
    m[0] = {t * u.x * u.x + c, t * u.x * u.y + s * u.z, t * u.x * u.z - s * u.y};
    m[1] = {t * u.x * u.y - s * u.z, t * u.y * u.y + c, t * u.y * u.z + s * u.x};
    m[2] = {t * u.x * u.z + s * u.y, t * u.y * u.z - s * u.x, t * u.z * u.z + c};
    return m;
}

Transform read_transform(const json::Node& n) {
    n.allow_only({"scale", "rotate", "translate"});
    glm::dvec3 scale(1.0);
    glm::dmat3 rotate(1.0);
    Transform t;
    if (auto s = n.find("scale")) scale = read_scale(*s);
    if (auto r = n.find("rotate")) {
        const auto e = r->elements(2, "an array [[x, y, z], degrees] (an axis and an angle)");
        const glm::dvec3 axis = e[0].vec3();
        if (!is_nonzero(axis)) e[0].fail("expected a non-zero rotation axis, got [0, 0, 0]");
        rotate = rotation(axis, e[1].number());
    }
    if (auto tr = n.find("translate")) t.translate = tr->vec3();

    const glm::dmat3 scale_matrix(glm::dvec3(scale.x, 0, 0), glm::dvec3(0, scale.y, 0), glm::dvec3(0, 0, scale.z));
    t.linear = rotate * scale_matrix;
    // (R S)^-T = R S^-1 for a rotation R and a diagonal S, scaled here by the
    // smallest factor so that no entry exceeds 1.
    const double smallest = std::min({std::abs(scale.x), std::abs(scale.y), std::abs(scale.z)});
    const glm::dvec3 inverse = smallest / scale;
    t.normal_matrix = rotate * glm::dmat3(glm::dvec3(inverse.x, 0, 0), glm::dvec3(0, inverse.y, 0),
                                          glm::dvec3(0, 0, inverse.z));
    t.mirrors = scale.x * scale.y * scale.z < 0.0;
    return t;
}

std::optional<Transform> affine_transform(const glm::dmat3& linear, const glm::dvec3& translate) {
    // The cofactor matrix is det times the inverse transpose; its columns are the
    // cross products of the map's columns, with no division.
    glm::dmat3 cofactor(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                        glm::cross(linear[0], linear[1]));
    const double det = glm::dot(linear[0], cofactor[0]);
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return std::nullopt;
    // A positive multiple of the inverse transpose, scaled so no entry exceeds 1.
    if (det < 0.0) cofactor = -cofactor;
    double biggest = 0.0;
    for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) biggest = std::max(biggest, std::abs(cofactor[c][r]));
    }
    Transform t;
    t.linear = linear;
    t.translate = translate;
    t.normal_matrix = cofactor / biggest;
    t.mirrors = det < 0.0;
    return t;
}

}  // namespace vkrt

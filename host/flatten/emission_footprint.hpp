#pragma once
// Textured emitters weighed by what they emit: a triangle (or quad) whose material
// has an emission texture is an area light only where its own footprint in the
// texture emits, picked with a weight equal to the mean textured emission over that
// footprint (kernel/shapes/triangle.glsl, triangle_emitter_weight). A scanned asset's
// emission texture is mostly black: its few lit texels light the scene, and the
// thousands of triangles over black texels are no emitters at all.
//
// The footprint is the set of texels the kernel's bilinear look-ups can reach from
// any point of the triangle: the box of its texture coordinates (after the
// material's transform), widened by a texel for the filter and one more for float
// rounding, wrapped as the texture wraps. Its mean comes from a summed-area table of
// the texture times the emission, built once per texture and emission colour, so
// that the cost is linear in texels plus triangles.
#include <cstdint>
#include <map>
#include <span>
#include <tuple>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec2.hpp>

#include "scene/scene.hpp"

namespace vkrt {

class EmissionFootprints {
public:
    explicit EmissionFootprints(const Scene& scene) : scene_(scene) {}

    // The mean over the footprint of the texture coordinates `uv` (3 for a triangle,
    // 4 for a parallelogram's corners) taken through `transform` (as
    // Material::uv_transform) of mean_c(emission_c * texel_c), with the texel as the
    // kernel decodes it; 0 when every texel there is black. `material` must have an
    // emission texture.
    double mean_emission(const Material& material, std::span<const glm::dvec2> uv,
                         const std::array<double, 6>& transform);

private:
    // Sums of the emission over texels [0, x) x [0, y), (width + 1) x (height + 1),
    // in integer units of the brightest texel / kUnits (or of a bound of it), each
    // texel rounded up: exact, so that a footprint's sum is 0 exactly when all its
    // texels are black, however bright the rest of the texture (a table of doubles
    // would cancel). Kept modulo 2^32, in half the memory of 64-bit sums: a
    // rectangle's sum from its four corners is still exact while the true sum stays
    // below 2^32, which kPieceSide x kPieceSide texels of at most kUnits + 1 units
    // each do; larger rectangles are summed piece by piece.
    static constexpr std::uint32_t kUnits = std::uint32_t(1) << 11;
    static constexpr std::uint32_t kPieceSide = 1024;
    struct Table {
        std::uint32_t width = 0;
        std::uint32_t height = 0;
        double unit = 0.0;
        TexelWords sums;
        std::uint64_t rect(std::uint32_t x0, std::uint32_t x1, std::uint32_t y0, std::uint32_t y1) const;  // inclusive
    };
    const Table& table(std::uint32_t texture, const glm::dvec3& emission);
    template <class Emitted>
    static void fill_sums(Table& table, double brightest, const Emitted& emitted);

    const Scene& scene_;
    std::map<std::tuple<std::uint32_t, double, double, double>, Table> tables_;
};

// The texel intervals [first, last] of an axis of n texels that the unwrapped texel
// indices [lo, hi] reach under a wrap mode: one for clamp, up to three for repeat
// and mirror; the whole axis once the span reaches the mode's period.
struct TexelInterval {
    std::uint32_t first;
    std::uint32_t last;
};
std::vector<TexelInterval> wrapped_intervals(std::int64_t lo, std::int64_t hi, std::uint32_t n, Wrap mode);

}  // namespace vkrt

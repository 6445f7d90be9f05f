#include "flatten/emission_footprint.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace vkrt {

namespace {

// Texel positions beyond this are no longer integers in double's grid of a
// texture's size, nor anything the kernel's floats resolve: the whole axis.
constexpr double kFarTexel = 1e15;

// The unwrapped texel indices [lo, hi] the kernel's bilinear look-ups can reach on
// an axis of n texels from coordinates in [cmin, cmax]: texel position c n - 0.5
// (texture.glsl), its floor and the next, one more each side for float rounding.
// False when some coordinate is not finite or too far: the kernel then reads
// anywhere on the axis (it takes 0 for such coordinates).
bool reached(double cmin, double cmax, std::uint32_t n, std::int64_t& lo, std::int64_t& hi) {
    // The kernel ignores coordinates at or beyond 1e30 (wrap_coordinate).
    if (!(std::abs(cmin) < 1e30 && std::abs(cmax) < 1e30)) return false;
    const double a = cmin * n - 0.5, b = cmax * n - 0.5;
    if (!(std::abs(a) < kFarTexel && std::abs(b) < kFarTexel)) return false;
    lo = std::int64_t(std::floor(a)) - 1;
    hi = std::int64_t(std::floor(b)) + 2;
    return true;
}

std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

}  // namespace

std::vector<TexelInterval> wrapped_intervals(std::int64_t lo, std::int64_t hi, std::uint32_t n, Wrap mode) {
    const std::int64_t size = n;
    const TexelInterval all{0, n - 1};
    if (mode == Wrap::Clamp) {
        return {{std::uint32_t(std::clamp<std::int64_t>(lo, 0, size - 1)),
                 std::uint32_t(std::clamp<std::int64_t>(hi, 0, size - 1))}};
    }
    // Repeat has period n; mirror 2n, its odd periods reflected.
    const std::int64_t period = mode == Wrap::Repeat ? size : 2 * size;
    if (hi - lo + 1 >= period) return {all};
    std::vector<TexelInterval> out;
    for (std::int64_t k = floor_div(lo, size); k * size <= hi; ++k) {
        const std::int64_t a = std::max(lo, k * size) - k * size, b = std::min(hi, k * size + size - 1) - k * size;
        const bool reflected = mode == Wrap::Mirror && (k % 2 + 2) % 2 == 1;
        if (reflected) {
            out.push_back({std::uint32_t(size - 1 - b), std::uint32_t(size - 1 - a)});
        } else {
            out.push_back({std::uint32_t(a), std::uint32_t(b)});
        }
    }
    return out;
}

std::uint64_t EmissionFootprints::Table::rect(std::uint32_t x0, std::uint32_t x1, std::uint32_t y0,
                                              std::uint32_t y1) const {
    const std::size_t row = std::size_t(width) + 1;
    const auto at = [&](std::size_t x, std::size_t y) { return sums[y * row + x]; };
    std::uint64_t sum = 0;
    for (std::uint32_t py = y0; py <= y1; py += std::min(kPieceSide, y1 - py + 1)) {
        const std::uint32_t qy = std::min(y1, py + (kPieceSide - 1));
        for (std::uint32_t px = x0; px <= x1; px += std::min(kPieceSide, x1 - px + 1)) {
            const std::uint32_t qx = std::min(x1, px + (kPieceSide - 1));
            // Unsigned arithmetic wraps modulo 2^32, as the table does.
            const std::uint32_t piece = at(qx + 1, qy + 1) - at(px, qy + 1) - at(qx + 1, py) + at(px, py);
            sum += piece;
        }
    }
    return sum;
}

template <class Emitted>
void EmissionFootprints::fill_sums(Table& table, double brightest, const Emitted& emitted) {
    // Each texel rounded up, so that one that emits at all counts at least 1 unit.
    // (With a bound of the brightest texel the units are coarser, never too fine to
    // hold a texel in kUnits + 1.)
    table.unit = brightest / double(kUnits);
    const double per_unit = brightest > 0.0 ? 1.0 / table.unit : 0.0;
    const std::size_t row = std::size_t(table.width) + 1;
    table.sums.resize(row * (std::size_t(table.height) + 1));  // each word written below
    std::fill_n(table.sums.begin(), row, 0u);
    // Each row's running sums, rows in parallel; then, columns in parallel, each
    // row adds the one above.
    parallel_for(table.height, [&](std::size_t y) {
        std::uint32_t* out = table.sums.data() + (y + 1) * row;
        std::uint32_t running = 0;
        out[0] = 0;
        for (std::size_t x = 0; x < table.width; ++x) {
            const double e = emitted(y * table.width + x);
            running += e > 0.0 ? std::uint32_t(std::ceil(e * per_unit)) : 0u;
            out[x + 1] = running;
        }
    });
    constexpr std::size_t kColumns = 256;
    parallel_for((row + kColumns - 1) / kColumns, [&](std::size_t block) {
        const std::size_t first = block * kColumns, last = std::min(row, first + kColumns);
        for (std::size_t y = 2; y <= table.height; ++y) {
            std::uint32_t* out = table.sums.data() + y * row;
            const std::uint32_t* above = out - row;
            for (std::size_t x = first; x < last; ++x) out[x] += above[x];
        }
    });
}

const EmissionFootprints::Table& EmissionFootprints::table(std::uint32_t texture, const glm::dvec3& emission) {
    const auto key = std::tuple{texture, emission.x, emission.y, emission.z};
    if (auto it = tables_.find(key); it != tables_.end()) return it->second;
    const TextureImage& t = scene_.textures[texture];
    const std::span<const std::uint32_t> texels = scene_.texels.words();
    Table table;
    table.width = t.width;
    table.height = t.height;
    // As the kernel weighs emission (emission_weight): the mean over the channels
    // of emission times texel, never below 0.
    if (t.format == TexelFormat::Rgba8) {
        // An 8-bit texel's channels each take one of 256 values: the products come
        // from a table per channel. The brightest texel is bounded by the sum of
        // each channel's product at its largest byte (a byte's value grows with
        // it), found by a pass over the bytes alone.
        std::array<std::uint32_t, 3> top{};
        for (std::size_t i = 0; i < t.texel_count(); ++i) {
            const std::uint32_t word = texels[t.first_word + i];
            for (int c = 0; c < 3; ++c) top[c] = std::max(top[c], (word >> (8 * c)) & 255u);
        }
        std::array<std::array<double, 256>, 3> product{};
        double bound = 0.0;
        for (int c = 0; c < 3; ++c) {
            for (std::uint32_t b = 0; b < 256; ++b) product[c][b] = emission[c] * colour_byte_value(t, b);
            bound += std::max(product[c][0], product[c][top[c]]);
        }
        fill_sums(table, std::max(0.0, bound / 3.0), [&](std::size_t i) {
            const std::uint32_t word = texels[t.first_word + i];
            return std::max(0.0, (product[0][word & 255u] + product[1][(word >> 8) & 255u] +
                                  product[2][(word >> 16) & 255u]) / 3.0);
        });
    } else {
        const auto emitted = [&](std::size_t i) {
            const glm::vec4 c = texel_value(t, texels, i);
            return std::max(0.0, (emission.x * c.r + emission.y * c.g + emission.z * c.b) / 3.0);
        };
        double brightest = 0.0;
        for (std::size_t i = 0; i < t.texel_count(); ++i) brightest = std::max(brightest, emitted(i));
        fill_sums(table, brightest, emitted);
    }
    return tables_.emplace(key, std::move(table)).first->second;
}

double EmissionFootprints::mean_emission(const Material& material, std::span<const glm::dvec2> uv,
                                         const std::array<double, 6>& a) {
    const TextureImage& t = scene_.textures[*material.emission_texture];
    glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    bool finite = true;
    for (const glm::dvec2& p : uv) {
        const glm::dvec2 q(a[0] * p.x + a[1] * p.y + a[2], a[3] * p.x + a[4] * p.y + a[5]);
        finite = finite && std::isfinite(q.x) && std::isfinite(q.y);
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    std::int64_t x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    const std::vector<TexelInterval> xs = finite && reached(lo.x, hi.x, t.width, x0, x1)
                                              ? wrapped_intervals(x0, x1, t.width, t.wrap_s)
                                              : std::vector<TexelInterval>{{0, t.width - 1}};
    const std::vector<TexelInterval> ys = finite && reached(lo.y, hi.y, t.height, y0, y1)
                                              ? wrapped_intervals(y0, y1, t.height, t.wrap_t)
                                              : std::vector<TexelInterval>{{0, t.height - 1}};
    const Table& sums = table(*material.emission_texture, material.emission);
    std::uint64_t sum = 0;
    double count = 0.0;
    for (const TexelInterval& x : xs) {
        for (const TexelInterval& y : ys) {
            sum += sums.rect(x.first, x.last, y.first, y.last);
            count += double(x.last - x.first + 1) * double(y.last - y.first + 1);
        }
    }
    return double(sum) * sums.unit / count;
}

}  // namespace vkrt

#include "accel/grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace vkrt {
namespace {

using glm::dvec3;

// Largest cells per axis: far beyond any useful grid, small enough that cell
// coordinates stay exact in float and int.
constexpr double kMaxAxisCells = 1 << 20;

// At most 2^25 cells (128 MiB of cell starts) whatever the device allows: the
// heuristic never asks for more below 4 million primitives.
constexpr std::uint64_t kMaxGridCells = std::uint64_t(1) << 25;

// Relative padding of each primitive box: a thousandth of a cell, plus the float
// rounding of positions at the scene's magnitude and the rays' reach (2^-20 is
// eight float ULPs). Over-inclusion costs a test; under-inclusion loses a hit.
constexpr double kCellPad = 1e-3;
constexpr double kMagnitudePad = 0x1p-20;

// The float at or below x, and at or above it.
double float_down(double x) {
    float f = static_cast<float>(x);
    if (double(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
    return f;
}
double float_up(double x) {
    float f = static_cast<float>(x);
    if (double(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return f;
}

dvec3 to_dvec3(const kernel::vec4& v) { return dvec3(v.x, v.y, v.z); }

std::uint64_t product(const GridResolution& r) { return std::uint64_t(r[0]) * r[1] * r[2]; }

// The box the grid covers: every primitive, with axes of (almost) no extent widened
// so that every cell has a positive size.
Aabb grid_box(const std::vector<Aabb>& boxes) {
    Aabb box{dvec3(std::numeric_limits<double>::infinity()), dvec3(-std::numeric_limits<double>::infinity())};
    for (const Aabb& b : boxes) {
        box.lo = glm::min(box.lo, b.lo);
        box.hi = glm::max(box.hi, b.hi);
    }
    const dvec3 extent = box.hi - box.lo;
    const double largest = std::max({extent.x, extent.y, extent.z});
    const double magnitude = std::max({std::abs(box.lo.x), std::abs(box.lo.y), std::abs(box.lo.z),
                                       std::abs(box.hi.x), std::abs(box.hi.y), std::abs(box.hi.z)});
    const double least = std::max(largest * 1e-3, magnitude * kMagnitudePad + 1e-30);
    for (int a = 0; a < 3; ++a) {
        if (extent[a] < least) {
            box.lo[a] -= least / 2;
            box.hi[a] += least / 2;
        }
    }
    return box;
}

// Fits a resolution under the device's limit on the cell-starts array.
GridResolution fit(GridResolution r, std::uint64_t max_cells) {
    while (product(r) > max_cells) {
        const int a = int(std::max_element(r.begin(), r.end()) - r.begin());
        r[a] = std::max(1u, static_cast<std::uint32_t>(r[a] * 0.9));
    }
    return r;
}

}  // namespace

Aabb bounds(const kernel::Sphere& s) {
    const dvec3 c = to_dvec3(s.center_radius);
    const double r = s.center_radius.w;
    return {c - r, c + r};
}

Aabb bounds(const kernel::Triangle& t) {
    const dvec3 a = to_dvec3(t.p0), b = to_dvec3(t.p1), c = to_dvec3(t.p2);
    return {glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c))};
}

GridResolution grid_resolution(const Aabb& box, std::size_t primitives, double density, std::uint64_t max_cells) {
    const dvec3 extent = box.hi - box.lo;
    const double largest = std::max({extent.x, extent.y, extent.z});
    GridResolution res{1, 1, 1};
    if (!(largest > 0.0) || primitives == 0) return res;
    const double target = std::clamp(density * double(primitives), 1.0, double(max_cells));
    // Cells per axis = k * extent, with k chosen so that the product meets the target.
    // An axis that would get less than one cell gets exactly one, and the others
    // share the target between them.
    std::array<bool, 3> split{extent.x > 0.0, extent.y > 0.0, extent.z > 0.0};
    double k = 0.0;
    for (int round = 0; round < 3; ++round) {
        int n = 0;
        double volume = 1.0;
        for (int a = 0; a < 3; ++a) {
            if (split[a]) {
                ++n;
                volume *= extent[a];
            }
        }
        if (n == 0) return res;
        k = std::pow(target / volume, 1.0 / n);
        bool changed = false;
        for (int a = 0; a < 3; ++a) {
            if (split[a] && k * extent[a] < 1.0) {
                split[a] = false;
                changed = true;
            }
        }
        if (!changed) break;
    }
    for (int a = 0; a < 3; ++a) {
        if (split[a]) res[a] = static_cast<std::uint32_t>(std::clamp(std::round(k * extent[a]), 1.0, kMaxAxisCells));
    }
    return fit(res, max_cells);
}

std::array<GridResolution, 2> Grid::cells_overlapping(const Aabb& box) const {
    std::array<GridResolution, 2> range{};
    for (int a = 0; a < 3; ++a) {
        const double last = resolution[a] - 1;
        const double first_cell = std::floor((box.lo[a] - pad[a] - lo[a]) / cell[a]);
        const double last_cell = std::floor((box.hi[a] + pad[a] - lo[a]) / cell[a]);
        range[0][a] = static_cast<std::uint32_t>(std::clamp(first_cell, 0.0, last));
        range[1][a] = static_cast<std::uint32_t>(std::clamp(last_cell, 0.0, last));
    }
    return range;
}

Grid build_grid(std::span<const kernel::Sphere> spheres, std::span<const kernel::Triangle> triangles,
                const GridRequest& request, std::string& note) {
    std::vector<Aabb> boxes;
    std::vector<std::uint32_t> ids;
    boxes.reserve(spheres.size() + triangles.size());
    ids.reserve(boxes.capacity());
    for (std::size_t i = 0; i < spheres.size(); ++i) {
        boxes.push_back(bounds(spheres[i]));
        ids.push_back((kernel::REF_SPHERE << kernel::REF_KIND_SHIFT) | std::uint32_t(i));
    }
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        boxes.push_back(bounds(triangles[i]));
        ids.push_back((kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | std::uint32_t(i));
    }

    Grid g;
    if (boxes.empty()) {
        g.cell_starts = {0, 0};
        return g;
    }
    const Aabb box = grid_box(boxes);
    const std::uint64_t max_cells = std::min(request.max_entries - 1, kMaxGridCells);
    GridResolution res = request.resolution;
    if (product(res) == 0) {
        res = grid_resolution(box, boxes.size(), kGridDensity, max_cells);
    } else if (product(res) > max_cells) {
        const GridResolution asked = res;
        res = fit(res, max_cells);
        note = fmt::format("grid resolution {}x{}x{} exceeds this device's buffer limit of {} entries; using {}x{}x{}",
                           asked[0], asked[1], asked[2], request.max_entries, res[0], res[1], res[2]);
    }

    const double magnitude = std::max({std::abs(box.lo.x), std::abs(box.lo.y), std::abs(box.lo.z),
                                       std::abs(box.hi.x), std::abs(box.hi.y), std::abs(box.hi.z)});
    // Rays travel at most from the eye across the box.
    double reach = glm::length(box.hi - box.lo);
    if (request.eye) reach += glm::length(*request.eye - glm::clamp(*request.eye, box.lo, box.hi));
    for (;;) {
        g.resolution = res;
        for (int a = 0; a < 3; ++a) {
            g.lo[a] = float_down(box.lo[a]);
            g.cell[a] = float_up((box.hi[a] - g.lo[a]) / res[a]);
            g.hi[a] = float_up(g.lo[a] + g.cell[a] * res[a]);
            g.pad[a] = kCellPad * g.cell[a] + (magnitude + reach) * kMagnitudePad;
        }
        // Two passes: count each cell's references, then place them after the prefix sum.
        const std::uint64_t cells = g.cell_count();
        std::vector<std::uint64_t> counts(cells + 1, 0);
        for (const Aabb& b : boxes) {
            const auto [first, last] = g.cells_overlapping(b);
            for (std::uint32_t z = first[2]; z <= last[2]; ++z) {
                for (std::uint32_t y = first[1]; y <= last[1]; ++y) {
                    const std::uint64_t row = (std::uint64_t(z) * res[1] + y) * res[0];
                    for (std::uint32_t x = first[0]; x <= last[0]; ++x) ++counts[row + x];
                }
            }
        }
        std::uint64_t total = 0;
        for (std::uint64_t c = 0; c <= cells; ++c) {
            const std::uint64_t n = counts[c];
            counts[c] = total;
            total += n;
        }
        if (total > request.max_entries && product(res) > 1) {
            // Too many references for one buffer: coarser cells hold fewer copies of
            // the large primitives.
            const GridResolution before = res;
            res = fit(res, std::max<std::uint64_t>(1, product(res) / 2));
            note = fmt::format("grid {}x{}x{} needs {} references, over this device's buffer limit of {}; "
                               "trying {}x{}x{}", before[0], before[1], before[2], total, request.max_entries,
                               res[0], res[1], res[2]);
            continue;
        }
        if (total > request.max_entries) {
            throw std::runtime_error(fmt::format("the scene's {} primitives do not fit one grid buffer of {} entries",
                                                 boxes.size(), request.max_entries));
        }
        g.cell_starts.assign(counts.begin(), counts.end());
        g.refs.assign(total, 0);
        std::vector<std::uint64_t> cursor(counts.begin(), counts.end() - 1);
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            const auto [first, last] = g.cells_overlapping(boxes[i]);
            for (std::uint32_t z = first[2]; z <= last[2]; ++z) {
                for (std::uint32_t y = first[1]; y <= last[1]; ++y) {
                    const std::uint64_t row = (std::uint64_t(z) * res[1] + y) * res[0];
                    for (std::uint32_t x = first[0]; x <= last[0]; ++x) g.refs[cursor[row + x]++] = ids[i];
                }
            }
        }
        return g;
    }
}

}  // namespace vkrt

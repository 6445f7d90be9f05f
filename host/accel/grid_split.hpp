#pragma once
// The second half of building the grid (grid.hpp): each root cell becomes a leaf, or,
// where primitives crowd it, an inner cell of 4 x 4 x 4 children, recursively.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "accel/box_overlap.hpp"
#include "accel/grid.hpp"

namespace vkrt {

// Padding of each primitive box, as a fraction of the cell it is binned into.
inline constexpr double kCellPad = 1e-3;

// Which cells a primitive goes into: every cell its padded box overlaps, except that
// a triangle or a quad goes only into the cells its polygon overlaps once the cell is
// grown by the padding (which is the same as padding the polygon). Root cells and a
// split cell's children are binned alike.
struct Binner {
    std::span<const kernel::Triangle> triangles;

    // Calls f(x, y, z) for each cell of the grid of `res` cells of size `cell` from
    // corner `lo` that the primitive `id` (a reference) with box `box` overlaps.
    template <class F>
    void cells(const Aabb& box, std::uint32_t id, const glm::dvec3& lo, const glm::dvec3& cell, const glm::dvec3& pad,
               const GridResolution& res, F&& f) const {
        const auto [first, last] = cells_overlapping(box, lo, cell, pad, res);
        std::array<glm::dvec3, 4> v;
        // A polygon within a row of cells crosses each of them: its projection on
        // the row's axis is its box's. Only a range wide on two axes needs the test.
        const int wide = int(first[0] < last[0]) + int(first[1] < last[1]) + int(first[2] < last[2]);
        const std::size_t n = wide >= 2 ? polygon(id, v) : 0;
        const PolygonOverlap shape(std::span<const glm::dvec3>(v.data(), n));
        for (std::uint32_t z = first[2]; z <= last[2]; ++z) {
            for (std::uint32_t y = first[1]; y <= last[1]; ++y) {
                for (std::uint32_t x = first[0]; x <= last[0]; ++x) {
                    if (n != 0) {
                        const glm::dvec3 c_lo = lo + cell * glm::dvec3(x, y, z) - pad;
                        if (!shape.overlaps(c_lo, c_lo + cell + 2.0 * pad)) continue;
                    }
                    f(x, y, z);
                }
            }
        }
    }

    // The vertices of reference `id` when it is a triangle (3) or a quad (4, its
    // fourth as the kernel computes it); 0 for the other kinds.
    std::size_t polygon(std::uint32_t id, std::array<glm::dvec3, 4>& v) const;
};

// What one root cell holds: indices into the builder's boxes, ascending.
struct RootCells {
    std::vector<std::uint32_t> starts;   // root cells + 1 offsets into items
    std::vector<std::uint32_t> items;
};

// Fills g.nodes and appends the leaves' lists to g.refs (which holds the loose
// references). `boxes` and `ids` are the listed primitives; `rounding` the part of
// each one's padding that is float rounding rather than a fraction of a cell. Splits
// only when `split` is set, and never beyond `max_refs` references or `max_words`
// node words in all.
void place_cells(Grid& g, const RootCells& roots, const std::vector<Aabb>& boxes,
                 const std::vector<std::uint32_t>& ids, const Binner& binner, const std::vector<double>& rounding,
                 bool split, std::uint64_t max_refs, std::uint64_t max_words);

}  // namespace vkrt

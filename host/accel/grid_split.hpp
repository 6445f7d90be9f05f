#pragma once
// The second half of building the grid (grid.hpp): each root cell becomes a leaf, or,
// where primitives crowd it, an inner cell of 4 x 4 x 4 children, recursively.
#include <cstdint>
#include <vector>

#include "accel/grid.hpp"

namespace vkrt {

// Padding of each primitive box, as a fraction of the cell it is binned into.
inline constexpr double kCellPad = 1e-3;

// What one root cell holds: indices into the builder's boxes, ascending.
struct RootCells {
    std::vector<std::uint32_t> starts;   // root cells + 1 offsets into items
    std::vector<std::uint32_t> items;
};

// Fills g.nodes and appends the leaves' lists to g.refs (which holds the loose
// references). `boxes` and `ids` are the listed primitives; `magnitude_pad` the part
// of the padding that is float rounding rather than a fraction of a cell. Splits
// only when `split` is set, and never beyond `max_refs` references or `max_words`
// node words in all.
void place_cells(Grid& g, const RootCells& roots, const std::vector<Aabb>& boxes,
                 const std::vector<std::uint32_t>& ids, double magnitude_pad, bool split, std::uint64_t max_refs,
                 std::uint64_t max_words);

}  // namespace vkrt

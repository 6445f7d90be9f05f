#include "accel/grid.hpp"
#include "accel/grid_split.hpp"
#include "scene_shapes.hpp"  // each kind's bounds(), host/scene/shapes/<name>.hpp, generated

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace vkrt {
namespace {

using glm::dvec3;

// Largest root cells per axis: far beyond any useful grid, small enough that fine
// coordinates (kernel GRID_FRACTION_BITS) fit a uint and root indices stay exact in
// float.
constexpr double kMaxAxisCells = double(1u << (32u - kernel::GRID_FRACTION_BITS));

// At most 2^25 cells (128 MiB of root nodes) whatever the device allows: the
// heuristic never asks for more below 4 million primitives.
constexpr std::uint64_t kMaxGridCells = std::uint64_t(1) << 25;

// At most 2^28 references (1 GiB) whatever the device allows: the host holds the
// array in memory, and the reference backend reads it from there.
constexpr std::uint64_t kMaxGridRefs = std::uint64_t(1) << 28;

// Padding of each primitive box: a thousandth of a cell (kCellPad), plus the float
// rounding of positions near the box (Grid::rounding_pad; 2^-20 is eight float ULPs).
// Over-inclusion costs a test; under-inclusion loses a hit.
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

Aabb union_of(const Aabb& a, const Aabb& b) { return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)}; }

// A box's volume with every extent counted as at least `least`, so that flat boxes
// (a floor, a planar mesh) still compare.
double padded_volume(const Aabb& b, double least) {
    const dvec3 e = glm::max(b.hi - b.lo, dvec3(least));
    return e.x * e.y * e.z;
}

// Leaving primitives out of the grid must shrink its box at least this many times
// (by volume): less would save little walking and cost every ray their tests.
constexpr double kLooseShrink = 8.0;
// And each of them must be this many times larger (largest extent) than any primitive
// the grid keeps: where the next ones are nearly as large, the box is still theirs.
constexpr double kLooseGap = 8.0;

// The primitives loose for their size: at most `max_loose` of the largest boxes, the
// fewest whose absence shrinks the grid's box to within twice the smallest box that
// leaving out up to `max_loose` of them reaches, and only if they shrink it kLooseShrink times
// and they are kLooseGap times larger than the rest. A floor 100 units wide under a
// tree 3 units wide (SPD tree) otherwise sets the box, and the cell size that the
// primitive count buys spreads the tree's 53,000 primitives over a few dozen cells
// (730 tests per ray). A stadium of 8 walls and 32 floor triangles around a small
// cluster is left alone: without its walls the floor still sets the box, now a flat
// one whose cells are no smaller around the cluster (tests/scenes/stability case 6:
// 870 tests per ray against 404). Returns one flag per box; `shrink` gets the volume
// ratio.
std::vector<bool> choose_stretching(const std::vector<Aabb>& boxes, std::size_t max_loose, double& shrink) {
    std::vector<bool> loose(boxes.size(), false);
    shrink = 1.0;
    if (boxes.empty()) return loose;
    const std::size_t k = std::min(max_loose, boxes.size() - 1);  // at least one is listed
    if (k == 0) return loose;
    auto largest_extent = [&](std::size_t i) {
        const dvec3 e = boxes[i].hi - boxes[i].lo;
        return std::max({e.x, e.y, e.z});
    };
    std::vector<std::size_t> order(boxes.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    // The k largest and, after them, the largest of the rest.
    auto larger = [&](std::size_t a, std::size_t b) {
        const double ea = largest_extent(a), eb = largest_extent(b);
        return ea != eb ? ea > eb : a < b;   // ties by index: the same choice every run
    };
    std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(k + 1), order.end(), larger);
    // rest[j]: the box of every primitive but the j largest.
    std::vector<Aabb> rest(k + 1);
    rest[k] = boxes[order[k]];
    for (std::size_t i = k + 1; i < order.size(); ++i) rest[k] = union_of(rest[k], boxes[order[i]]);
    for (std::size_t j = k; j-- > 0;) rest[j] = union_of(rest[j + 1], boxes[order[j]]);
    const dvec3 full = rest[0].hi - rest[0].lo;
    const double least = std::max({full.x, full.y, full.z}) * 1e-3;
    std::vector<double> volume(k + 1);
    for (std::size_t j = 0; j <= k; ++j) volume[j] = padded_volume(rest[j], least);
    const double best = *std::min_element(volume.begin(), volume.end());
    if (!(best > 0.0)) return loose;   // every box a point: nothing to shrink
    std::size_t j = 0;
    while (volume[j] > 2.0 * best) ++j;
    if (j == 0 || !(volume[j] * kLooseShrink <= volume[0])) return loose;
    if (largest_extent(order[j - 1]) < kLooseGap * largest_extent(order[j])) return loose;
    for (std::size_t i = 0; i < j; ++i) loose[order[i]] = true;
    shrink = volume[0] / volume[j];
    return loose;
}

// Fits a resolution under a limit on its cell count.
GridResolution fit(GridResolution r, std::uint64_t max_cells) {
    max_cells = std::max<std::uint64_t>(max_cells, 1);
    while (product(r) > max_cells) {
        const int a = int(std::max_element(r.begin(), r.end()) - r.begin());
        r[a] = std::max(1u, static_cast<std::uint32_t>(r[a] * 0.9));
    }
    return r;
}

}  // namespace

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

std::array<GridResolution, 2> cells_overlapping(const Aabb& box, const dvec3& lo, const dvec3& cell, const dvec3& pad,
                                                const GridResolution& res) {
    std::array<GridResolution, 2> range{};
    for (int a = 0; a < 3; ++a) {
        const double last = res[a] - 1;
        const double first_cell = std::floor((box.lo[a] - pad[a] - lo[a]) / cell[a]);
        const double last_cell = std::floor((box.hi[a] + pad[a] - lo[a]) / cell[a]);
        range[0][a] = static_cast<std::uint32_t>(std::clamp(first_cell, 0.0, last));
        range[1][a] = static_cast<std::uint32_t>(std::clamp(last_cell, 0.0, last));
    }
    return range;
}

double Grid::rounding_pad(const Aabb& box) const {
    const double magnitude = std::max({std::abs(box.lo.x), std::abs(box.lo.y), std::abs(box.lo.z),
                                       std::abs(box.hi.x), std::abs(box.hi.y), std::abs(box.hi.z)});
    // The farthest any ray travels to reach the box along one axis: a position's
    // rounding on an axis grows with the distance travelled along that axis.
    const dvec3 centre = (box.lo + box.hi) * 0.5, half = (box.hi - box.lo) * 0.5;
    double reach = 0.0;
    for (const dvec3& o : origins) {
        const dvec3 d = glm::abs(o - centre) + half;
        reach = std::max({reach, d.x, d.y, d.z});
    }
    return (magnitude + std::max({cell.x, cell.y, cell.z}) + reach) * kMagnitudePad;
}

dvec3 Grid::padding(const Aabb& box) const { return kCellPad * cell + rounding_pad(box); }

std::array<GridResolution, 2> Grid::cells_overlapping(const Aabb& box) const {
    return vkrt::cells_overlapping(box, lo, cell, padding(box), resolution);
}

namespace {

// The primitives the grid's cells list: each one's box and reference (kind <<
// REF_KIND_SHIFT | index), in the same order.
struct Listed {
    std::vector<Aabb> boxes;
    std::vector<std::uint32_t> ids;
};

// Appends one kind's boxes and references, in index order.
template <class Primitive>
void add_kind(std::span<const Primitive> items, std::uint32_t kind, const char* name, Listed& out) {
    if (items.size() > std::size_t(kernel::REF_INDEX_MASK) + 1) {
        throw std::runtime_error(fmt::format("the grid holds at most {} {} (a reference's index bits), the "
                                             "scene has {}",
                                             std::size_t(kernel::REF_INDEX_MASK) + 1, name, items.size()));
    }
    for (std::size_t i = 0; i < items.size(); ++i) {
        out.boxes.push_back(bounds(items[i]));
        out.ids.push_back((kind << kernel::REF_KIND_SHIFT) | std::uint32_t(i));
    }
}

// Every primitive's box and reference, kind by kind in the kernel's loop order:
// binning keeps this order within every cell, so each cell's references come
// grouped by kind.
Listed primitive_boxes(const GridPrimitives& primitives) {
    Listed all;
    all.boxes.reserve(0
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) +primitives.names.size()
#include "kernel/shapes/kinds.glsl"
    );
    all.ids.reserve(all.boxes.capacity());
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    add_kind(primitives.names, kernel::REF_##NAME, #names, all);
#include "kernel/shapes/kinds.glsl"
    return all;
}

// Which primitives are loose: those of the kinds the request names, and those that
// would stretch the box of the others (choose_stretching; `shrink` gets its ratio).
// Kinds loose as a whole take no part in choosing the others.
std::vector<bool> choose_loose(const Listed& all, const GridRequest& request, double& shrink) {
    std::vector<bool> loose(all.boxes.size());
    std::vector<std::size_t> kept;  // the others' indices
    std::vector<Aabb> kept_boxes;
    kept.reserve(all.boxes.size());
    kept_boxes.reserve(all.boxes.size());
    for (std::size_t i = 0; i < all.boxes.size(); ++i) {
        loose[i] = request.loose_kinds[all.ids[i] >> kernel::REF_KIND_SHIFT];
        if (!loose[i]) {
            kept.push_back(i);
            kept_boxes.push_back(all.boxes[i]);
        }
    }
    const std::vector<bool> stretching = choose_stretching(kept_boxes, request.max_loose, shrink);
    for (std::size_t k = 0; k < kept.size(); ++k) loose[kept[k]] = loose[kept[k]] || stretching[k];
    return loose;
}

// Moves the loose primitives out of `listed`; returns their references, in the order
// they were listed (by kind, like a cell's).
std::vector<std::uint32_t> take_loose(Listed& listed, const std::vector<bool>& loose) {
    std::vector<std::uint32_t> loose_refs;
    // Nothing loose, the common case: no copy of the boxes.
    if (std::find(loose.begin(), loose.end(), true) == loose.end()) return loose_refs;
    Listed kept;
    for (std::size_t i = 0; i < listed.boxes.size(); ++i) {
        if (loose[i]) {
            loose_refs.push_back(listed.ids[i]);
        } else {
            kept.boxes.push_back(listed.boxes[i]);
            kept.ids.push_back(listed.ids[i]);
        }
    }
    listed = std::move(kept);
    return loose_refs;
}

void add_note(std::string& note, const std::string& text) { note += (note.empty() ? "" : "; ") + text; }

// How large the grid may be: the device's limit on a buffer's entries or vkrt's own,
// whichever is less, and each named as the builder's notes name it.
struct GridLimits {
    std::uint64_t cells = 0;  // root cells
    std::uint64_t refs = 0;   // references
    std::string cell_limit;
    std::string ref_limit;
};

GridLimits grid_limits(std::uint64_t max_entries) {
    GridLimits limits;
    limits.refs = std::min(max_entries, kMaxGridRefs);
    // The nodes hold one entry more than there are root cells.
    limits.cells = std::min(std::max<std::uint64_t>(max_entries, 2) - 1, kMaxGridCells);
    const std::string device_limit = fmt::format("this device's buffer limit of {} entries", max_entries);
    limits.cell_limit =
        limits.cells == kMaxGridCells ? fmt::format("vkrt's limit of {} cells", kMaxGridCells) : device_limit;
    limits.ref_limit =
        limits.refs == kMaxGridRefs ? fmt::format("vkrt's limit of {} references", kMaxGridRefs) : device_limit;
    return limits;
}

// The root cells per axis: the heuristic's for `primitives` in `box`, or the
// request's, reduced (with a note) to the cell limit.
GridResolution root_resolution(const GridRequest& request, const Aabb& box, std::size_t primitives,
                               const GridLimits& limits, std::string& note) {
    const GridResolution& asked = request.resolution;
    if (product(asked) == 0) return grid_resolution(box, primitives, kGridDensity, limits.cells);
    if (product(asked) <= limits.cells) return asked;
    const GridResolution res = fit(asked, limits.cells);
    add_note(note, fmt::format("grid resolution {}x{}x{} exceeds {}; using {}x{}x{}", asked[0], asked[1], asked[2],
                               limits.cell_limit, res[0], res[1], res[2]));
    return res;
}

// Where rays start, for the padding: the corners of the box of everything (loose
// primitives included) and the eye, when given.
std::vector<dvec3> ray_origins(const Aabb& everything, const std::optional<dvec3>& eye) {
    std::vector<dvec3> origins;
    for (int corner = 0; corner < 8; ++corner) {
        origins.push_back({corner & 1 ? everything.hi.x : everything.lo.x,
                           corner & 2 ? everything.hi.y : everything.lo.y,
                           corner & 4 ? everything.hi.z : everything.lo.z});
    }
    if (eye) origins.push_back(*eye);
    return origins;
}

// At least any box's rounding padding (Grid::rounding_pad): a box's magnitude is at
// most the scene's, a root cell at most twice it (the box of everything, with a
// little margin), and a ray travels at most from the eye across the box of everything.
double most_rounding(const Aabb& everything, const std::optional<dvec3>& eye) {
    const double magnitude =
        std::max({std::abs(everything.lo.x), std::abs(everything.lo.y), std::abs(everything.lo.z),
                  std::abs(everything.hi.x), std::abs(everything.hi.y), std::abs(everything.hi.z)});
    double reach = glm::length(everything.hi - everything.lo);
    if (eye) reach += glm::length(*eye - glm::clamp(*eye, everything.lo, everything.hi));
    return (3.1 * magnitude + reach) * kMagnitudePad;
}

// Lays `res` root cells over `box`: float corners and cell size, the box grown by the
// largest padding so that a ray grazing a primitive on the boundary still clips to a
// non-empty interval despite rounding in the slab test.
void lay_root_cells(Grid& g, const Aabb& box, const GridResolution& res, double most_rounding) {
    g.resolution = res;
    for (int a = 0; a < 3; ++a) {
        // 1.1: the cell ends up a little wider than extent / res, by the margins.
        const double margin = 1.1 * kCellPad * (box.hi[a] - box.lo[a]) / res[a] + most_rounding;
        g.lo[a] = float_down(box.lo[a] - margin);
        g.cell[a] = float_up((box.hi[a] + margin - g.lo[a]) / res[a]);
        g.hi[a] = float_up(g.lo[a] + g.cell[a] * res[a]);
        g.pad[a] = margin;
    }
}

// Each box's rounding padding in the grid as laid.
std::vector<double> rounding_pads(const Grid& g, const std::vector<Aabb>& boxes) {
    std::vector<double> rounding(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) rounding[i] = g.rounding_pad(boxes[i]);
    return rounding;
}

// A root cell's padding of a box (Grid::padding) whose rounding padding is `rounding`.
dvec3 root_pad(const Grid& g, double rounding) { return kCellPad * g.cell + rounding; }

// The references the root cells would hold, loose ones included, counted before
// anything is allocated: an upper bound, as triangles go only into the cells they cross.
std::uint64_t count_references(const Grid& g, const std::vector<Aabb>& boxes, const std::vector<double>& rounding) {
    std::uint64_t total = g.loose;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const auto [first, last] =
            vkrt::cells_overlapping(boxes[i], g.lo, g.cell, root_pad(g, rounding[i]), g.resolution);
        total += std::uint64_t(last[0] - first[0] + 1) * (last[1] - first[1] + 1) * (last[2] - first[2] + 1);
    }
    return total;
}

// Lays the root cells, starting at `res`, coarser (with a note) until their
// references fit the limit: coarser cells hold fewer copies of the large
// primitives. Returns the boxes' rounding paddings in the grid as laid; throws if
// even one cell holds too many.
std::vector<double> lay_within_limits(Grid& g, const Aabb& box, GridResolution res, const std::vector<Aabb>& boxes,
                                      double most_rounding, const GridLimits& limits, std::string& note) {
    for (;;) {
        lay_root_cells(g, box, res, most_rounding);
        std::vector<double> rounding = rounding_pads(g, boxes);
        const std::uint64_t total = count_references(g, boxes, rounding);
        if (total <= limits.refs) return rounding;
        if (product(res) <= 1) {
            throw std::runtime_error(fmt::format("the scene's {} primitives do not fit one grid: {} references, "
                                                 "over {}",
                                                 boxes.size() + g.loose, total, limits.ref_limit));
        }
        res = fit(res, product(res) / 2);
        add_note(note, fmt::format("grid {}x{}x{} needs {} references, over {}; using {}x{}x{}", g.resolution[0],
                                   g.resolution[1], g.resolution[2], total, limits.ref_limit, res[0], res[1], res[2]));
    }
}

// Each root cell's primitives, in two passes: count them, then place them after
// the prefix sum.
RootCells bin_root_cells(const Grid& g, const Listed& listed, const Binner& binner,
                         const std::vector<double>& rounding) {
    const GridResolution res = g.resolution;  // a copy: the counts written below cannot alias it
    const std::uint64_t cells = g.cell_count();
    const auto cell_index = [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
        return (std::uint64_t(z) * res[1] + y) * res[0] + x;
    };
    const auto for_each_cell = [&](std::size_t i, const auto& f) {
        binner.cells(listed.boxes[i], listed.ids[i], g.lo, g.cell, root_pad(g, rounding[i]), res, f);
    };
    RootCells roots;
    roots.starts.assign(cells + 1, 0);
    for (std::size_t i = 0; i < listed.boxes.size(); ++i) {
        for_each_cell(i, [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
            ++roots.starts[cell_index(x, y, z)];
        });
    }
    std::uint32_t sum = 0;
    for (std::uint64_t c = 0; c <= cells; ++c) {
        const std::uint32_t n = roots.starts[c];
        roots.starts[c] = sum;
        sum += n;
    }
    std::vector<std::uint32_t> cursor(roots.starts.begin(), roots.starts.end() - 1);
    roots.items.assign(sum, 0);
    for (std::size_t i = 0; i < listed.boxes.size(); ++i) {
        for_each_cell(i, [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
            roots.items[cursor[cell_index(x, y, z)]++] = std::uint32_t(i);
        });
    }
    return roots;
}

}  // namespace

Grid build_grid(const GridPrimitives& primitives, const GridRequest& request, std::string& note) {
    Listed listed = primitive_boxes(primitives);
    Grid g;
    if (listed.boxes.empty()) {
        g.nodes = {0, 0};  // one empty root cell
        return g;
    }
    // Rays may start on a loose primitive far outside the grid's box: the padding
    // allows for positions at the magnitude of, and rays as long as, the box of
    // everything.
    const Aabb everything = grid_box(listed.boxes);
    std::vector<std::uint32_t> loose_refs = take_loose(listed, choose_loose(listed, request, g.loose_shrink));
    g.loose = std::uint32_t(loose_refs.size());
    if (listed.boxes.empty()) {  // everything is loose: one cell, empty
        g.nodes = {g.loose, g.loose};
        g.refs = std::move(loose_refs);
        return g;
    }
    const Aabb box = grid_box(listed.boxes);
    const GridLimits limits = grid_limits(request.max_entries);
    const GridResolution res = root_resolution(request, box, listed.boxes.size(), limits, note);
    g.origins = ray_origins(everything, request.eye);
    const std::vector<double> rounding =
        lay_within_limits(g, box, res, listed.boxes, most_rounding(everything, request.eye), limits, note);
    const Binner binner{primitives.triangles};
    const RootCells roots = bin_root_cells(g, listed, binner, rounding);
    g.refs = std::move(loose_refs);
    const bool split = request.split && product(request.resolution) == 0;
    place_cells(g, roots, listed.boxes, listed.ids, binner, rounding, split, limits.refs, request.max_entries);
    return g;
}

}  // namespace vkrt

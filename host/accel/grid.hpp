#pragma once
// The grid the kernel walks (shaders/kernel/grid.glsl), built on the host and flattened
// into two arrays: the cells' nodes and one concatenated list of primitive
// references. A uniform grid of root cells, the paper's Fig. 7, whose crowded cells
// are split into 4 x 4 x 4 children, recursively. docs/grid.md describes the heuristics.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "kernel/types.hpp"
#include "scene/shapes/support.hpp"  // Aabb

namespace vkrt {

// What the grid was for one render, as the stats report it.
struct GridStats {
    bool used = false;
    std::string reason;                              // why it was, or was not, used
    // What is left out of the grid and tested once per ray instead: whole kinds, as
    // "triangles: 2", and loose primitives (GridRequest::max_loose), as "triangles: 2 of 49294".
    std::vector<std::string> outside;
    // What the builder reduced and the limit that forced it (build_grid's note), empty
    // when it built what was asked: also in `reason`, and printed as a warning.
    std::string warning;
    std::array<std::uint32_t, 3> resolution{0, 0, 0};  // root cells per axis
    std::uint64_t cells = 0;                         // leaf cells: those a walk visits
    std::uint32_t levels = 0;                        // how deep the deepest split goes
    std::uint64_t references = 0;                    // primitive references: the loose ones and all cells'
    std::size_t bytes = 0;                           // both grid buffers
    double build_seconds = 0.0;
};

using GridResolution = std::array<std::uint32_t, 3>;

struct Grid {
    // Float-representable corners and cell size: exactly the values the kernel gets.
    glm::dvec3 lo{0.0};
    glm::dvec3 hi{0.0};
    glm::dvec3 cell{1.0};
    GridResolution resolution{1, 1, 1};      // root cells per axis
    // One word per node, the offset of its references (kernel::GRID_INNER,
    // constants.glsl), and one more where the last node's end: nodes 0 to cells - 1
    // are the root cells (x fastest), then the children of split cells, 64 at a time.
    // References [0, nodes[0]) are the loose primitives. Without splits, the
    // uniform grid's prefix sum of cell sizes.
    std::vector<std::uint32_t> nodes;
    // kind << REF_KIND_SHIFT | index: first the loose primitives, refs [0, loose),
    // listed in no cell and tested once per ray, then each node's, in node order (an
    // inner cell's is the node of its first child).
    std::vector<std::uint32_t> refs;
    std::uint32_t loose = 0;
    std::uint64_t leaves = 0;                // leaf cells
    std::uint32_t levels = 0;                // 0: no cell split, a uniform grid
    // Where rays start, for the padding: the corners of the box of everything (loose
    // primitives included) and the eye, when given.
    std::vector<glm::dvec3> origins;
    // How many times larger the box would be with the ones left out for their boxes.
    double loose_shrink = 1.0;

    std::uint64_t cell_count() const {   // root cells
        return std::uint64_t(resolution[0]) * resolution[1] * resolution[2];
    }
    std::size_t bytes() const { return (nodes.size() + refs.size()) * sizeof(std::uint32_t); }
    // The largest padding any primitive's box gets, on each side; the grid box leaves
    // at least this much around every primitive.
    glm::dvec3 pad{0.0};

    // The part of a box's padding that is float rounding: a position near the box is
    // known, on each axis, to within a few 2^-24 of its magnitude, of the width of the
    // root cell whose corner it is found from, and of the distance a ray travels
    // along the axis to get there. (A root corner, grid_min + root * cell, is rounded
    // at the grid's extent, but every box has a corner of the scene at least half
    // the extent away, so the reach covers it.)
    double rounding_pad(const Aabb& box) const;
    // A root cell's padding of the box: a thousandth of the cell and the rounding.
    glm::dvec3 padding(const Aabb& box) const;

    // The cell index range [first, last] (inclusive, per axis) a box overlaps once
    // padded: the root cells the builder binned the box into (a triangle's: those of
    // them it crosses).
    std::array<GridResolution, 2> cells_overlapping(const Aabb& box) const;
};

// The cells [first, last] (inclusive, per axis) of a grid of `res` cells of size
// `cell` from corner `lo` that a box overlaps once grown by `pad` on every side,
// clamped into the grid: how the builder bins a box, into root cells and into a
// split cell's children alike.
std::array<GridResolution, 2> cells_overlapping(const Aabb& box, const glm::dvec3& lo, const glm::dvec3& cell,
                                                const glm::dvec3& pad, const GridResolution& res);

// Cells per total primitive: Woo's rule, total cells = density * primitives, with the
// cells per axis proportional to the box's extent on that axis.
inline constexpr double kGridDensity = 4.0;

// Cells per axis for `primitives` primitives in `box`, at most `max_cells` in all.
// Axes with (nearly) no extent get one cell and leave the budget to the others.
GridResolution grid_resolution(const Aabb& box, std::size_t primitives, double density, std::uint64_t max_cells);

struct GridRequest {
    GridResolution resolution{0, 0, 0};  // zeros: by the heuristic
    std::uint64_t max_entries = 0xFFFFFFFFu;  // per array, the device's limit
    // Where rays from outside the grid start (the camera). A float ray's position is
    // only known to about its distance travelled times 2^-23, so the boxes are padded
    // by that much, lest the walk step past a primitive the ray really touches.
    std::optional<glm::dvec3> eye;
    // Loose primitives are listed in no cell and tested once per ray instead: every
    // primitive of a kind flagged here (indexed by kind, REF_SPHERE...), and at most
    // `max_loose` more whose boxes would stretch the grid's far beyond the rest (a
    // floor polygon under a tree; build_grid says when).
    std::array<bool, kernel::PRIMITIVE_KINDS> loose_kinds{};
    std::size_t max_loose = 0;
    // Split crowded cells where it pays (docs/grid.md). A resolution given above
    // asks for one particular uniform grid, which is never split.
    bool split = true;
};

// What the grid is built over: one span per kind of primitive
// (shaders/kernel/shapes/kinds.glsl), each primitive bounded by its kind's
// bounds() (host/scene/shapes/<name>.hpp). Kinds left out are empty.
struct GridPrimitives {
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) std::span<const kernel::Name> names;
#include "kernel/shapes/kinds.glsl"
};

// Builds the grid over every primitive but the loose ones (GridRequest::max_loose).
// Within each leaf cell, and among the loose ones, the references are grouped by kind, in
// the order of shapes/kinds.glsl, each kind in index order: the
// kernel walks a cell in one loop per kind (shaders/kernel/traversal.glsl). A
// resolution that would not fit the device is reduced until it does; `note` then
// says so. More than 2^29 primitives of one kind (the reference's index bits) is an
// error.
Grid build_grid(const GridPrimitives& primitives, const GridRequest& request, std::string& note);

}  // namespace vkrt

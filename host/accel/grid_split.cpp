#include "accel/grid_split.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <span>
#include <utility>

namespace vkrt {
namespace {

using glm::dvec3;

constexpr std::uint32_t kPerAxis = 1u << kernel::GRID_SPLIT_BITS;

// Where to split a cell: a surface-area argument (after MacDonald & Booth 1990). A
// ray through a cell crosses on average 1 + 3 * 4 * 1/3 = 5 of its 4 x 4 x 4
// children (a cube's mean chord is 2/3 of its side, and a random direction projects
// a third of it on each axis), and meets a child's primitives with the probability
// that it meets the child, whose surface is 1/16 of the cell's. A step into a split
// cell costs about two primitive tests (a node per level, and the lookup of the
// point where the ray leaves; docs/decisions/0023-split-grid-cells.md). A leaf
// costs its n tests; a split pays when 5 * 2 + (sum of the children's counts) / 16
// costs less.
constexpr double kChildrenCrossed = 5.0;
constexpr double kVisitCost = 2.0;
constexpr double kChildShare = 1.0 / 16.0;

// Whether to keep the splits at all: a walk that may meet split cells costs more per
// step on every ray (a node per level, the point where the ray leaves), which the
// kernel leaves out of a grid without splits (feature GRID_SPLIT). The splits are
// kept when the root cells are crowded, a listed primitive sharing its cell with
// kCrowded others on average (sum of n^2 over sum of n), and when they bring the
// expected cost of a ray through the cells they split, summed over the non-empty
// leaves as surface times (visit + tests), below kSplitGain of those cells' own.
// docs/decisions/0023-split-grid-cells.md gives the measurements behind both.
constexpr double kUniformVisitCost = 1.0;
constexpr double kCrowded = 64.0;
constexpr double kSplitGain = 0.5;

// Cells no smaller than this many times the rounding padding: below it the padding
// lists every primitive in most of the children.
constexpr double kFinestInPads = 2.0;

// A cell waiting to be placed: its node, its primitives, its depth (0: root) and
// its lowest fine coordinates.
struct Pending {
    std::uint32_t node;
    std::vector<std::uint32_t> items;
    std::uint32_t level;
    std::array<std::uint32_t, 3> fine_lo;
};

struct Splitter {
    Grid& g;
    const std::vector<Aabb>& boxes;
    const std::vector<std::uint32_t>& ids;
    const Binner& binner;
    const std::vector<double>& rounding;
    bool split;
    std::uint64_t max_refs;
    std::uint64_t max_words;
    std::uint64_t planned_refs;   // references once every split decided so far is made
    // The expected cost of a ray through the split root cells, as the sum over their
    // non-empty leaf cells of surface (a root cell's is 1) times (visit + tests), and
    // as it would be had they not been split.
    double split_cost = 0.0;
    double unsplit_cost = 0.0;
    std::deque<Pending> queue;    // children, in node order

    // Places a cell whose node is the next one: a leaf's references, or an inner
    // cell's reference to its first child, whose children then wait in the queue.
    // Cells placed in node order lay out their references in node order, so that
    // each leaf's end is the next node's start.
    void place(std::uint32_t node, std::span<const std::uint32_t> items, std::uint32_t level,
               const std::array<std::uint32_t, 3>& fine_lo) {
        if (split && double(items.size()) > kChildrenCrossed * kVisitCost) {
            std::array<std::vector<std::uint32_t>, kernel::GRID_CHILDREN> children;
            if (worth_splitting(items, level, fine_lo, children)) {
                const std::uint32_t first = std::uint32_t(g.nodes.size());
                g.nodes[node] = kernel::GRID_INNER | std::uint32_t(g.refs.size());
                g.refs.push_back(first);
                g.nodes.resize(g.nodes.size() + kernel::GRID_CHILDREN, 0);
                g.levels = std::max(g.levels, level + 1);
                if (level == 0) unsplit_cost += kUniformVisitCost + double(items.size());
                const std::uint32_t size = 1u << (kernel::GRID_FRACTION_BITS - (level + 1) * kernel::GRID_SPLIT_BITS);
                for (std::uint32_t k = 0; k < kernel::GRID_CHILDREN; ++k) {
                    const std::array<std::uint32_t, 3> c{k % kPerAxis, (k / kPerAxis) % kPerAxis,
                                                         k / (kPerAxis * kPerAxis)};
                    queue.push_back({first + k, std::move(children[k]), level + 1,
                                     {fine_lo[0] + c[0] * size, fine_lo[1] + c[1] * size, fine_lo[2] + c[2] * size}});
                }
                return;
            }
        }
        g.nodes[node] = std::uint32_t(g.refs.size());
        for (std::uint32_t i : items) g.refs.push_back(ids[i]);
        ++g.leaves;
        if (level > 0 && !items.empty()) {
            split_cost += std::pow(kChildShare, double(level)) * (kVisitCost + double(items.size()));
        }
    }

    // Bins the cell's primitives into its 64 children and says whether the split pays.
    bool worth_splitting(std::span<const std::uint32_t> items, std::uint32_t level,
                         const std::array<std::uint32_t, 3>& fine_lo,
                         std::array<std::vector<std::uint32_t>, kernel::GRID_CHILDREN>& children) {
        const double n = double(items.size());
        if (level >= kernel::GRID_MAX_LEVELS) return false;
        if (g.nodes.size() + kernel::GRID_CHILDREN + 1 > max_words) return false;
        const dvec3 child = g.cell / std::pow(double(kPerAxis), double(level + 1));
        double most_rounding = 0.0;
        for (std::uint32_t i : items) most_rounding = std::max(most_rounding, rounding[i]);
        if (std::max({child.x, child.y, child.z}) < kFinestInPads * most_rounding) return false;
        const dvec3 fine = g.cell / double(kernel::GRID_FINE);
        const dvec3 lo = g.lo + dvec3(fine_lo[0], fine_lo[1], fine_lo[2]) * fine;
        std::uint64_t sum = 0;
        for (std::uint32_t i : items) {
            binner.cells(boxes[i], ids[i], lo, child, kCellPad * child + rounding[i], {kPerAxis, kPerAxis, kPerAxis},
                         [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
                             children[(z * kPerAxis + y) * kPerAxis + x].push_back(i);
                             ++sum;
                         });
        }
        // One more reference: the inner cell's pointer to its children.
        const std::uint64_t added = sum + 1 - items.size();
        const bool pays = kChildrenCrossed * kVisitCost + double(sum) * kChildShare < n;
        if (!pays || planned_refs + added > max_refs) {
            for (auto& c : children) c.clear();
            return false;
        }
        planned_refs += added;
        return true;
    }
};

}  // namespace

std::size_t Binner::polygon(std::uint32_t id, std::array<dvec3, 4>& v) const {
    if ((id >> kernel::REF_KIND_SHIFT) != kernel::REF_TRIANGLE) return 0;
    const kernel::Triangle& t = triangles[id & kernel::REF_INDEX_MASK];
    auto point = [](const kernel::vec4& p) { return dvec3(p.x, p.y, p.z); };
    v[0] = point(t.p0);
    v[1] = point(t.p1);
    v[2] = point(t.p2);
    if (t.meta.z == kernel::SHAPE_TRIANGLE) return 3;
    v[3] = point(t.p0 + (t.p2 - t.p1));   // in float, as bounds() and the kernel
    return 4;
}

void place_cells(Grid& g, const RootCells& roots, const std::vector<Aabb>& boxes,
                 const std::vector<std::uint32_t>& ids, const Binner& binner, const std::vector<double>& rounding,
                 bool split, std::uint64_t max_refs, std::uint64_t max_words) {
    const std::uint64_t cells = g.cell_count();
    const std::size_t loose = g.refs.size();
    auto build = [&](bool split_cells) {
        g.nodes.assign(cells, 0);
        g.refs.resize(loose);
        g.leaves = 0;
        g.levels = 0;
        Splitter s{g, boxes, ids, binner, rounding, split_cells, max_refs, max_words, loose + roots.items.size(), 0.0, 0.0, {}};
        const GridResolution& res = g.resolution;
        for (std::uint64_t c = 0; c < cells; ++c) {
            const std::span<const std::uint32_t> items(roots.items.data() + roots.starts[c],
                                                       roots.starts[c + 1] - roots.starts[c]);
            s.place(std::uint32_t(c), items, 0,
                    {std::uint32_t(c % res[0]) << kernel::GRID_FRACTION_BITS,
                     std::uint32_t(c / res[0] % res[1]) << kernel::GRID_FRACTION_BITS,
                     std::uint32_t(c / (std::uint64_t(res[0]) * res[1])) << kernel::GRID_FRACTION_BITS});
        }
        while (!s.queue.empty()) {
            const Pending cell = std::move(s.queue.front());
            s.queue.pop_front();
            s.place(cell.node, cell.items, cell.level, cell.fine_lo);
        }
        g.nodes.push_back(std::uint32_t(g.refs.size()));   // where the last node's references end
        return s.split_cost < kSplitGain * s.unsplit_cost;
    };
    // The crowding is the root cells' alone: a grid that is not crowded is not tried.
    double squares = 0.0, listed = 0.0;
    for (std::uint64_t c = 0; c < cells; ++c) {
        const double n = double(roots.starts[c + 1] - roots.starts[c]);
        squares += n * n;
        listed += n;
    }
    const bool crowded = squares >= kCrowded * listed;
    if (!(split && crowded && build(true))) build(false);
}

}  // namespace vkrt

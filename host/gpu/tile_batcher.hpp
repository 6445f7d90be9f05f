#pragma once
// How many dispatches one Vulkan queue submission takes. The work is a sequence of
// items, sample by sample and within a sample tile by tile (item i is tile
// i % tiles). Tiles cost very different amounts (a tile of sky against one of a
// sphereflake), so a submission is planned from what each tile was measured to
// cost, never from an average: a batch of cheap tiles must not grow into one that
// runs into the expensive ones. No Vulkan here, so the tests can drive it.
#include <cstdint>
#include <vector>

namespace vkrt::gpu {

// A slab of `width` x `rows` pixels cut into tiles of `tile_width` x `tile_height`
// (multiples of 8, the workgroup's side; the last tiles of a row or column may be
// cut short by the edge).
struct Tiling {
    std::uint32_t width = 0, rows = 0;
    std::uint32_t tile_width = 0, tile_height = 0;

    std::uint32_t across() const { return (width + tile_width - 1) / tile_width; }
    std::uint32_t down() const { return (rows + tile_height - 1) / tile_height; }
    std::uint32_t count() const { return across() * down(); }
    // Halves the longer side of the tiles, to a multiple of 8 still covering the
    // slab in as many tiles; false when they are 8 x 8 already.
    bool split();
};

// The tiling of a slab with tiles at most `tile_width` x `tile_height`.
Tiling tile_slab(std::uint32_t width, std::uint32_t rows, std::uint32_t tile_width, std::uint32_t tile_height);

// A rectangle of a slab's pixels, from the slab's corner; its tiles, as tile_slab
// cuts a slab of its size, start at (x, y).
struct Region {
    std::uint32_t x = 0, y = 0, width = 0, rows = 0;
    bool operator==(const Region&) const = default;
};

// What remains of one sample of `region`, cut by `tiling`, once its tiles before
// `next_tile` (in order, row by row) are done: the rest of that tile's row, then the
// rows below, leaving out what is empty. Tiles can then be split in the middle of a
// sample, and the rest of it rendered with the smaller ones.
std::vector<Region> rest_of_sample(const Region& region, const Tiling& tiling, std::uint32_t next_tile);

class TileBatcher {
public:
    TileBatcher(std::uint32_t tiles, double target_seconds, std::uint32_t max_batch);

    // The items, from `first` on, that the next submission takes: as many as the
    // measured costs fit in the target, at least one, at most `left` and the
    // maximum. A tile not measured yet goes alone, so that it gets measured.
    std::uint32_t next(std::uint32_t first, std::uint32_t left) const;

    // The submission of items [first, first + count) took `seconds`: a lone tile
    // gets its cost; a batch rescales the costs of its tiles by measured / predicted,
    // which follows a machine that speeds up or slows down.
    void measured(std::uint32_t first, std::uint32_t count, double seconds);

    // The measured cost of the costliest tile, 0 before any.
    double costliest() const;

private:
    std::uint32_t tiles_;
    double target_;
    std::uint32_t max_batch_;
    std::vector<double> cost_;  // seconds of one tile of one sample; < 0 while unknown
};

}  // namespace vkrt::gpu

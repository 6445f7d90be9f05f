// How the Vulkan backend groups tile dispatches into submissions: from each tile's
// measured cost, so that no submission runs far past the target however unevenly
// the tiles cost.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "gpu/tile_batcher.hpp"

namespace {

using vkrt::gpu::TileBatcher;

// Runs `samples` samples of tiles costing `cost` seconds each through the batcher
// (a submission takes the sum of its items' costs, times `slowdown`) and returns
// the seconds of every submission.
std::vector<double> submissions(TileBatcher& batcher, const std::vector<double>& cost, std::uint32_t samples,
                                double slowdown = 1.0) {
    const std::uint32_t items = samples * std::uint32_t(cost.size());
    std::vector<double> out;
    for (std::uint32_t done = 0; done < items;) {
        const std::uint32_t n = batcher.next(done, items - done);
        EXPECT_GE(n, 1u);
        double seconds = 0.0;
        for (std::uint32_t i = done; i < done + n; ++i) seconds += cost[i % cost.size()] * slowdown;
        batcher.measured(done, n, seconds);
        out.push_back(seconds);
        done += n;
    }
    return out;
}

TEST(TileBatcher, MeasuresEveryTileAloneFirst) {
    TileBatcher batcher(4, 0.25, 256);
    const std::vector<double> times = submissions(batcher, {0.01, 0.02, 0.03, 0.04}, 1);
    EXPECT_EQ(times.size(), 4u);
}

TEST(TileBatcher, CheapTilesDoNotCarryABatchIntoExpensiveOnes) {
    // Sixteen tiles of sky at 1 ms, then four of heavy geometry at 0.2 s: a batch
    // sized by the average (or grown on the sky) would run for seconds.
    std::vector<double> cost(16, 0.001);
    cost.insert(cost.end(), 4, 0.2);
    TileBatcher batcher(std::uint32_t(cost.size()), 0.25, 256);
    const std::vector<double> times = submissions(batcher, cost, 50);
    EXPECT_LE(*std::max_element(times.begin(), times.end()), 0.25);
    // And it batches: far fewer submissions than the 1000 items.
    EXPECT_LT(times.size(), 300u);
}

TEST(TileBatcher, FollowsAMachineThatSlowsDown) {
    const std::vector<double> cost(8, 0.01);
    TileBatcher batcher(8, 0.25, 256);
    submissions(batcher, cost, 20);
    // Three times slower from now on: the first batch overshoots by the factor,
    // after which the rescaled costs bring the submissions back to the target.
    const std::vector<double> slow = submissions(batcher, cost, 40, 3.0);
    EXPECT_LE(slow.front(), 0.25 * 3.0 + 1e-9);
    EXPECT_LE(*std::max_element(slow.begin() + 1, slow.end()), 0.25 + 1e-9);
}

TEST(TileBatcher, ATileAboveTheTargetGoesAlone) {
    TileBatcher batcher(2, 0.25, 256);
    const std::vector<double> times = submissions(batcher, {0.6, 0.01}, 4);
    for (double t : times) EXPECT_TRUE(t == 0.6 || t <= 0.25) << t;
}

TEST(TileBatcher, NeverMoreThanLeftOrTheMaximum) {
    TileBatcher batcher(1, 10.0, 16);
    batcher.measured(0, 1, 0.0001);
    EXPECT_EQ(batcher.next(1, 100), 16u);
    EXPECT_EQ(batcher.next(1, 3), 3u);
}

}  // namespace

namespace {

using vkrt::gpu::Tiling;

TEST(Tiling, TilesAreCutToTheSlabAndToWholeWorkgroups) {
    const Tiling t = vkrt::gpu::tile_slab(20, 200, 256, 64);
    EXPECT_EQ(t.tile_width, 24u);   // 20 rounded up to whole 8-pixel workgroups
    EXPECT_EQ(t.tile_height, 64u);
    EXPECT_EQ(t.across(), 1u);
    EXPECT_EQ(t.down(), 4u);        // the last tile cut short by the edge
}

TEST(Tiling, SplittingHalvesTheLongerSideDownToOneWorkgroup) {
    Tiling t = vkrt::gpu::tile_slab(512, 512, 256, 64);
    EXPECT_EQ(t.count(), 16u);
    ASSERT_TRUE(t.split());
    EXPECT_EQ(t.tile_width, 128u);
    EXPECT_EQ(t.tile_height, 64u);
    int splits = 1;
    while (t.split()) ++splits;
    EXPECT_EQ(t.tile_width, 8u);
    EXPECT_EQ(t.tile_height, 8u);
    EXPECT_EQ(splits, 8);           // 256 -> 8 in five halvings, 64 -> 8 in three
    EXPECT_EQ(t.count(), 64u * 64u);
}

using vkrt::gpu::Region;

TEST(Tiling, TheRestOfASampleIsTheRestOfItsTileRowThenTheRowsBelow) {
    const Region region{8, 16, 100, 70};
    const Tiling t = vkrt::gpu::tile_slab(region.width, region.rows, 32, 32);   // 4 x 3 tiles
    EXPECT_EQ(vkrt::gpu::rest_of_sample(region, t, 0), std::vector<Region>{region});
    EXPECT_EQ(vkrt::gpu::rest_of_sample(region, t, 5),
              (std::vector<Region>{{40, 48, 68, 32}, {8, 80, 100, 6}}));
    EXPECT_EQ(vkrt::gpu::rest_of_sample(region, t, 4), std::vector<Region>{(Region{8, 48, 100, 38})});
    EXPECT_EQ(vkrt::gpu::rest_of_sample(region, t, 9), std::vector<Region>{(Region{40, 80, 68, 6})});
    EXPECT_TRUE(vkrt::gpu::rest_of_sample(region, t, t.count()).empty());
}

// Whatever tile a sample is cut at, its done tiles and the rest cover the region's
// pixels exactly once.
TEST(Tiling, TheRestOfASampleCoversWhatIsLeftExactlyOnce) {
    const Region region{16, 8, 75, 41};
    for (const std::uint32_t side : {8u, 16u, 24u, 64u}) {
        const Tiling t = vkrt::gpu::tile_slab(region.width, region.rows, side, side / 2 + 8);
        for (std::uint32_t next = 0; next <= t.count(); ++next) {
            std::vector<int> covered(std::size_t(region.x + region.width) * (region.y + region.rows), 0);
            auto cover = [&](std::uint32_t x0, std::uint32_t y0, std::uint32_t w, std::uint32_t h) {
                for (std::uint32_t y = y0; y < y0 + h; ++y)
                    for (std::uint32_t x = x0; x < x0 + w; ++x) ++covered[y * (region.x + region.width) + x];
            };
            for (std::uint32_t tile = 0; tile < next; ++tile) {
                const std::uint32_t x = tile % t.across() * t.tile_width, y = tile / t.across() * t.tile_height;
                cover(region.x + x, region.y + y, std::min(t.tile_width, region.width - x),
                      std::min(t.tile_height, region.rows - y));
            }
            for (const Region& r : vkrt::gpu::rest_of_sample(region, t, next)) cover(r.x, r.y, r.width, r.rows);
            for (std::uint32_t y = 0; y < region.y + region.rows; ++y) {
                for (std::uint32_t x = 0; x < region.x + region.width; ++x) {
                    const bool inside = x >= region.x && y >= region.y;
                    ASSERT_EQ(covered[y * (region.x + region.width) + x], inside ? 1 : 0)
                        << "tile side " << side << ", cut at tile " << next << ", pixel " << x << "," << y;
                }
            }
        }
    }
}

}  // namespace

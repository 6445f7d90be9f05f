// How the Vulkan backend groups band dispatches into submissions: from each band's
// measured cost, so that no submission runs far past the target however unevenly
// the bands cost.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "gpu/band_batcher.hpp"

namespace {

using vkrt::gpu::BandBatcher;

// Runs `samples` samples of bands costing `cost` seconds each through the batcher
// (a submission takes the sum of its items' costs, times `slowdown`) and returns
// the seconds of every submission.
std::vector<double> submissions(BandBatcher& batcher, const std::vector<double>& cost, std::uint32_t samples,
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

TEST(BandBatcher, MeasuresEveryBandAloneFirst) {
    BandBatcher batcher(4, 0.25, 256);
    const std::vector<double> times = submissions(batcher, {0.01, 0.02, 0.03, 0.04}, 1);
    EXPECT_EQ(times.size(), 4u);
}

TEST(BandBatcher, CheapBandsDoNotCarryABatchIntoExpensiveOnes) {
    // Sixteen bands of sky at 1 ms, then four of heavy geometry at 0.2 s: a batch
    // sized by the average (or grown on the sky) would run for seconds.
    std::vector<double> cost(16, 0.001);
    cost.insert(cost.end(), 4, 0.2);
    BandBatcher batcher(std::uint32_t(cost.size()), 0.25, 256);
    const std::vector<double> times = submissions(batcher, cost, 50);
    EXPECT_LE(*std::max_element(times.begin(), times.end()), 0.25);
    // And it batches: far fewer submissions than the 1000 items.
    EXPECT_LT(times.size(), 300u);
}

TEST(BandBatcher, FollowsAMachineThatSlowsDown) {
    const std::vector<double> cost(8, 0.01);
    BandBatcher batcher(8, 0.25, 256);
    submissions(batcher, cost, 20);
    // Three times slower from now on: the first batch overshoots by the factor,
    // after which the rescaled costs bring the submissions back to the target.
    const std::vector<double> slow = submissions(batcher, cost, 40, 3.0);
    EXPECT_LE(slow.front(), 0.25 * 3.0 + 1e-9);
    EXPECT_LE(*std::max_element(slow.begin() + 1, slow.end()), 0.25 + 1e-9);
}

TEST(BandBatcher, ABandAboveTheTargetGoesAlone) {
    BandBatcher batcher(2, 0.25, 256);
    const std::vector<double> times = submissions(batcher, {0.6, 0.01}, 4);
    for (double t : times) EXPECT_TRUE(t == 0.6 || t <= 0.25) << t;
}

TEST(BandBatcher, NeverMoreThanLeftOrTheMaximum) {
    BandBatcher batcher(1, 10.0, 16);
    batcher.measured(0, 1, 0.0001);
    EXPECT_EQ(batcher.next(1, 100), 16u);
    EXPECT_EQ(batcher.next(1, 3), 3u);
}

}  // namespace

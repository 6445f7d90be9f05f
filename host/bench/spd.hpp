#pragma once
// `vkrt bench --spd`: every SPD scene (.nff) in --spd-dir rendered under the SPD
// test rules on each backend; the ray counts by kind beside Eric Haines' published
// ones, and the preprocessing and ray-tracing times (docs/bench.md).
#include "bench/bench.hpp"

namespace vkrt::bench {

// Returns the exit status: 1 when a scene's counts differ between runs (they are
// deterministic, so that is a bug), else 0. Throws for errors the caller reports.
int run_spd_bench(const BenchArgs& args);

}  // namespace vkrt::bench

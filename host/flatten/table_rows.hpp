#pragma once
// The albedo tables' builders (ggx_albedo.cpp, sheen_albedo.cpp,
// rough_glass_albedo.cpp) integrate one row of knots after another on every core,
// each thread with its own reference Kernel, whose functions they integrate.
#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "kernel/kernel.hpp"

namespace vkrt {

// Calls row(kernel, j) once for each j in [0, rows), on up to 16 threads.
template <class Row>
void for_each_row_on_every_core(int rows, Row row) {
    std::atomic<int> next_row{0};
    auto work = [&] {
        kernel::Kernel k;
        for (int j = next_row++; j < rows; j = next_row++) row(k, j);
    };
    std::vector<std::thread> threads(std::max(1u, std::min(std::thread::hardware_concurrency(), 16u)) - 1);
    for (std::thread& t : threads) t = std::thread(work);
    work();
    for (std::thread& t : threads) t.join();
}

}  // namespace vkrt

#pragma once
// The kernel's invariants, CHECK(condition) in shaders/kernel/: finite weights,
// densities positive where a direction was drawn, unit directions. render.comp
// defines CHECK as nothing, so the GPU never pays for one; the reference backend
// (kernel.hpp) tests each condition while checks are on, which the test suite turns
// on for every test (tests/support) and a render never does: off, a check costs one
// relaxed load. A failed check does not stop the render; it is counted, and the
// first one is kept for the test to report.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

namespace vkrt::kernel::checks {

inline std::atomic<bool> enabled{false};
inline std::atomic<std::uint64_t> failures{0};
inline std::mutex first_mutex;
inline std::string first;  // "file:line: condition" of the first failure

inline void failed(const char* condition, const char* file, int line) {
    if (failures.fetch_add(1, std::memory_order_relaxed) == 0) {
        const std::lock_guard<std::mutex> lock(first_mutex);
        first = std::string(file) + ":" + std::to_string(line) + ": CHECK(" + condition + ")";
    }
}

// Forgets earlier failures (a test starts from none).
inline void reset() {
    failures.store(0, std::memory_order_relaxed);
    const std::lock_guard<std::mutex> lock(first_mutex);
    first.clear();
}

}  // namespace vkrt::kernel::checks

#define VKRT_KERNEL_CHECK(condition)                                                   \
    do {                                                                               \
        if (::vkrt::kernel::checks::enabled.load(std::memory_order_relaxed)) [[unlikely]] { \
            if (!(condition)) ::vkrt::kernel::checks::failed(#condition, __FILE__, __LINE__); \
        }                                                                              \
    } while (false)

#pragma once
// The process's peak resident memory so far, as the kernel counts it (VmHWM):
// what `vkrt render` reports and `vkrt bench` compares with other renderers.
#include <cstdint>

namespace vkrt::app {

// 0 where the kernel does not say (no /proc, or not Linux).
std::uint64_t peak_resident_bytes();

}  // namespace vkrt::app

#pragma once
#include <memory>

#include "kernel/kernel.hpp"
#include "render/backend.hpp"

namespace vkrt {

// The C++ reference renderer: the shared kernel run on `threads` CPU threads
// (0 = all hardware threads), in tiles.
std::unique_ptr<Backend> make_cpu_backend(unsigned threads = 0);

// One invocation's view of a flattened scene: what each reference thread runs, and
// what tests call kernel functions through. It borrows the scene's arrays.
kernel::Kernel make_kernel(const FlatScene& scene);

}  // namespace vkrt

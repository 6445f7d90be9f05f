#pragma once
#include <memory>

#include "render/backend.hpp"

namespace vkrt {

// The C++ reference renderer: the shared kernel run on `threads` CPU threads
// (0 = all hardware threads), in tiles.
std::unique_ptr<Backend> make_reference_backend(unsigned threads = 0);

}  // namespace vkrt

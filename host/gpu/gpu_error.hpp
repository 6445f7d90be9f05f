#pragma once
// What the Vulkan backend throws: every failure names the call or the limit.
#include <stdexcept>

namespace vkrt {

class GpuError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace vkrt

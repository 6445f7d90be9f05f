// Force-included into every module that must build without Vulkan (cmake/Modules.cmake):
// only host/gpu/ may include <vulkan/vulkan.h>. Including it anywhere else fails with
// "attempt to use poisoned VkInstance", below the line that included it.
#pragma once
#pragma GCC poison VkInstance

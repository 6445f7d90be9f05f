#pragma once
// How one scene's data reaches the kernel on one device: texel or storage buffers
// for the scene and the pixels, a texel or uniform buffer for the params, and how
// many rows of pixels one pixel buffer holds. The device choices of
// render_bindings.glsl, planned from the device's limits. No Vulkan here.
#include <cstdint>

#include "gpu/device_limits.hpp"
#include "gpu/gpu_error.hpp"
#include "kernel/types.hpp"

namespace vkrt::gpu {

// Buffer: storage or uniform buffers. Address: the scene through its device address
// (pixels in a storage buffer); for the scene only.
enum class PathChoice { Automatic, Texel, Buffer, Address };

// A scene or image too large for every data path of a device.
class SceneDoesNotFit : public GpuError {
public:
    using GpuError::GpuError;
};

struct DataPaths {
    bool scene_in_storage = false;   // SCENE_IN_STORAGE_BUFFERS: scene and pixels
    // The scene read through its buffer's device address (render.comp built with
    // SCENE_BY_ADDRESS), where no one binding can hold it; pixels as above, in
    // storage buffers.
    bool scene_by_address = false;
    bool params_in_uniform = false;  // PARAMS_IN_UNIFORM_BUFFER
    // Rows of the image the pixel buffer holds at once (a slab): all of them when they
    // fit, else a multiple of 8; the image is rendered slab by slab.
    std::uint32_t slab_rows = 0;
    std::uint32_t pixel_texels = 0;  // of one pixel's output (DataSizes)
};

struct DataSizes {
    std::uint64_t scene_texels = 0;  // the packed scene (scene_pack.hpp), rgba32ui texels
    std::uint64_t words_start = 0;   // texel where its r32ui arrays begin
    std::uint64_t word_count = 0;
    std::uint32_t width = 0;         // of the grid of rays the kernel traces
    std::uint32_t height = 0;
    // Texels of one pixel's output: kernel::PIXEL_TEXELS, and PASS_TEXELS more with
    // the render passes (kernel/layout.glsl).
    std::uint32_t pixel_texels = kernel::PIXEL_TEXELS;
};

// The largest scene, in bytes, the device can read by address: one allocation, and
// no more words than a 32-bit index reaches.
std::uint64_t max_addressed_bytes(const DeviceLimits& limits);

// Texel buffers where the scene's and a row of eight pixels' texels fit
// maxTexelBufferElements (docs/decisions/0001-texel-buffers.md: fastest on lavapipe),
// else storage buffers where the scene fits maxStorageBufferRange, else the scene by
// address where the device has bufferDeviceAddress and the scene fits one
// allocation; params from a uniform buffer except on CPU devices. A choice other
// than Automatic forces the path (tests). Throws SceneDoesNotFit naming the limits a
// scene or image exceeds on every path.
DataPaths plan_data_paths(const DeviceLimits& limits, bool cpu_device, const DataSizes& sizes,
                          PathChoice scene = PathChoice::Automatic, PathChoice params = PathChoice::Automatic);

}  // namespace vkrt::gpu

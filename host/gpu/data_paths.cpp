#include "gpu/data_paths.hpp"

#include <algorithm>
#include <string>

#include "gpu/render_interface.hpp"
#include "kernel/types.hpp"

namespace vkrt::gpu {

namespace {

constexpr std::uint64_t kTexelBytes = 16;

// Rows of `width` pixels of `pixel_texels` texels each that `texels` texels hold, as
// a multiple of 8 or the whole image; 0 when not even 8 rows fit.
std::uint32_t rows_fitting(std::uint64_t texels, std::uint32_t pixel_texels, std::uint32_t width,
                           std::uint32_t height) {
    const std::uint64_t rows = texels / (std::uint64_t(pixel_texels) * width);
    if (rows >= height) return height;
    return std::uint32_t(rows / kWorkgroupSide * kWorkgroupSide);
}

bool scene_fits_texels(const DeviceLimits& l, const DataSizes& s) {
    return s.words_start <= l.texel_elements && s.word_count <= l.texel_elements;
}

}  // namespace

std::uint64_t max_addressed_bytes(const DeviceLimits& l) {
    return std::min(l.allocation_bytes, std::uint64_t(4) << 32);
}

DataPaths plan_data_paths(const DeviceLimits& l, bool cpu_device, const DataSizes& s, PathChoice scene,
                          PathChoice params) {
    if (params == PathChoice::Address) {
        throw GpuError("params cannot be read by address; only the scene can");
    }
    const std::uint64_t scene_bytes = s.scene_texels * kTexelBytes;
    const std::uint32_t texel_rows = rows_fitting(l.texel_elements, s.pixel_texels, s.width, s.height);
    const std::uint32_t storage_rows = rows_fitting(l.storage_range / kTexelBytes, s.pixel_texels, s.width, s.height);
    const bool texel_ok = scene_fits_texels(l, s) && texel_rows > 0;
    const bool storage_ok = scene_bytes <= l.storage_range && storage_rows > 0;
    const bool address_ok = l.buffer_device_address && scene_bytes <= max_addressed_bytes(l) && storage_rows > 0;
    if (scene == PathChoice::Automatic) {
        scene = texel_ok ? PathChoice::Texel : storage_ok ? PathChoice::Buffer : PathChoice::Address;
    }
    const bool ok = scene == PathChoice::Texel ? texel_ok : scene == PathChoice::Buffer ? storage_ok : address_ok;
    if (!ok) {
        const std::string size = std::to_string(s.width) + "x" + std::to_string(s.height);
        std::string address = l.buffer_device_address
                                  ? "its maxMemoryAllocationSize " + std::to_string(l.allocation_bytes) + " bytes"
                                  : "it lacks bufferDeviceAddress";
        throw SceneDoesNotFit("this device cannot hold the scene (" + std::to_string(scene_bytes) +
                              " bytes) and a slab of 8 rows of the " + size +
                              " image: its maxTexelBufferElements is " + std::to_string(l.texel_elements) +
                              ", its maxStorageBufferRange " + std::to_string(l.storage_range) + " bytes, and " +
                              address);
    }
    DataPaths paths;
    paths.scene_in_storage = scene != PathChoice::Texel;
    paths.scene_by_address = scene == PathChoice::Address;
    paths.slab_rows = paths.scene_in_storage ? storage_rows : texel_rows;
    paths.pixel_texels = s.pixel_texels;
    paths.params_in_uniform = params == PathChoice::Automatic ? !cpu_device : params == PathChoice::Buffer;
    return paths;
}

}  // namespace vkrt::gpu

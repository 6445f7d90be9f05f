#pragma once
// A VkPipelineCache kept on disk between runs, so that a repeated render does not
// compile its pipeline again on a driver that fills one (docs/porting.md, "Pipeline
// cache"). One file per device model and driver build: the file's name and header
// carry the vendor, device and pipelineCacheUUID, and a file whose header names
// another is not handed to the driver. A cache only saves time: every failure to
// read or write one is a warning at most, never an error.
#include <cstdint>
#include <filesystem>
#include <span>
#include <unordered_map>
#include <vector>

#include <vulkan/vulkan.h>

namespace vkrt::gpu {

// Where cache files live: $VKRT_CACHE_DIR when set (set and empty: no cache), else
// $XDG_CACHE_HOME/vkrt, else $HOME/.cache/vkrt; empty when none can be named.
std::filesystem::path pipeline_cache_dir();

// The file of this device's cache in `dir`.
std::filesystem::path pipeline_cache_file(const std::filesystem::path& dir, const VkPhysicalDeviceProperties& device);

// Whether `data` starts with a pipeline cache header (the specification's "Pipeline
// Cache Header", version one) of this device.
bool cache_header_matches(std::span<const std::uint8_t> data, const VkPhysicalDeviceProperties& device);

class PipelineCache {
public:
    // Reads the cache file of the device in `dir` (empty: no file, an empty cache).
    PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties, std::filesystem::path dir);
    ~PipelineCache();
    PipelineCache(const PipelineCache&) = delete;
    PipelineCache& operator=(const PipelineCache&) = delete;

    VkPipelineCache get() const { return cache_; }
    // Writes the cache file when the driver's data differs from what was read; by a
    // rename, so a concurrent vkrt reads the old file or the new one, whole.
    void save();

private:
    VkDevice device_;
    VkPipelineCache cache_ = VK_NULL_HANDLE;
    std::filesystem::path file_;
    std::vector<std::uint8_t> read_;
};

// The kernel's SPIR-V as specialized for a feature set (gpu/spirv_specialize.hpp),
// kept in the same directory: SPIRV-Tools takes longer over the whole kernel than
// a warm driver takes to compile the result, and the result depends only on the
// module and the constants. Files are `spirv-KEY.bin`: the words, then a 64-bit
// checksum of them; a file that fails it is not used.
std::uint64_t specialization_key(std::span<const std::uint32_t> module,
                                 const std::unordered_map<std::uint32_t, bool>& values);
// Empty when `dir` is empty or holds no good file of that key.
std::vector<std::uint32_t> read_cached_spirv(const std::filesystem::path& dir, std::uint64_t key);
void write_cached_spirv(const std::filesystem::path& dir, std::uint64_t key, std::span<const std::uint32_t> words);

}  // namespace vkrt::gpu

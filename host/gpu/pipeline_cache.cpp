#include "gpu/pipeline_cache.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include "gpu/spirv_specialize.hpp"
#include "render/fingerprint.hpp"

namespace vkrt::gpu {
namespace {

constexpr std::size_t kHeaderBytes = 16 + VK_UUID_SIZE;

std::uint32_t word_at(std::span<const std::uint8_t> data, std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, data.data() + at, sizeof v);  // the header is in the host's byte order
    return v;
}

void warn(const std::string& what) { std::fprintf(stderr, "warning: pipeline cache: %s\n", what.c_str()); }

// Writes `bytes` to `file` through a temporary beside it and a rename, so that a
// vkrt running at the same time reads the old file or the new one, whole. False
// (after a warning) when that fails.
bool write_whole(const std::filesystem::path& file, std::span<const std::uint8_t> bytes) {
    std::error_code error;
    std::filesystem::create_directories(file.parent_path(), error);
    const std::filesystem::path temporary = file.string() + ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream out(temporary, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        if (!out) {
            warn("cannot write " + temporary.string() + " (set VKRT_CACHE_DIR to another directory, or empty to keep "
                 "no cache)");
            std::filesystem::remove(temporary, error);
            return false;
        }
    }
    std::filesystem::rename(temporary, file, error);
    if (error) {
        warn("cannot replace " + file.string() + ": " + error.message());
        std::filesystem::remove(temporary, error);
        return false;
    }
    return true;
}

std::vector<std::uint8_t> read_whole(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::filesystem::path spirv_file(const std::filesystem::path& dir, std::uint64_t key) {
    char name[40];
    std::snprintf(name, sizeof name, "spirv-%016llx.bin", static_cast<unsigned long long>(key));
    return dir / name;
}

std::uint64_t words_checksum(std::span<const std::uint32_t> words) {
    Fnv1a hash;
    hash.add(words.data(), words.size_bytes());
    return hash.value();
}

}  // namespace

std::filesystem::path pipeline_cache_dir() {
    if (const char* dir = std::getenv("VKRT_CACHE_DIR")) return dir;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "vkrt";
    if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "vkrt";
    return {};
}

std::filesystem::path pipeline_cache_file(const std::filesystem::path& dir, const VkPhysicalDeviceProperties& device) {
    char name[96];
    int at = std::snprintf(name, sizeof name, "pipelines-%04x-%04x-", device.vendorID, device.deviceID);
    for (std::uint8_t b : device.pipelineCacheUUID) at += std::snprintf(name + at, sizeof name - at, "%02x", b);
    std::snprintf(name + at, sizeof name - at, ".bin");
    return dir / name;
}

bool cache_header_matches(std::span<const std::uint8_t> data, const VkPhysicalDeviceProperties& device) {
    return data.size() >= kHeaderBytes && word_at(data, 0) >= kHeaderBytes && word_at(data, 0) <= data.size() &&
           word_at(data, 4) == VK_PIPELINE_CACHE_HEADER_VERSION_ONE && word_at(data, 8) == device.vendorID &&
           word_at(data, 12) == device.deviceID &&
           std::memcmp(data.data() + 16, device.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

PipelineCache::PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties, std::filesystem::path dir)
    : device_(device) {
    if (!dir.empty()) {
        file_ = pipeline_cache_file(dir, properties);
        read_ = read_whole(file_);
        // Another driver's or a damaged file is left out; the next save replaces it.
        if (!cache_header_matches(read_, properties)) read_.clear();
    }
    VkPipelineCacheCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO;
    info.initialDataSize = read_.size();
    info.pInitialData = read_.empty() ? nullptr : read_.data();
    if (vkCreatePipelineCache(device_, &info, nullptr, &cache_) != VK_SUCCESS) {
        // The driver refused the data after all: start empty rather than fail.
        read_.clear();
        info.initialDataSize = 0;
        info.pInitialData = nullptr;
        if (vkCreatePipelineCache(device_, &info, nullptr, &cache_) != VK_SUCCESS) cache_ = VK_NULL_HANDLE;
    }
}

PipelineCache::~PipelineCache() {
    if (cache_ != VK_NULL_HANDLE) vkDestroyPipelineCache(device_, cache_, nullptr);
}

void PipelineCache::save() {
    if (cache_ == VK_NULL_HANDLE || file_.empty()) return;
    std::size_t size = 0;
    if (vkGetPipelineCacheData(device_, cache_, &size, nullptr) != VK_SUCCESS) return;
    std::vector<std::uint8_t> data(size);
    if (vkGetPipelineCacheData(device_, cache_, &size, data.data()) != VK_SUCCESS) return;
    data.resize(size);
    if (data == read_) return;
    if (write_whole(file_, data)) read_ = std::move(data);
}

std::uint64_t specialization_key(std::span<const std::uint32_t> module,
                                 const std::unordered_map<std::uint32_t, bool>& values) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted;
    for (const auto& [id, on] : values) sorted.emplace_back(id, on ? 1u : 0u);
    std::sort(sorted.begin(), sorted.end());
    Fnv1a hash;
    hash.add(&kSpecializationRecipe, sizeof kSpecializationRecipe);
    hash.add(module.data(), module.size_bytes());
    hash.add(sorted);
    return hash.value();
}

std::vector<std::uint32_t> read_cached_spirv(const std::filesystem::path& dir, std::uint64_t key) {
    if (dir.empty()) return {};
    const std::vector<std::uint8_t> bytes = read_whole(spirv_file(dir, key));
    constexpr std::uint32_t kSpirvMagic = 0x07230203;
    constexpr std::size_t kMinWords = 5;  // the module header
    if (bytes.size() % 4 != 0 || bytes.size() < (kMinWords + 2) * 4) return {};
    std::vector<std::uint32_t> words(bytes.size() / 4 - 2);
    std::memcpy(words.data(), bytes.data(), words.size() * 4);
    std::uint64_t stored;
    std::memcpy(&stored, bytes.data() + words.size() * 4, sizeof stored);
    if (words[0] != kSpirvMagic || stored != words_checksum(words)) return {};
    return words;
}

void write_cached_spirv(const std::filesystem::path& dir, std::uint64_t key, std::span<const std::uint32_t> words) {
    if (dir.empty()) return;
    const auto* first = reinterpret_cast<const std::uint8_t*>(words.data());
    std::vector<std::uint8_t> bytes(first, first + words.size_bytes());
    const std::uint64_t checksum = words_checksum(words);
    const auto* sum = reinterpret_cast<const std::uint8_t*>(&checksum);
    bytes.insert(bytes.end(), sum, sum + sizeof checksum);
    write_whole(spirv_file(dir, key), bytes);
}

}  // namespace vkrt::gpu

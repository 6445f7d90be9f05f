// The pipeline cache kept between runs: whose data it hands to the driver, where it
// lives, and that renders through it (a first, a repeated, one over a damaged file)
// give the same image.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>

#include "gpu/pipeline_cache.hpp"
#include "image/compare.hpp"
#include "image/image.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;
namespace fs = std::filesystem;

VkPhysicalDeviceProperties device() {
    VkPhysicalDeviceProperties p{};
    p.vendorID = 0x10005;
    p.deviceID = 0x1234;
    for (std::uint8_t i = 0; i < VK_UUID_SIZE; ++i) p.pipelineCacheUUID[i] = std::uint8_t(i * 7 + 1);
    return p;
}

std::vector<std::uint8_t> header(const VkPhysicalDeviceProperties& p, std::uint32_t length = 32) {
    std::vector<std::uint8_t> h(48, 0xab);  // 16 bytes of driver data after the header
    const std::uint32_t words[4] = {length, VK_PIPELINE_CACHE_HEADER_VERSION_ONE, p.vendorID, p.deviceID};
    std::memcpy(h.data(), words, sizeof words);
    std::memcpy(h.data() + 16, p.pipelineCacheUUID, VK_UUID_SIZE);
    return h;
}

TEST(PipelineCache, HandsTheDriverOnlyItsOwnData) {
    const VkPhysicalDeviceProperties p = device();
    EXPECT_TRUE(gpu::cache_header_matches(header(p), p));
    VkPhysicalDeviceProperties other = p;
    other.pipelineCacheUUID[15] ^= 1;  // another driver build
    EXPECT_FALSE(gpu::cache_header_matches(header(p), other));
    other = p;
    other.deviceID += 1;
    EXPECT_FALSE(gpu::cache_header_matches(header(p), other));
    std::vector<std::uint8_t> h = header(p);
    EXPECT_FALSE(gpu::cache_header_matches(std::span(h).first(31), p));  // cut inside the header
    EXPECT_FALSE(gpu::cache_header_matches(header(p, 31), p));           // a length shorter than a header
    EXPECT_FALSE(gpu::cache_header_matches(header(p, 49), p));           // longer than the data
    h[4] = 2;                                                            // an unknown header version
    EXPECT_FALSE(gpu::cache_header_matches(h, p));
    EXPECT_FALSE(gpu::cache_header_matches({}, p));
}

TEST(PipelineCache, FileNamesTheDeviceAndDriverBuild) {
    const fs::path file = gpu::pipeline_cache_file("/c", device());
    EXPECT_EQ(file, "/c/pipelines-10005-1234-01080f161d242b323940474e555c636a.bin");
}

struct ScopedEnv {
    std::string name;
    std::optional<std::string> old;
    ScopedEnv(std::string n, const char* value) : name(std::move(n)) {
        if (const char* v = std::getenv(name.c_str())) old = v;
        if (value) {
            setenv(name.c_str(), value, 1);
        } else {
            unsetenv(name.c_str());
        }
    }
    ~ScopedEnv() {
        if (old) {
            setenv(name.c_str(), old->c_str(), 1);
        } else {
            unsetenv(name.c_str());
        }
    }
};

TEST(PipelineCache, LivesWhereTheEnvironmentSays) {
    {
        ScopedEnv dir("VKRT_CACHE_DIR", "/tmp/own"), xdg("XDG_CACHE_HOME", "/x");
        EXPECT_EQ(gpu::pipeline_cache_dir(), "/tmp/own");
    }
    {
        ScopedEnv dir("VKRT_CACHE_DIR", ""), xdg("XDG_CACHE_HOME", "/x");
        EXPECT_EQ(gpu::pipeline_cache_dir(), "");  // set and empty: no cache
    }
    {
        ScopedEnv dir("VKRT_CACHE_DIR", nullptr), xdg("XDG_CACHE_HOME", "/x");
        EXPECT_EQ(gpu::pipeline_cache_dir(), "/x/vkrt");
    }
    {
        ScopedEnv dir("VKRT_CACHE_DIR", nullptr), xdg("XDG_CACHE_HOME", nullptr), home("HOME", "/home/u");
        EXPECT_EQ(gpu::pipeline_cache_dir(), "/home/u/.cache/vkrt");
    }
}

TEST(SpirvCache, GivesBackOnlyWhatItStoredWhole) {
    const fs::path dir = test::temp_dir("spirv_cache");
    const std::vector<std::uint32_t> words{0x07230203u, 0x10000u, 0u, 42u, 0u, 7u, 8u, 9u};
    const std::unordered_map<std::uint32_t, bool> on{{0, true}, {3, false}}, off{{0, false}, {3, false}};
    const std::uint64_t key = gpu::specialization_key(words, on);
    EXPECT_NE(key, gpu::specialization_key(words, off));  // another feature set, another file
    EXPECT_TRUE(gpu::read_cached_spirv(dir, key).empty());
    gpu::write_cached_spirv(dir, key, words);
    EXPECT_EQ(gpu::read_cached_spirv(dir, key), words);
    EXPECT_TRUE(gpu::read_cached_spirv("", key).empty());  // no directory: no cache

    const fs::path file = dir / fmt::format("spirv-{:016x}.bin", key);
    ASSERT_TRUE(fs::exists(file));
    std::fstream damage(file, std::ios::in | std::ios::out | std::ios::binary);
    damage.seekp(12);
    damage.put('\x7f');  // one byte of the module changed: the checksum fails
    damage.close();
    EXPECT_TRUE(gpu::read_cached_spirv(dir, key).empty());
    fs::resize_file(file, 10);  // cut short
    EXPECT_TRUE(gpu::read_cached_spirv(dir, key).empty());
}

fs::path only_file(const fs::path& dir, const std::string& prefix) {
    std::vector<fs::path> found;
    if (fs::exists(dir)) {
        for (const auto& entry : fs::directory_iterator(dir)) {
            if (entry.path().filename().string().rfind(prefix, 0) == 0) found.push_back(entry.path());
        }
    }
    EXPECT_EQ(found.size(), 1u) << prefix << " files in " << dir;
    return found.empty() ? fs::path() : found.front();
}

std::size_t bytes_of(const fs::path& file) { return fs::exists(file) ? std::size_t(fs::file_size(file)) : 0; }

// Through the real program: the first render writes the device's pipeline cache and
// the specialized kernel, a repeated one reads them, and one over damaged files
// replaces them; the images are equal.
TEST(PipelineCache, RendersThroughItGiveTheSameImage) {
    const fs::path dir = test::temp_dir("pipeline_cache");
    const fs::path cache = dir / "cache";
    const ScopedEnv env("VKRT_CACHE_DIR", cache.c_str());
    const std::string scene = test::shell_quote((test::source_dir() / "scenes" / "area_light.json").string());
    auto render = [&](const std::string& name) {
        const fs::path out = dir / (name + ".exr");
        const test::ProgramRun run = test::run_vkrt(
            fmt::format("render {} --width 40 --height 30 -q -o {}", scene, test::shell_quote(out.string())), dir);
        EXPECT_EQ(run.code, 0);
        EXPECT_EQ(run.stderr_text, "") << "a cache problem is at most a warning, and here there is none";
        return read_image(out);
    };
    const Image first = render("first");
    const fs::path pipelines = only_file(cache, "pipelines-");
    const fs::path spirv = only_file(cache, "spirv-");
    EXPECT_GE(bytes_of(pipelines), 32u);
    const std::size_t spirv_bytes = bytes_of(spirv);
    EXPECT_GT(spirv_bytes, 1000u);
    const Image again = render("again");
    for (const fs::path& file : {pipelines, spirv}) {
        std::ofstream(file, std::ios::binary | std::ios::trunc) << "not a cache at all, damaged on disk";
    }
    const Image over_damage = render("over_damage");
    EXPECT_GE(bytes_of(pipelines), 32u) << "the damaged pipeline cache is replaced by the driver's data";
    EXPECT_EQ(bytes_of(spirv), spirv_bytes) << "the damaged SPIR-V is specialized again and replaced";
    EXPECT_EQ(compare_images(first, again).max_abs, 0.0);
    EXPECT_EQ(compare_images(first, over_damage).max_abs, 0.0);
}

}  // namespace

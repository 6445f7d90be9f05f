#include "render/partial_file.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "image/image.hpp"
#include "image/image_files.hpp"
#include "render/fingerprint.hpp"
#include "render/pixel_sums.hpp"
#include "render/sample_ranges.hpp"
#include "scene/limits.hpp"
#include "vkrt_version.h"

namespace vkrt {
namespace {

// Bumped when the channels or attributes change meaning; a reader refuses others.
// 2: vkrt:version and vkrt:checksum. 3: the sums of squares (vkrt.sq.*).
constexpr int kFormatVersion = 3;

// The words of a PixelSum and of Counters, in the order of their layout.
constexpr std::array<const char*, 24> kSumChannels = {
    "vkrt.sum.r0", "vkrt.sum.r1", "vkrt.sum.r2", "vkrt.sum.count",    // red words, samples summed
    "vkrt.sum.g0", "vkrt.sum.g1", "vkrt.sum.g2", "vkrt.sum.clamped",  // green words, samples clamped
    "vkrt.sum.b0", "vkrt.sum.b1", "vkrt.sum.b2", "vkrt.sum.unused",
    "vkrt.sq.r0",  "vkrt.sq.r1",  "vkrt.sq.r2",  "vkrt.sq.unused.r",  // the squares' sums
    "vkrt.sq.g0",  "vkrt.sq.g1",  "vkrt.sq.g2",  "vkrt.sq.unused.g",
    "vkrt.sq.b0",  "vkrt.sq.b1",  "vkrt.sq.b2",  "vkrt.sq.unused.b"};
constexpr std::array<const char*, 16> kCounterChannels = {
    "vkrt.rays.0", "vkrt.rays.1", "vkrt.rays.2", "vkrt.rays.3", "vkrt.work.0",  "vkrt.work.1",
    "vkrt.work.2", "vkrt.work.3", "vkrt.tree.0", "vkrt.tree.1", "vkrt.tree.2",  "vkrt.tree.3",
    "vkrt.paths.0", "vkrt.paths.1", "vkrt.paths.2", "vkrt.paths.3"};
constexpr int kChannels = 3 + int(kSumChannels.size()) + int(kCounterChannels.size());

std::uint32_t& sum_word(kernel::PixelSum& s, std::size_t i) {
    glm::uvec4* lanes[] = {&s.red, &s.green, &s.blue, &s.red_squares, &s.green_squares, &s.blue_squares};
    return (*lanes[i / 4])[glm::length_t(i % 4)];
}
std::uint32_t& counter_word(kernel::Counters& c, std::size_t i) {
    glm::uvec4& v = i < 4 ? c.rays : i < 8 ? c.work : i < 12 ? c.tree : c.paths;
    return v[glm::length_t(i % 4)];
}

// The file's vkrt:checksum: FNV-1a steps over the 64-bit words of each pixel's sums
// and then its counters, pixel by pixel, so that a reader can check it block by block.
void add_to_checksum(Fnv1a& hash, const kernel::PixelSum& sum, const kernel::Counters& counters) {
    static_assert(sizeof(kernel::PixelSum) % 8 == 0 && sizeof(kernel::Counters) % 8 == 0);
    hash.add_words(&sum, sizeof sum);
    hash.add_words(&counters, sizeof counters);
}

std::uint64_t checksum(const RenderResult& r) {
    Fnv1a hash;
    for (std::size_t p = 0; p < r.sums.size(); ++p) add_to_checksum(hash, r.sums[p], r.counters[p]);
    return hash.value();
}

[[noreturn]] void not_partial(const std::string& name, const std::string& why) {
    throw ImageError(fmt::format("{}: not a vkrt partial file ({}); partial files come from "
                                 "`vkrt render --samples A:B` or `vkrt merge -o NAME.exr`",
                                 name, why));
}

}  // namespace

std::string build_version() { return VKRT_VERSION " kernel " VKRT_KERNEL_HASH; }

void write_partial(const PartialFile& partial, const std::filesystem::path& file) {
    const std::string name = file.string();
    const RenderResult& r = partial.sums;
    FileSpec spec;
    spec.width = r.width;
    spec.height = r.height;
    spec.channels = {"R", "G", "B"};
    spec.types.assign(3, ChannelType::Float);
    for (const char* c : kSumChannels) spec.channels.emplace_back(c);
    for (const char* c : kCounterChannels) spec.channels.emplace_back(c);
    spec.types.resize(kChannels, ChannelType::UInt32);
    spec.strings["oiio:ColorSpace"] = "Linear";
    spec.ints["vkrt:partial_version"] = kFormatVersion;
    spec.strings["vkrt:samples"] = format_sample_ranges(partial.samples);
    spec.strings["vkrt:scene"] = partial.scene;
    spec.strings["vkrt:seed"] = std::to_string(partial.seed);  // a string: EXR has no unsigned attribute
    spec.strings["vkrt:fingerprint"] = format_fingerprint(partial.fingerprint);
    spec.strings["vkrt:backend"] = partial.backend;
    spec.ints["vkrt:corners"] = partial.corners ? 1 : 0;
    spec.strings["vkrt:version"] = partial.version;
    spec.strings["vkrt:checksum"] = format_fingerprint(checksum(r));

    // Every channel is 4 bytes: one uint32 array holds the pixels in the native
    // per-channel formats, the floats by their bits.
    std::vector<std::uint32_t> pixels(r.sums.size() * kChannels);
    for (std::size_t p = 0; p < r.sums.size(); ++p) {
        std::uint32_t* px = &pixels[p * kChannels];
        const glm::vec3 mean = mean_radiance(r.sums[p]);
        for (int c = 0; c < 3; ++c) px[c] = std::bit_cast<std::uint32_t>(mean[c]);
        kernel::PixelSum s = r.sums[p];
        for (std::size_t i = 0; i < kSumChannels.size(); ++i) px[3 + i] = sum_word(s, i);
        kernel::Counters k = r.counters[p];
        for (std::size_t i = 0; i < kCounterChannels.size(); ++i) px[3 + kSumChannels.size() + i] = counter_word(k, i);
    }
    std::string error;
    if (!image_files().write(name, spec, pixels.data(), error)) throw ImageError(fmt::format("{}: {}", name, error));
}

namespace {

// Opens a partial file and reads its header; the pixels are left to the caller.
PartialFile read_header(const std::string& name, ImageFileReader& in) {
    const FileSpec& spec = in.spec();
    PartialFile partial;
    const int version = spec.int_or("vkrt:partial_version", 0);
    if (version == 0) not_partial(name, "it has no vkrt:partial_version attribute");
    if (version != kFormatVersion) {
        throw ImageError(fmt::format("{}: a vkrt partial file of format version {}, but this vkrt reads version {}",
                                     name, version, kFormatVersion));
    }
    const std::string samples = spec.string_or("vkrt:samples");
    const auto ranges = parse_sample_ranges(samples, limits::kMaxSpp);
    if (!ranges) not_partial(name, fmt::format("its vkrt:samples attribute '{}' is no list of ranges A:B", samples));
    partial.samples = normalize_sample_ranges(*ranges);
    partial.scene = spec.string_or("vkrt:scene");
    const std::string seed = spec.string_or("vkrt:seed");
    const std::string fingerprint = spec.string_or("vkrt:fingerprint");
    try {
        std::size_t used = 0;
        const unsigned long long value = std::stoull(seed, &used);
        if (used != seed.size() || value > 0xffffffffull) throw std::invalid_argument("seed");
        partial.seed = std::uint32_t(value);
        partial.fingerprint = std::stoull(fingerprint, &used, 16);
        if (used != fingerprint.size()) throw std::invalid_argument("fingerprint");
    } catch (const std::logic_error&) {  // invalid_argument and out_of_range alike
        not_partial(name, fmt::format("its vkrt:seed '{}' or vkrt:fingerprint '{}' is no number", seed, fingerprint));
    }
    partial.backend = spec.string_or("vkrt:backend");
    partial.corners = spec.int_or("vkrt:corners", 0) != 0;
    partial.version = spec.string_or("vkrt:version");
    partial.sums.width = spec.width;
    partial.sums.height = spec.height;
    return partial;
}

std::unique_ptr<ImageFileReader> open_partial(const std::string& name) {
    if (!std::filesystem::exists(name)) throw ImageError(fmt::format("{}: no such file", name));
    std::string error;
    auto in = image_files().open(name, error);
    if (!in) throw ImageError(fmt::format("{}: cannot read image ({})", name, error));
    return in;
}

}  // namespace

PartialFile read_partial_header(const std::filesystem::path& file) {
    const std::string name = file.string();
    return read_header(name, *open_partial(name));
}

namespace {

// Rows read at once: the pixels of a 4K partial are 1 GB in the file's layout; a
// block of rows keeps memory to the sums and a few megabytes.
constexpr std::uint32_t kRowsPerRead = 64;

// Reads the pixels of the open partial `in` a block of rows at a time and hands each
// pixel's sums and counters to use(p, sum, counters), in order; then verifies the
// checksum. Throws ImageError naming the file for a truncated or damaged one.
template <class Use>
void read_pixels(const std::string& name, ImageFileReader& in, const PartialFile& header, Use use) {
    const FileSpec& spec = in.spec();
    // Channels by name, wherever the file put them (OpenEXR stores them sorted by
    // name), at their byte offsets in a pixel of native per-channel formats.
    std::vector<std::size_t> offset(spec.channels.size());
    std::size_t pixel_bytes = 0;
    for (std::size_t c = 0; c < spec.channels.size(); ++c) {
        offset[c] = pixel_bytes;
        pixel_bytes += channel_bytes(spec.types[c]);
    }
    auto find = [&](const char* channel) {
        for (std::size_t c = 0; c < spec.channels.size(); ++c) {
            if (spec.channels[c] == channel) {
                if (spec.types[c] != ChannelType::UInt32) {
                    not_partial(name, fmt::format("channel {} is not 32-bit unsigned", channel));
                }
                return offset[c];
            }
        }
        not_partial(name, fmt::format("it has no channel {}", channel));
    };
    std::array<std::size_t, kSumChannels.size()> sum_at{};
    for (std::size_t i = 0; i < kSumChannels.size(); ++i) sum_at[i] = find(kSumChannels[i]);
    std::array<std::size_t, kCounterChannels.size()> counter_at{};
    for (std::size_t i = 0; i < kCounterChannels.size(); ++i) counter_at[i] = find(kCounterChannels[i]);

    const std::size_t width = std::size_t(spec.width);
    std::vector<unsigned char> data(std::size_t(kRowsPerRead) * width * pixel_bytes);
    Fnv1a hash;
    for (std::uint32_t y = 0; y < spec.height; y += kRowsPerRead) {
        const std::uint32_t rows = std::min(kRowsPerRead, spec.height - y);
        if (!in.read_rows(y, y + rows, data.data())) {
            throw ImageError(fmt::format("{}: cannot read its pixels, the file is truncated or damaged ({}); "
                                         "render its samples ({}) again",
                                         name, in.error(), format_sample_ranges(header.samples)));
        }
        for (std::size_t i = 0; i < std::size_t(rows) * width; ++i) {
            const unsigned char* pixel = &data[i * pixel_bytes];
            kernel::PixelSum sum{};
            kernel::Counters counters{};
            for (std::size_t k = 0; k < sum_at.size(); ++k) std::memcpy(&sum_word(sum, k), pixel + sum_at[k], 4);
            for (std::size_t k = 0; k < counter_at.size(); ++k) {
                std::memcpy(&counter_word(counters, k), pixel + counter_at[k], 4);
            }
            add_to_checksum(hash, sum, counters);
            use(std::size_t(y) * width + i, sum, counters);
        }
    }
    if (spec.string_or("vkrt:checksum") != format_fingerprint(hash.value())) {
        throw ImageError(fmt::format("{}: its pixels do not match its checksum, the file is damaged; render its "
                                     "samples ({}) again",
                                     name, format_sample_ranges(header.samples)));
    }
}

}  // namespace

PartialFile read_partial(const std::filesystem::path& file) {
    const std::string name = file.string();
    const std::unique_ptr<ImageFileReader> in = open_partial(name);
    PartialFile partial = read_header(name, *in);
    RenderResult& r = partial.sums;
    r.sums.resize(std::size_t(r.width) * r.height);
    r.counters.resize(r.sums.size());
    read_pixels(name, *in, partial, [&r](std::size_t p, const kernel::PixelSum& sum, const kernel::Counters& counters) {
        r.sums[p] = sum;
        r.counters[p] = counters;
    });
    return partial;
}

PartialFile check_partial(const std::filesystem::path& file) {
    const std::string name = file.string();
    const std::unique_ptr<ImageFileReader> in = open_partial(name);
    const PartialFile partial = read_header(name, *in);
    read_pixels(name, *in, partial, [](std::size_t, const kernel::PixelSum&, const kernel::Counters&) {});
    return partial;
}

PartialFile add_partial(const std::filesystem::path& file, RenderResult& total) {
    const std::string name = file.string();
    const std::unique_ptr<ImageFileReader> in = open_partial(name);
    PartialFile partial = read_header(name, *in);
    const RenderResult& size = partial.sums;
    if (total.sums.empty()) {
        total.width = size.width;
        total.height = size.height;
        total.sums.assign(std::size_t(size.width) * size.height, kernel::PixelSum{});
        total.counters.assign(total.sums.size(), kernel::Counters{});
    }
    if (total.width != size.width || total.height != size.height) {
        throw ImageError(fmt::format("{} is {}x{}, not {}x{} as the partials added before it", name, size.width,
                                     size.height, total.width, total.height));
    }
    read_pixels(name, *in, partial,
                [&total](std::size_t p, const kernel::PixelSum& sum, const kernel::Counters& counters) {
                    total.sums[p] = kernel::add_sums(total.sums[p], sum);
                    total.counters[p] = total.counters[p] + counters;
                });
    return partial;
}

}  // namespace vkrt

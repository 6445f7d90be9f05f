#include "scene/texture_image.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include <fmt/format.h>
#include <glm/packing.hpp>

#include "image/image.hpp"
#include "image/image_readers.hpp"
#include "scene/scene.hpp"
#include "scene/scene_error.hpp"

namespace vkrt {

double srgb_to_linear(double encoded) {
    // IEC 61966-2-1: linear below the knee, a 2.4 power above it.
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

const std::array<float, 256>& srgb_byte_table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (std::size_t b = 0; b < t.size(); ++b) t[b] = float(srgb_to_linear(double(b) / 255.0));
        return t;
    }();
    return table;
}

glm::vec4 texel_value(const TextureImage& texture, std::span<const std::uint32_t> texels, std::size_t i) {
    if (texture.format == TexelFormat::Half) {
        const std::size_t w = texture.first_word + 2 * i;
        return glm::vec4(glm::unpackHalf2x16(texels[w]), glm::unpackHalf2x16(texels[w + 1]));
    }
    const std::uint32_t word = texels[texture.first_word + i];
    const auto byte = [&](int k) { return (word >> (8 * k)) & 255u; };
    return glm::vec4(colour_byte_value(texture, byte(0)), colour_byte_value(texture, byte(1)),
                     colour_byte_value(texture, byte(2)), float(byte(3)) * (1.0f / 255.0f));
}

float colour_byte_value(const TextureImage& texture, std::uint32_t byte) {
    // As the kernel: a float times the float nearest 1/255, one rounding.
    return texture.srgb ? srgb_byte_table()[byte] : float(byte) * (1.0f / 255.0f);
}

// TexelStore ----------------------------------------------------------------------

TexelWords& TexelStore::own() {
    if (!words_) {
        words_ = std::make_shared<TexelWords>();
    } else if (words_.use_count() > 1) {
        words_ = std::make_shared<TexelWords>(*words_);
    }
    return *words_;
}

std::uint64_t TexelStore::append(TexelWords&& words) {
    const std::uint64_t first = size();
    if (first == 0) {
        words_ = std::make_shared<TexelWords>(std::move(words));
    } else {
        TexelWords& w = own();
        w.insert(w.end(), words.begin(), words.end());
    }
    return first;
}

std::uint64_t TexelStore::grow(std::size_t count) {
    TexelWords& w = own();
    const std::uint64_t first = w.size();
    w.resize(w.size() + count);
    return first;
}

std::span<std::uint32_t> TexelStore::mutable_words(std::uint64_t first, std::size_t count) {
    return std::span<std::uint32_t>(own()).subspan(first, count);
}

std::span<const std::uint32_t> TexelStore::words() const {
    return words_ ? std::span<const std::uint32_t>(*words_) : std::span<const std::uint32_t>();
}

// Decoding ------------------------------------------------------------------------

namespace {

// All of a scene's texels: 512 MiB, what 2^26 half-float texels took.
constexpr std::uint64_t kMaxTextureWords = kMaxTextureTexels * 2;

[[noreturn]] void fail(const std::string& name, const std::string& element, const std::string& what) {
    throw SceneError(name == element ? fmt::format("{}: {}", element, what)
                                     : fmt::format("{}: texture {}: {}", element, name, what));
}

// What an opened image becomes: its size, format and words; checked before any
// texel is decoded.
struct Plan {
    DecodedImage image;  // words not yet allocated
    std::size_t words = 0;
};

Plan plan(const ImageFileReader& in, Encoding encoding, const std::string& name, const std::string& element) {
    const FileSpec& spec = in.spec();
    if (spec.width == 0 || spec.height == 0 || spec.channels.empty()) fail(name, element, "the image is empty");
    if (spec.width > kMaxTextureSide || spec.height > kMaxTextureSide) {
        fail(name, element, fmt::format("{} x {} texels is larger than the {} x {} vkrt takes", spec.width,
                                        spec.height, kMaxTextureSide, kMaxTextureSide));
    }
    Plan p;
    p.image.width = spec.width;
    p.image.height = spec.height;
    const bool bytes = std::all_of(spec.types.begin(), spec.types.end(), [](ChannelType t) { return t == ChannelType::UInt8; });
    p.image.format = bytes ? TexelFormat::Rgba8 : TexelFormat::Half;
    p.image.srgb = bytes && encoding == Encoding::SrgbUnlessFloat;
    p.words = std::size_t(spec.width) * spec.height * (bytes ? 1 : 2);
    return p;
}

// Every texel as linear floats, grey and grey-alpha spread to RGBA; 8- and 16-bit
// values sRGB-decoded when `encoding` says so.
std::vector<glm::vec4> read_linear(ImageFileReader& in, Encoding encoding, const std::string& name,
                                   const std::string& element) {
    const FileSpec& spec = in.spec();
    const std::size_t channels = spec.channels.size();
    std::vector<float> values(std::size_t(spec.width) * spec.height * channels);
    if (!in.read_floats(values.data())) fail(name, element, fmt::format("cannot read its pixels: {}", one_line(in.error())));
    const bool floats = spec.types.front() == ChannelType::Float || spec.types.front() == ChannelType::Half;
    const bool decode = encoding == Encoding::SrgbUnlessFloat && !floats;
    std::vector<glm::vec4> texels(std::size_t(spec.width) * spec.height);
    for (std::size_t i = 0; i < texels.size(); ++i) {
        const float* v = &values[i * channels];
        for (std::size_t c = 0; c < channels; ++c) {
            if (!std::isfinite(v[c])) fail(name, element, "a texel is not a finite number");
        }
        // Grey, grey and alpha, RGB or RGBA; channels past the fourth are ignored.
        const float r = v[0];
        const float g = channels >= 3 ? v[1] : r;
        const float b = channels >= 3 ? v[2] : r;
        const float a = channels == 2 ? v[1] : channels >= 4 ? v[3] : 1.0f;
        const auto linear = [&](float c) { return decode ? float(srgb_to_linear(std::clamp(c, 0.0f, 1.0f))) : c; };
        texels[i] = glm::vec4(linear(r), linear(g), linear(b), a);
    }
    return texels;
}

// Decodes the planned image into `out` (p.words words).
void decode(ImageFileReader& in, Encoding encoding, const Plan& p, std::span<std::uint32_t> out,
            const std::string& name, const std::string& element) {
    if (p.image.format == TexelFormat::Rgba8) {
        if (!in.read_rgba8(out.data())) fail(name, element, fmt::format("cannot read its pixels: {}", one_line(in.error())));
        return;
    }
    const std::vector<glm::vec4> texels = read_linear(in, encoding, name, element);
    for (std::size_t i = 0; i < texels.size(); ++i) {
        const glm::vec4& c = texels[i];
        out[2 * i] = glm::packHalf2x16(glm::vec2(c.r, c.g));
        out[2 * i + 1] = glm::packHalf2x16(glm::vec2(c.b, c.a));
    }
}

std::unique_ptr<ImageFileReader> open_file(const std::filesystem::path& file, const std::string& element) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) fail(file.string(), element, "no such file");
    std::string error;
    std::unique_ptr<ImageFileReader> in;
    try {
        in = open_image_file(file.string(), error);
    } catch (const ImageError& e) {
        fail(file.string(), element, one_line(e.what()));
    }
    if (!in) fail(file.string(), element, fmt::format("cannot read it as an image: {}", one_line(error)));
    return in;
}

std::unique_ptr<ImageFileReader> open_memory(const EncodedImage& image) {
    std::string error;
    std::unique_ptr<ImageFileReader> in;
    try {
        in = open_image_memory(image.data, image.size, image.format, error);
    } catch (const ImageError& e) {
        throw SceneError(fmt::format("{}: {}", image.element, one_line(e.what())));
    }
    if (!in) throw SceneError(fmt::format("{}: cannot read the image it holds: {}", image.element, one_line(error)));
    return in;
}

DecodedImage decode_whole(ImageFileReader& in, Encoding encoding, const std::string& name, const std::string& element) {
    Plan p = plan(in, encoding, name, element);
    p.image.words.resize(p.words);
    decode(in, encoding, p, p.image.words, name, element);
    return std::move(p.image);
}

void check_total(const Scene& scene, std::size_t more, const std::string& name, const std::string& element) {
    const std::uint64_t words = scene.texels.size() + more;
    if (words > kMaxTextureWords) {
        fail(name, element, fmt::format("the scene's textures would take {} MiB, more than the {} MiB vkrt takes",
                                        words * 4 >> 20, kMaxTextureWords * 4 >> 20));
    }
}

}  // namespace

DecodedImage load_texture_file(const std::filesystem::path& file, Encoding encoding, const std::string& element) {
    std::unique_ptr<ImageFileReader> in = open_file(file, element);
    return decode_whole(*in, encoding, file.string(), element);
}

DecodedImage load_texture_memory(const unsigned char* data, std::size_t size, const std::string& format,
                                 Encoding encoding, const std::string& element) {
    std::unique_ptr<ImageFileReader> in = open_memory({data, size, format, encoding, element});
    return decode_whole(*in, encoding, element, element);
}

LinearImage load_linear_image(const std::filesystem::path& file, Encoding encoding, const std::string& element) {
    std::unique_ptr<ImageFileReader> in = open_file(file, element);
    const Plan p = plan(*in, encoding, file.string(), element);
    LinearImage out;
    out.name = file.string();
    out.width = p.image.width;
    out.height = p.image.height;
    out.texels = read_linear(*in, encoding, out.name, element);
    return out;
}

std::vector<TextureImage> decode_textures(const std::vector<EncodedImage>& images, Scene& scene) {
    // Headers first, in order, so that a bad image is named before any decoding and
    // the texels' room is made once.
    std::vector<std::unique_ptr<ImageFileReader>> readers;
    std::vector<Plan> plans;
    std::size_t words = 0;
    for (const EncodedImage& image : images) {
        readers.push_back(open_memory(image));
        plans.push_back(plan(*readers.back(), image.encoding, image.element, image.element));
        words += plans.back().words;
    }
    if (images.empty()) return {};
    const auto start = std::chrono::steady_clock::now();
    check_total(scene, words, images.front().element, images.front().element);
    std::uint64_t first = scene.texels.grow(words);
    std::vector<TextureImage> out(images.size());
    std::vector<std::span<std::uint32_t>> slices;
    for (std::size_t i = 0; i < images.size(); ++i) {
        TextureImage& t = out[i];
        t.name = images[i].element;
        t.width = plans[i].image.width;
        t.height = plans[i].image.height;
        t.format = plans[i].image.format;
        t.srgb = plans[i].image.srgb;
        t.first_word = first;
        slices.push_back(scene.texels.mutable_words(first, plans[i].words));
        first += plans[i].words;
    }
    // An image's error is kept and the first (in order) thrown after all have stopped.
    std::vector<std::string> errors(images.size());
    parallel_for(images.size(), [&](std::size_t i) {
        try {
            decode(*readers[i], images[i].encoding, plans[i], slices[i], images[i].element, images[i].element);
        } catch (const SceneError& e) {
            errors[i] = e.what();
        }
        readers[i].reset();  // its decoded pixels, where it kept any
    });
    for (const std::string& e : errors) {
        if (!e.empty()) throw SceneError(e);
    }
    scene.texture_decode_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

std::vector<DecodedImage> decode_images(const std::vector<EncodedImage>& images, Scene& scene) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<DecodedImage> out(images.size());
    std::vector<std::string> errors(images.size());
    parallel_for(images.size(), [&](std::size_t i) {
        const EncodedImage& image = images[i];
        try {
            out[i] = load_texture_memory(image.data, image.size, image.format, image.encoding, image.element);
        } catch (const SceneError& e) {
            errors[i] = e.what();
        }
    });
    for (const std::string& e : errors) {
        if (!e.empty()) throw SceneError(e);
    }
    scene.texture_decode_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

void parallel_for(std::size_t count, const std::function<void(std::size_t)>& work) {
    // Each worker takes the next index until none is left: images and rows differ
    // widely in cost, so no fixed split.
    std::atomic<std::size_t> next{0};
    const auto worker = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < count;) work(i);
    };
    const std::size_t workers = std::min<std::size_t>(count, std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::jthread> threads;
    for (std::size_t w = 1; w < workers; ++w) threads.emplace_back(worker);
    worker();
}

std::uint32_t load_texture(Scene& scene, const std::filesystem::path& file, Encoding encoding, const std::string& element) {
    const auto start = std::chrono::steady_clock::now();
    DecodedImage image = load_texture_file(file, encoding, element);
    scene.texture_decode_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return add_texture(scene, std::move(image), file.string(), element);
}

std::uint32_t add_texture(Scene& scene, DecodedImage image, const std::string& name, const std::string& element) {
    check_total(scene, image.words.size(), name, element);
    TextureImage t;
    t.name = name;
    t.width = image.width;
    t.height = image.height;
    t.format = image.format;
    t.srgb = image.srgb;
    t.first_word = scene.texels.append(std::move(image.words));
    return add_texture_record(scene, std::move(t));
}

std::uint32_t add_texture_record(Scene& scene, TextureImage texture) {
    scene.textures.push_back(std::move(texture));
    return static_cast<std::uint32_t>(scene.textures.size() - 1);
}

std::array<double, 6> texture_transform(double offset_u, double offset_v, double rotation, double scale_u,
                                        double scale_v) {
    const double c = std::cos(rotation), s = std::sin(rotation);
    return {scale_u * c, scale_v * s, offset_u, -scale_u * s, scale_v * c, offset_v};
}

}  // namespace vkrt

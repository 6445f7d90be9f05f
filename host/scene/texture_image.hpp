#pragma once
// Texture images: decoded once (PNG and JPEG in this process, anything else through
// OpenImageIO: image/image_readers.hpp) and kept in the compact form the kernel
// reads (kernel/texture.glsl): 8-bit files stay 8-bit, four bytes a texel; only
// float and 16-bit files take half floats. All of a scene's texels live in one
// array, Scene::texels, which the flattened scene shares rather than copies.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

namespace vkrt {

enum class Wrap : std::uint8_t { Repeat, Clamp, Mirror };  // kernel WRAP_REPEAT, _CLAMP, _MIRROR

// How a texture's texels are stored, row after row from the top:
//   Rgba8: one word a texel, red in the low byte, alpha in the high one; the value
//          of a byte b is b / 255, or for red, green and blue of an sRGB-encoded
//          texture sRGB's decoding of it (TextureImage::srgb). 8-bit files.
//   Half:  two words a texel, half floats of (red, green) and of (blue, alpha), low
//          half first, linear. Float files, and 16-bit ones decoded to linear.
enum class TexelFormat : std::uint8_t { Half, Rgba8 };  // kernel TEXEL_HALF, TEXEL_RGBA8

// How a file's values become linear: colour textures in 8- or 16-bit formats are
// sRGB-encoded (glTF's base colour, PNG and JPEG by convention); float formats
// (.exr, .hdr) hold linear values already.
enum class Encoding : std::uint8_t { SrgbUnlessFloat, Linear };

// An allocator whose vectors leave new elements unset when they grow: texel arrays
// are written whole by their decoders, and zeroing them first would touch every
// fresh page twice, once in one thread (page faults cost as much as decoding where
// memory is virtualized: 64 MiB of them took 0.17 s on the 2-core test machine).
template <class T>
struct UninitializedAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = UninitializedAllocator<U>;
    };
    UninitializedAllocator() = default;
    template <class U>
    UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

// Texel words as TexelFormat says; a vector that grows without zeroing.
using TexelWords = std::vector<std::uint32_t, UninitializedAllocator<std::uint32_t>>;

// One image's texels, decoded.
struct DecodedImage {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    TexelFormat format = TexelFormat::Rgba8;
    bool srgb = false;                 // Rgba8: red, green and blue are sRGB-encoded
    TexelWords words;                  // as TexelFormat says
};

// A scene's texture: where its texels are in Scene::texels, and how to read them.
struct TextureImage {
    std::string name;  // the file, or where in a file the image was
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    TexelFormat format = TexelFormat::Rgba8;
    bool srgb = false;
    std::uint64_t first_word = 0;  // in Scene::texels
    Wrap wrap_s = Wrap::Repeat;
    Wrap wrap_t = Wrap::Repeat;
    // A normal map holds glTF's encoding c of tangent-space normals; the kernel bends
    // the shading normal by (2 c - 1) * (normal_scale, normal_scale, 1)
    // (kernel/normal_map.glsl). Unused by other textures.
    double normal_scale = 1.0;

    std::size_t texel_count() const { return std::size_t(width) * height; }
    std::size_t word_count() const { return texel_count() * (format == TexelFormat::Half ? 2 : 1); }
};

// Every texel of a scene, one array; copies of a Scene share it, and appending to a
// shared one copies it first, so a copy never sees another's textures change.
class TexelStore {
public:
    // Appends the words and returns where they start.
    std::uint64_t append(TexelWords&& words);
    // Room for `count` more words, unset, at the end; returns where it starts. For
    // decoders that write every word in place (mutable_words).
    std::uint64_t grow(std::size_t count);
    std::span<std::uint32_t> mutable_words(std::uint64_t first, std::size_t count);

    std::span<const std::uint32_t> words() const;
    std::size_t size() const { return words_ ? words_->size() : 0; }
    // The array itself, for the flattened scene to share (null when empty).
    std::shared_ptr<const TexelWords> share() const { return words_; }

private:
    TexelWords& own();
    std::shared_ptr<TexelWords> words_;
};

// The most texels one texture, and all of a scene's together, may hold.
inline constexpr std::uint32_t kMaxTextureSide = 16384;
inline constexpr std::uint64_t kMaxTextureTexels = std::uint64_t(1) << 26;

// The image file `file`; `element` names where the scene asked for it. Throws
// SceneError naming both when it cannot be read or is empty, too large or has
// no channels.
DecodedImage load_texture_file(const std::filesystem::path& file, Encoding encoding, const std::string& element);

// The same from a file's bytes held in memory (an image inside a .glb); `format`
// is a file name whose extension says what the bytes are (e.g. "image.png").
DecodedImage load_texture_memory(const unsigned char* data, std::size_t size, const std::string& format,
                                 Encoding encoding, const std::string& element);

// An image in linear float RGBA, rows from the top (an environment image).
struct LinearImage {
    std::string name;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<glm::vec4> texels;
};

// The image file `file` as linear floats (8- and 16-bit formats sRGB-decoded with
// Encoding::SrgbUnlessFloat); throws SceneError as load_texture_file does.
LinearImage load_linear_image(const std::filesystem::path& file, Encoding encoding, const std::string& element);

// An image file's bytes held in memory, to be decoded with others (decode_textures).
struct EncodedImage {
    const unsigned char* data = nullptr;
    std::size_t size = 0;
    std::string format;   // as load_texture_memory's
    Encoding encoding = Encoding::SrgbUnlessFloat;
    std::string element;  // for messages
};

struct Scene;

// Decodes the images on all hardware threads straight into the scene's texels, each
// once, and returns each one's TextureImage (not yet in scene.textures: callers add
// the records they need with add_texture_record). Throws SceneError as
// load_texture_memory does, for the first image (in order) that fails.
std::vector<TextureImage> decode_textures(const std::vector<EncodedImage>& images, Scene& scene);

// The same decoding, on all hardware threads, into images of their own rather than
// the scene's texels: for images only read to make others from (a specular-glossiness
// material's textures, converted), which then need not stay in the scene. Timed into
// Scene::texture_decode_seconds; throws as decode_textures does.
std::vector<DecodedImage> decode_images(const std::vector<EncodedImage>& images, Scene& scene);

// Calls work(i) for every i below `count`, on all hardware threads; `work` must not throw.
void parallel_for(std::size_t count, const std::function<void(std::size_t)>& work);

// The image file `file` decoded (load_texture_file) and added to the scene
// (add_texture), its decoding timed into Scene::texture_decode_seconds; its index.
std::uint32_t load_texture(Scene& scene, const std::filesystem::path& file, Encoding encoding, const std::string& element);

// Appends a decoded texture to the scene; throws SceneError naming `element` when the
// scene's textures would together pass kMaxTextureTexels. Returns its index.
std::uint32_t add_texture(Scene& scene, DecodedImage image, const std::string& name, const std::string& element);

// Appends a record of texels already in Scene::texels (decode_textures); returns its index.
std::uint32_t add_texture_record(Scene& scene, TextureImage texture);

// The affine map of texture coordinates that glTF's KHR_texture_transform
// describes: scaled, rotated by `rotation` radians (counter-clockwise in (u, v),
// clockwise in the image, whose v runs down), then offset; as Material::uv_transform.
std::array<double, 6> texture_transform(double offset_u, double offset_v, double rotation, double scale_u,
                                        double scale_v);

// Texel i (row y, column x: y * width + x) as the kernel reads it: linear, in float,
// bit for bit (texel_at in kernel/texture.glsl); a normal map's encoding undecoded.
glm::vec4 texel_value(const TextureImage& texture, std::span<const std::uint32_t> texels, std::size_t i);

// A colour channel (red, green or blue) of an Rgba8 texture holding `byte`, as
// texel_value decodes it; alpha is never sRGB-encoded.
float colour_byte_value(const TextureImage& texture, std::uint32_t byte);

// sRGB's transfer function, decoded: an encoded value in [0, 1] to linear.
double srgb_to_linear(double encoded);

// The 256 values of an sRGB-encoded byte, decoded and rounded to float: the table
// the kernel looks them up in.
const std::array<float, 256>& srgb_byte_table();

}  // namespace vkrt

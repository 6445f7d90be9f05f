#pragma once
// Texture images: read through OpenImageIO (image/image_files.hpp), held as linear
// RGBA floats for the flattening stage to pack (kernel/texture.glsl samples them).
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec4.hpp>
#include <glm/ext/vector_double4.hpp>

namespace vkrt {

enum class Wrap : std::uint8_t { Repeat, Clamp, Mirror };  // kernel WRAP_REPEAT, _CLAMP, _MIRROR

struct TextureImage {
    std::string name;  // the file, or where in a file the image was
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<glm::vec4> texels;  // linear, rows from the top
    Wrap wrap_s = Wrap::Repeat;
    Wrap wrap_t = Wrap::Repeat;
};

// How a file's values become linear: colour textures in 8- or 16-bit formats are
// sRGB-encoded (glTF's base colour, PNG and JPEG by convention); float formats
// (.exr, .hdr) hold linear values already.
enum class Encoding : std::uint8_t { SrgbUnlessFloat, Linear };

// The most texels one texture, and all of a scene's together, may hold.
inline constexpr std::uint32_t kMaxTextureSide = 16384;
inline constexpr std::uint64_t kMaxTextureTexels = std::uint64_t(1) << 26;

// The image file `file`; `element` names where the scene asked for it. Throws
// SceneError naming both when it cannot be read or is empty, too large or has
// no channels.
TextureImage load_texture_file(const std::filesystem::path& file, Encoding encoding, const std::string& element);

// The same from a file's bytes held in memory (an image inside a .glb); `format`
// is a file name whose extension says what the bytes are (e.g. "image.png").
TextureImage load_texture_memory(const unsigned char* data, std::size_t size, const std::string& format,
                                 Encoding encoding, const std::string& element);

struct Scene;

// Appends a texture to the scene; throws SceneError naming `element` when the
// scene's textures would together pass kMaxTextureTexels.
void add_texture(Scene& scene, TextureImage texture, const std::string& element);

// The affine map of texture coordinates that glTF's KHR_texture_transform
// describes: scaled, rotated by `rotation` radians (counter-clockwise in (u, v),
// clockwise in the image, whose v runs down), then offset; as Material::uv_transform.
std::array<double, 6> texture_transform(double offset_u, double offset_v, double rotation, double scale_u,
                                        double scale_v);

// The mean of a texture's texels, channel by channel (an emission texture's share
// of its emitter's power).
glm::dvec4 texture_mean(const TextureImage& texture);

// A linear normal map's texels made tangent-space vectors, as glTF defines them:
// (2 rgb - 1) * (scale, scale, 1); alpha is kept. The kernel (normal_map.glsl)
// filters and normalizes them.
void decode_normal_map(TextureImage& texture, double scale);

// sRGB's transfer function, decoded: an encoded value in [0, 1] to linear.
double srgb_to_linear(double encoded);

}  // namespace vkrt

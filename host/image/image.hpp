#pragma once
// Linear float RGB images and their files. The extension picks the format: .png is
// written here, every other format through OpenImageIO (image/image_files.hpp).
// .exr and .hdr are written as linear float; every other format (.png, .ppm, .jpg,
// ...) goes through the display transform (display.hpp: exposure, tone curve, clamp
// to [0, 1]), is sRGB-encoded and stored in 8 bits.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/display.hpp"

namespace vkrt {

class ImageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct Image {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<float> rgb;  // row-major, row 0 at the top, 3 floats a pixel

    Image() = default;
    Image(std::uint32_t w, std::uint32_t h) : width(w), height(h), rgb(std::size_t(w) * h * 3, 0.0f) {}
    float* pixel(std::uint32_t x, std::uint32_t y) { return &rgb[(std::size_t(y) * width + x) * 3]; }
    const float* pixel(std::uint32_t x, std::uint32_t y) const {
        return &rgb[(std::size_t(y) * width + x) * 3];
    }
};

// True for the formats written as linear floats.
bool is_float_format(const std::filesystem::path& file);

// True for .png (written here) and when OpenImageIO has a writer for the extension.
bool can_write_image_format(const std::filesystem::path& file);

// The sRGB transfer function (IEC 61966-2-1) for a linear value clamped to [0, 1].
float linear_to_srgb(float linear);

// The bytes an 8-bit file stores: each channel through the display transform,
// sRGB-encoded and rounded.
std::vector<std::uint8_t> to_srgb8(const Image& image, const Display& display = {});

// `display` applies to the 8-bit formats only.
void write_image(const Image& image, const std::filesystem::path& file, const Display& display = {});

// Further channels beside an image's R, G, B in one OpenEXR file: a layer named
// `name` whose channels are `name.<channel>` (as OpenImageIO and Blender's
// compositor name a layer's; a layer without a name has its channels bare, as the
// depth channel Z), `values` pixel after pixel, channel after channel.
struct ImageLayer {
    std::string name;
    std::vector<std::string> channels;
    std::vector<float> values;
};

// The image and its layers as a linear float OpenEXR file (`file` must end in .exr),
// with string `attributes` in its header.
void write_layered_exr(const Image& image, const std::vector<ImageLayer>& layers, const std::filesystem::path& file,
                       const std::map<std::string, std::string>& attributes = {});

// The layer `name` of an image file (its channels name.R, name.G, name.B, as
// write_layered_exr writes them) as an image; none when the file has no such layer.
std::optional<Image> read_layer(const std::filesystem::path& file, const std::string& name);

// Reads the first three channels (one channel is repeated as grey) as stored: 8-bit
// files give their encoded values scaled to [0, 1], float files their linear values.
Image read_image(const std::filesystem::path& file);

}  // namespace vkrt

#pragma once
// Image files through OpenImageIO, which vkrt loads only when a command reads or
// writes a format it has no writer of its own for (libvkrt_oiio.so,
// host/image/oiio_files.cpp): Debian's OpenImageIO pulls in some 260 shared
// libraries (OpenCV, FFmpeg, DCMTK, ...), which would otherwise load, and cost
// start-up, on every run. The interface holds only standard types, and errors
// cross it as text, so the plug-in and the program share no exception or OIIO type.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace vkrt {

enum class ChannelType : std::uint8_t { UInt8, UInt16, UInt32, Float, Half, Other };

// An image file's layout and attributes.
struct FileSpec {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<std::string> channels;           // names, in the file's order
    std::vector<ChannelType> types;              // one per channel
    std::map<std::string, std::string> strings;  // string attributes
    std::map<std::string, int> ints;             // integer attributes

    std::string string_or(const std::string& name, const std::string& otherwise = {}) const {
        const auto it = strings.find(name);
        return it == strings.end() ? otherwise : it->second;
    }
    int int_or(const std::string& name, int otherwise) const {
        const auto it = ints.find(name);
        return it == ints.end() ? otherwise : it->second;
    }
};

inline std::size_t channel_bytes(ChannelType type) {
    return type == ChannelType::UInt8 ? 1 : type == ChannelType::Half || type == ChannelType::UInt16 ? 2 : 4;
}

class ImageFileReader {
public:
    virtual ~ImageFileReader() = default;
    virtual const FileSpec& spec() const = 0;
    // Rows [first, end) in the channels' own types, pixel after pixel; false, with
    // error() saying why, when the file is truncated or damaged.
    virtual bool read_rows(std::uint32_t first, std::uint32_t end, void* pixels) = 0;
    // Every pixel, every channel converted to float.
    virtual bool read_floats(float* pixels) = 0;
    // Every pixel as 8-bit RGBA in one word, red in the low byte: one channel spread
    // to red, green and blue, two as grey and alpha, a missing alpha 255. Only for
    // images whose channels are all UInt8 (false otherwise).
    virtual bool read_rgba8(std::uint32_t* texels) {
        const FileSpec& s = spec();
        const std::size_t channels = s.channels.size();
        if (channels == 0) return false;
        for (ChannelType t : s.types) {
            if (t != ChannelType::UInt8) return false;
        }
        // Row by row, so that the file's own pixels never need a buffer of their size.
        std::vector<std::uint8_t> row(std::size_t(s.width) * channels);
        for (std::uint32_t y = 0; y < s.height; ++y) {
            if (!read_rows(y, y + 1, row.data())) return false;
            for (std::uint32_t x = 0; x < s.width; ++x) {
                const std::uint8_t* v = &row[std::size_t(x) * channels];
                const std::uint32_t r = v[0], g = channels >= 3 ? v[1] : r, b = channels >= 3 ? v[2] : r;
                const std::uint32_t a = channels == 2 ? v[1] : channels >= 4 ? v[3] : 255u;
                texels[std::size_t(y) * s.width + x] = r | g << 8 | b << 16 | a << 24;
            }
        }
        return true;
    }
    virtual std::string error() const = 0;
};

// The plug-in's functions. Each reports failure by its result and `error`.
struct ImageFiles {
    bool (*can_write)(const std::string& file);
    std::unique_ptr<ImageFileReader> (*open)(const std::string& file, std::string& error);
    // An image file's bytes held in memory (`data` must outlive the reader); `name`'s
    // extension tells the format.
    std::unique_ptr<ImageFileReader> (*open_memory)(const void* data, std::size_t size, const std::string& name,
                                                    std::string& error);
    // `pixels` in the spec's channel types, pixel after pixel.
    bool (*write)(const std::string& file, const FileSpec& spec, const void* pixels, std::string& error);
};

// Loads the plug-in on the first call; throws ImageError when it cannot be found
// or loaded.
const ImageFiles& image_files();

// The name under which the plug-in exports `const ImageFiles* vkrt_image_files()`.
inline constexpr const char* kImageFilesSymbol = "vkrt_image_files";

}  // namespace vkrt

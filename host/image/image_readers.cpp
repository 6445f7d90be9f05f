#include "image/image_readers.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <vector>

#include <spng.h>
#include <turbojpeg.h>

namespace vkrt {
namespace {

// The most texels a side the readers here decode; a texture may have fewer
// (texture_image.hpp), and a header claiming more is refused before any allocation.
constexpr std::uint32_t kMaxSide = 1u << 16;

bool is_png(const unsigned char* p, std::size_t n) {
    static const unsigned char magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    return n >= 8 && std::memcmp(p, magic, 8) == 0;
}

bool is_jpeg(const unsigned char* p, std::size_t n) { return n >= 3 && p[0] == 0xff && p[1] == 0xd8 && p[2] == 0xff; }

// The file's bytes, where the reader keeps them (a file read from disk) or where the
// caller does (memory).
struct Bytes {
    std::vector<unsigned char> owned;
    const unsigned char* data = nullptr;
    std::size_t size = 0;
};

// A reader that decodes the whole image at the first read into `pixels_` (RGBA, 8 or
// 16 bits a channel), except read_rgba8, which decodes into the caller's words.
class WholeImageReader : public ImageFileReader {
public:
    const FileSpec& spec() const override { return spec_; }
    std::string error() const override { return error_; }

    bool read_rows(std::uint32_t first, std::uint32_t end, void* pixels) override {
        if (!decoded() || first > end || end > spec_.height) return false;
        const std::size_t row = std::size_t(spec_.width) * 4 * bytes_per_channel();
        std::memcpy(pixels, pixels_.data() + first * row, (end - first) * row);
        return true;
    }

    bool read_floats(float* out) override {
        if (!decoded()) return false;
        const std::size_t n = std::size_t(spec_.width) * spec_.height * 4;
        if (bytes_per_channel() == 1) {
            for (std::size_t i = 0; i < n; ++i) out[i] = float(pixels_[i]) / 255.0f;
        } else {
            for (std::size_t i = 0; i < n; ++i) {
                std::uint16_t v;
                std::memcpy(&v, &pixels_[2 * i], 2);
                out[i] = float(v) / 65535.0f;
            }
        }
        return true;
    }

    bool read_rgba8(std::uint32_t* texels) override {
        if (bytes_per_channel() != 1) return false;
        return decode(reinterpret_cast<unsigned char*>(texels), std::size_t(spec_.width) * spec_.height * 4);
    }

protected:
    void set_spec(std::uint32_t width, std::uint32_t height, ChannelType type) {
        spec_.width = width;
        spec_.height = height;
        spec_.channels = {"R", "G", "B", "A"};
        spec_.types.assign(4, type);
    }
    std::size_t bytes_per_channel() const { return spec_.types.front() == ChannelType::UInt8 ? 1 : 2; }
    // Decodes into `out` of `size` bytes (RGBA, the spec's channel type); false, with
    // error_ set, on damaged data.
    virtual bool decode(unsigned char* out, std::size_t size) = 0;

    std::string error_;

private:
    bool decoded() {
        if (!pixels_.empty()) return true;
        pixels_.resize(std::size_t(spec_.width) * spec_.height * 4 * bytes_per_channel());
        if (decode(pixels_.data(), pixels_.size())) return true;
        pixels_.clear();
        return false;
    }

    FileSpec spec_;
    std::vector<unsigned char> pixels_;
};

// PNG (ISO/IEC 15948) through libspng: any colour type and depth, as RGBA, 8 bits a
// channel, or 16 for 16-bit files; a tRNS chunk becomes alpha.
class PngReader final : public WholeImageReader {
public:
    explicit PngReader(Bytes bytes) : bytes_(std::move(bytes)) {}
    ~PngReader() override { spng_ctx_free(ctx_); }
    PngReader(const PngReader&) = delete;
    PngReader& operator=(const PngReader&) = delete;

    bool open() {
        ctx_ = spng_ctx_new(0);
        if (!ctx_) return fail(SPNG_EMEM);
        spng_set_image_limits(ctx_, kMaxSide, kMaxSide);
        // Ancillary chunks of up to 64 MiB each, 256 MiB in all: a text chunk cannot
        // make the decoder hold more than a large texture would.
        spng_set_chunk_limits(ctx_, 64u << 20, 256u << 20);
        int r = spng_set_png_buffer(ctx_, bytes_.data, bytes_.size);
        spng_ihdr ihdr{};
        if (r == 0) r = spng_get_ihdr(ctx_, &ihdr);
        if (r != 0) return fail(r);
        set_spec(ihdr.width, ihdr.height, ihdr.bit_depth == 16 ? ChannelType::UInt16 : ChannelType::UInt8);
        return true;
    }

private:
    bool decode(unsigned char* out, std::size_t size) override {
        const int format = bytes_per_channel() == 1 ? SPNG_FMT_RGBA8 : SPNG_FMT_RGBA16;
        std::size_t needed = 0;
        int r = spng_decoded_image_size(ctx_, format, &needed);
        if (r == 0 && needed != size) r = SPNG_EOVERFLOW;
        if (r == 0) r = spng_decode_image(ctx_, out, size, format, SPNG_DECODE_TRNS);
        return r == 0 || fail(r);
    }
    bool fail(int code) {
        error_ = std::string("PNG: ") + spng_strerror(code);
        return false;
    }

    Bytes bytes_;
    spng_ctx* ctx_ = nullptr;
};

// JPEG through libjpeg-turbo's TurboJPEG interface, with libjpeg's default (accurate)
// DCT and upsampling, as RGBA. Warnings (a truncated file, whose missing rows are
// grey) are accepted, as viewers accept them; errors are not.
class JpegReader final : public WholeImageReader {
public:
    explicit JpegReader(Bytes bytes) : bytes_(std::move(bytes)) {}
    ~JpegReader() override {
        if (handle_) tjDestroy(handle_);
    }
    JpegReader(const JpegReader&) = delete;
    JpegReader& operator=(const JpegReader&) = delete;

    bool open() {
        handle_ = tjInitDecompress();
        if (!handle_) {
            error_ = "JPEG: cannot start the decoder";
            return false;
        }
        int width = 0, height = 0, subsampling = 0, colorspace = 0;
        if (tjDecompressHeader3(handle_, bytes_.data, static_cast<unsigned long>(bytes_.size), &width, &height,
                                &subsampling, &colorspace) != 0) {
            return fail();
        }
        if (colorspace == TJCS_CMYK || colorspace == TJCS_YCCK) {
            error_ = "JPEG: CMYK";  // left to the plug-in (open_image_memory)
            return false;
        }
        if (width <= 0 || height <= 0 || std::uint32_t(width) > kMaxSide || std::uint32_t(height) > kMaxSide) {
            error_ = "JPEG: " + std::to_string(width) + " x " + std::to_string(height) + " pixels is beyond what vkrt reads";
            return false;
        }
        set_spec(std::uint32_t(width), std::uint32_t(height), ChannelType::UInt8);
        return true;
    }

private:
    bool decode(unsigned char* out, std::size_t) override {
        const FileSpec& s = spec();
        const int r = tjDecompress2(handle_, bytes_.data, static_cast<unsigned long>(bytes_.size), out, int(s.width),
                                    0, int(s.height), TJPF_RGBA, 0);
        return r == 0 || tjGetErrorCode(handle_) == TJERR_WARNING || fail();
    }
    bool fail() {
        std::string text = std::string("JPEG: ") + tjGetErrorStr2(handle_);
        std::replace(text.begin(), text.end(), '\n', ' ');
        error_ = text;
        return false;
    }

    Bytes bytes_;
    tjhandle handle_ = nullptr;
};

// A PNG or JPEG reader over `bytes`, or null: not such a file (`recognized` false),
// or one whose header cannot be read (`error`).
std::unique_ptr<ImageFileReader> open_builtin(Bytes bytes, bool& recognized, std::string& error) {
    recognized = true;
    if (is_png(bytes.data, bytes.size)) {
        auto r = std::make_unique<PngReader>(std::move(bytes));
        if (r->open()) return r;
        error = r->error();
        return nullptr;
    }
    if (is_jpeg(bytes.data, bytes.size)) {
        auto r = std::make_unique<JpegReader>(std::move(bytes));
        if (r->open()) return r;
        error = r->error();
        // CMYK JPEGs are rare enough to leave to OpenImageIO.
        recognized = error != "JPEG: CMYK";
        return nullptr;
    }
    recognized = false;
    return nullptr;
}

}  // namespace

std::unique_ptr<ImageFileReader> open_image_memory(const void* data, std::size_t size, const std::string& name,
                                                   std::string& error) {
    Bytes bytes;
    bytes.data = static_cast<const unsigned char*>(data);
    bytes.size = size;
    bool recognized = false;
    if (auto r = open_builtin(std::move(bytes), recognized, error)) return r;
    if (recognized) return nullptr;
    error.clear();
    return image_files().open_memory(data, size, name, error);
}

std::unique_ptr<ImageFileReader> open_image_file(const std::string& file, std::string& error) {
    unsigned char head[8] = {};
    std::ifstream in(file, std::ios::binary);
    in.read(reinterpret_cast<char*>(head), sizeof head);
    const std::size_t got = in ? sizeof head : std::size_t(in.gcount());
    if (is_png(head, got) || is_jpeg(head, got)) {
        std::error_code ec;
        const std::uintmax_t size = std::filesystem::file_size(file, ec);
        if (ec) {
            error = ec.message();
            return nullptr;
        }
        Bytes bytes;
        bytes.owned.resize(size);
        in.seekg(0);
        if (!in.read(reinterpret_cast<char*>(bytes.owned.data()), std::streamsize(size))) {
            error = "cannot read the file";
            return nullptr;
        }
        bytes.data = bytes.owned.data();
        bytes.size = bytes.owned.size();
        bool recognized = false;
        if (auto r = open_builtin(std::move(bytes), recognized, error)) return r;
        if (recognized) return nullptr;
        error.clear();
    }
    return image_files().open(file, error);
}

}  // namespace vkrt

// libvkrt_oiio.so: image files through OpenImageIO, behind image/image_files.hpp.
// Built as a plug-in that vkrt loads on first use; nothing else links OpenImageIO.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "image/image_files.hpp"

namespace vkrt {
namespace {

OIIO::TypeDesc oiio_type(ChannelType type) {
    switch (type) {
    case ChannelType::UInt8: return OIIO::TypeDesc::UINT8;
    case ChannelType::UInt16: return OIIO::TypeDesc::UINT16;
    case ChannelType::UInt32: return OIIO::TypeDesc::UINT32;
    case ChannelType::Half: return OIIO::TypeDesc::HALF;
    default: return OIIO::TypeDesc::FLOAT;
    }
}

ChannelType channel_type(OIIO::TypeDesc type) {
    if (type == OIIO::TypeDesc::UINT8) return ChannelType::UInt8;
    if (type == OIIO::TypeDesc::UINT16) return ChannelType::UInt16;
    if (type == OIIO::TypeDesc::UINT32) return ChannelType::UInt32;
    if (type == OIIO::TypeDesc::FLOAT) return ChannelType::Float;
    if (type == OIIO::TypeDesc::HALF) return ChannelType::Half;
    return ChannelType::Other;
}

class OiioReader final : public ImageFileReader {
public:
    explicit OiioReader(std::unique_ptr<OIIO::ImageInput> in, std::unique_ptr<OIIO::Filesystem::IOProxy> proxy = nullptr)
        : proxy_(std::move(proxy)), in_(std::move(in)) {
        const OIIO::ImageSpec& s = in_->spec();
        spec_.width = std::uint32_t(s.width);
        spec_.height = std::uint32_t(s.height);
        for (int c = 0; c < s.nchannels; ++c) {
            spec_.channels.push_back(s.channelnames[std::size_t(c)]);
            spec_.types.push_back(channel_type(s.channelformat(c)));
        }
        for (const OIIO::ParamValue& p : s.extra_attribs) {
            if (p.type() == OIIO::TypeDesc::STRING) spec_.strings[p.name().string()] = p.get_string();
            if (p.type() == OIIO::TypeDesc::INT) spec_.ints[p.name().string()] = p.get_int();
        }
    }
    const FileSpec& spec() const override { return spec_; }
    bool read_rows(std::uint32_t first, std::uint32_t end, void* pixels) override {
        const OIIO::ImageSpec& s = in_->spec();
        return in_->read_scanlines(0, 0, s.y + int(first), s.y + int(end), 0, 0, s.nchannels, OIIO::TypeDesc::UNKNOWN,
                                   pixels);
    }
    bool read_floats(float* pixels) override {
        return in_->read_image(0, 0, 0, in_->spec().nchannels, OIIO::TypeDesc::FLOAT, pixels);
    }
    std::string error() const override { return in_->geterror(); }

private:
    std::unique_ptr<OIIO::Filesystem::IOProxy> proxy_;  // the bytes of an image read from memory; outlives in_
    std::unique_ptr<OIIO::ImageInput> in_;
    FileSpec spec_;
};

bool can_write(const std::string& file) { return OIIO::ImageOutput::create(file) != nullptr; }

std::unique_ptr<ImageFileReader> open(const std::string& file, std::string& error) {
    auto in = OIIO::ImageInput::open(file);
    if (!in) {
        error = OIIO::geterror();
        return nullptr;
    }
    return std::make_unique<OiioReader>(std::move(in));
}

std::unique_ptr<ImageFileReader> open_memory(const void* data, std::size_t size, const std::string& name,
                                             std::string& error) {
    auto proxy = std::make_unique<OIIO::Filesystem::IOMemReader>(const_cast<void*>(data), size);
    auto in = OIIO::ImageInput::open(name, nullptr, proxy.get());
    if (!in) {
        error = OIIO::geterror();
        return nullptr;
    }
    return std::make_unique<OiioReader>(std::move(in), std::move(proxy));
}

bool write(const std::string& file, const FileSpec& spec, const void* pixels, std::string& error) {
    auto out = OIIO::ImageOutput::create(file);
    if (!out) {
        error = "cannot write this image format (" + OIIO::geterror() + ")";
        return false;
    }
    OIIO::ImageSpec s(int(spec.width), int(spec.height), int(spec.channels.size()), oiio_type(spec.types.front()));
    s.channelnames = spec.channels;
    // Per-channel formats only where channels differ: not every writer takes them.
    for (ChannelType t : spec.types) {
        if (t != spec.types.front()) {
            for (ChannelType each : spec.types) s.channelformats.push_back(oiio_type(each));
            break;
        }
    }
    for (const auto& [name, value] : spec.strings) s.attribute(name, value);
    for (const auto& [name, value] : spec.ints) s.attribute(name, value);
    if (!out->open(file, s)) {
        error = "cannot open for writing: " + out->geterror();
        return false;
    }
    if (!out->write_image(OIIO::TypeDesc::UNKNOWN, pixels) || !out->close()) {
        error = "writing failed: " + out->geterror();
        return false;
    }
    return true;
}

const ImageFiles kFiles{&can_write, &open, &open_memory, &write};

}  // namespace
}  // namespace vkrt

extern "C" __attribute__((visibility("default"))) const vkrt::ImageFiles* vkrt_image_files() { return &vkrt::kFiles; }

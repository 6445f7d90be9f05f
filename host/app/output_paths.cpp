#include "app/output_paths.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <unistd.h>

#include "image/image.hpp"

namespace vkrt::app {

void check_writable_file(const std::filesystem::path& file, const char* what) {
    const std::filesystem::path dir = file.parent_path().empty() ? "." : file.parent_path();
    if (!std::filesystem::is_directory(dir)) {
        throw std::runtime_error(fmt::format("{}: cannot write the {} there: no directory {}", file.string(), what,
                                             dir.string()));
    }
}

void check_writable_image(const std::filesystem::path& file) {
    check_writable_file(file, "image");
    if (!can_write_image_format(file)) {
        throw std::runtime_error(fmt::format(
            "{}: unknown image format '{}' (use .png or .ppm for 8-bit sRGB, .exr, .hdr or .pfm for linear float)",
            file.string(), file.extension().string()));
    }
}

bool is_exr(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".exr";
}

void write_atomically(const std::filesystem::path& file,
                      const std::function<void(const std::filesystem::path& temporary)>& write) {
    // Hidden, and named for this process, so two renders into one directory never
    // share a temporary; the extension stays last, where OpenImageIO reads the format.
    const std::filesystem::path temporary =
        file.parent_path() / fmt::format(".{}.vkrt-{}{}", file.stem().string(), ::getpid(), file.extension().string());
    try {
        write(temporary);
        std::error_code error;
        std::filesystem::rename(temporary, file, error);
        if (error) throw std::runtime_error(fmt::format("{}: cannot replace it: {}", file.string(), error.message()));
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw;
    }
}

}  // namespace vkrt::app

#include "scene/read_text.hpp"

#include <cerrno>
#include <cstdio>
#include <memory>
#include <system_error>

#include <fmt/format.h>

#include "scene/scene_error.hpp"

namespace vkrt {

std::string read_text(const std::filesystem::path& file, const std::string& name, std::string_view kind) {
    // C stdio rather than iostreams: it reliably leaves errno set, so the message
    // can say why (no such file, permission denied, is a directory).
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
    if (!f) {
        throw SceneError(fmt::format("{}: cannot open {} file ({})", name, kind,
                                     std::generic_category().message(errno)));
    }
    std::string text;
    char buffer[1 << 16];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, f.get())) > 0) text.append(buffer, n);
    if (std::ferror(f.get())) {
        throw SceneError(fmt::format("{}: cannot open {} file (read failed: {})", name, kind,
                                     std::generic_category().message(errno)));
    }
    return text;
}

}  // namespace vkrt

#include "scene/read_text.hpp"

#include <cerrno>
#include <climits>
#include <cstdio>
#include <memory>
#include <system_error>

#include <fmt/format.h>
#include <zlib.h>

#include "scene/scene_error.hpp"

namespace vkrt {
namespace {

bool is_gzip(const std::string& bytes) {
    // RFC 1952: ID1 = 0x1f, ID2 = 0x8b.
    return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
           static_cast<unsigned char>(bytes[1]) == 0x8b;
}

// Every gzip member of `bytes`, decompressed and concatenated (RFC 1952 allows several).
std::string gunzip(const std::string& bytes, const std::string& name) {
    if (bytes.size() > UINT_MAX) throw SceneError(fmt::format("{}: gzip file larger than 4 GiB", name));
    z_stream z{};
    // 15 + 16: the largest window, gzip framing.
    if (inflateInit2(&z, 15 + 16) != Z_OK) throw SceneError(fmt::format("{}: cannot start gzip decompression", name));
    const std::unique_ptr<z_stream, int (*)(z_stream*)> end(&z, &inflateEnd);
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
    z.avail_in = static_cast<uInt>(bytes.size());
    std::string text;
    char buffer[1 << 16];
    for (;;) {
        z.next_out = reinterpret_cast<Bytef*>(buffer);
        z.avail_out = sizeof buffer;
        const int status = inflate(&z, Z_NO_FLUSH);
        text.append(buffer, sizeof buffer - z.avail_out);
        if (status == Z_OK) continue;
        if (status == Z_STREAM_END) {
            if (z.avail_in == 0) return text;
            inflateReset(&z);  // another member follows
            continue;
        }
        if (status == Z_BUF_ERROR && z.avail_in == 0) {
            throw SceneError(fmt::format("{}: corrupt gzip data (the file ends inside the compressed stream)", name));
        }
        throw SceneError(fmt::format("{}: corrupt gzip data ({})", name,
                                     z.msg != nullptr ? z.msg : fmt::format("zlib error {}", status)));
    }
}

}  // namespace

std::string read_text(const std::filesystem::path& file, const std::string& name, std::string_view kind) {
    // C stdio rather than iostreams: it reliably leaves errno set, so the message
    // can say why (no such file, permission denied, is a directory).
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
    if (!f) {
        throw SceneError(fmt::format("{}: cannot open {} file ({})", name, kind,
                                     std::generic_category().message(errno)));
    }
    // Sized once from the file's length (a 10 MB scene is otherwise copied as it
    // grows); a file that grows meanwhile, or a pipe, is read on in chunks.
    std::error_code size_error;
    const std::uintmax_t size = std::filesystem::file_size(file, size_error);
    std::string bytes(size_error ? 0 : std::size_t(size), '\0');
    const std::size_t used = bytes.empty() ? 0 : std::fread(bytes.data(), 1, bytes.size(), f.get());
    bytes.resize(used);
    char buffer[1 << 16];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, f.get())) > 0) bytes.append(buffer, n);
    if (std::ferror(f.get())) {
        throw SceneError(fmt::format("{}: cannot open {} file (read failed: {})", name, kind,
                                     std::generic_category().message(errno)));
    }
    if (is_gzip(bytes)) return gunzip(bytes, name);
    return bytes;
}

std::string format_extension(const std::filesystem::path& file) {
    const std::filesystem::path named = file.extension() == ".gz" ? file.stem() : file.filename();
    return named.extension().string();
}

std::string scene_stem(const std::filesystem::path& file) {
    const std::filesystem::path named = file.extension() == ".gz" ? file.stem() : file.filename();
    return named.stem().string();
}

}  // namespace vkrt

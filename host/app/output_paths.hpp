#pragma once
// Checks on the files a command will write, made before any work starts, so that a
// typo in a path is an error at once and not after a long render.
#include <filesystem>
#include <functional>

namespace vkrt::app {

// Throws when the file's directory does not exist; `what` names it in the message
// ("image", "stats file", ...).
void check_writable_file(const std::filesystem::path& file, const char* what);

// As check_writable_file, and the extension must be an image format OpenImageIO writes.
void check_writable_image(const std::filesystem::path& file);

// Whether the file is OpenEXR by its extension (any case): the only format a partial
// file can be.
bool is_exr(const std::filesystem::path& file);

// Writes `file` whole or not at all: `write` fills a temporary file beside it (same
// directory and extension, so the same format), which then replaces `file` by a
// rename. A reader, or a render killed while writing, never sees half a file.
void write_atomically(const std::filesystem::path& file,
                      const std::function<void(const std::filesystem::path& temporary)>& write);

}  // namespace vkrt::app

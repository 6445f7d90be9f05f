#pragma once
// Opening an image to read: PNG and JPEG, the formats glTF textures come in, are
// decoded in this process (libspng, libjpeg-turbo); anything else goes through the
// OpenImageIO plug-in (image_files.hpp). The plug-in brings some 260 shared
// libraries, whose loading alone took about a second and 280 MB of resident memory
// on a glTF asset with one PNG texture; the two decoders cost a few milliseconds.
#include <cstddef>
#include <memory>
#include <string>

#include "image/image_files.hpp"

namespace vkrt {

// An image file's bytes held in memory (`data` must outlive the reader). PNG and JPEG
// are recognized by their first bytes; for anything else `name`'s extension tells
// the plug-in the format. Null, with `error` saying why in one line, when the image
// cannot be opened; throws ImageError when the plug-in is needed and cannot load.
std::unique_ptr<ImageFileReader> open_image_memory(const void* data, std::size_t size, const std::string& name,
                                                   std::string& error);

// The same for a file on disk.
std::unique_ptr<ImageFileReader> open_image_file(const std::string& file, std::string& error);

}  // namespace vkrt

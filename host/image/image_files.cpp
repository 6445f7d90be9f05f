#include "image/image_files.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <filesystem>
#include <system_error>

#include <fmt/format.h>

#include "image/image.hpp"

namespace vkrt {
namespace {

constexpr const char* kPlugin = "libvkrt_oiio.so";

// Beside the program (an installed or relocated vkrt), else where this build put it
// (the test programs, which live one directory below).
std::vector<std::filesystem::path> plugin_candidates() {
    std::vector<std::filesystem::path> paths;
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) paths.push_back(self.parent_path() / kPlugin);
    paths.push_back(std::filesystem::path(VKRT_PLUGIN_DIR) / kPlugin);
    return paths;
}

const ImageFiles* load() {
    std::string errors;
    for (const std::filesystem::path& path : plugin_candidates()) {
        if (!std::filesystem::exists(path)) continue;
        void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!library) {
            errors += fmt::format("; {}", dlerror());
            continue;
        }
        using Entry = const ImageFiles* (*)();
        if (auto entry = reinterpret_cast<Entry>(dlsym(library, kImageFilesSymbol))) return entry();
        errors += fmt::format("; {} has no {}", path.string(), kImageFilesSymbol);
    }
    throw ImageError(fmt::format("cannot load {}, through which vkrt reads and writes image files other than PNG "
                                 "output (it is built beside build/vkrt: run ./scripts/setup){}",
                                 kPlugin, errors));
}

}  // namespace

const ImageFiles& image_files() {
    static const ImageFiles* const files = load();  // tried again after a failure
    return *files;
}

}  // namespace vkrt

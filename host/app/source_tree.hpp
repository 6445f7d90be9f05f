#pragma once
// Files the program reads beside its scenes: the benchmark's default scenes and the
// SPD scenes (scenes/), the plot script (scripts/). An unpacked bundle
// (scripts/bundle) holds them in share/vkrt/ beside bin/; a build reads them from the
// source tree it was built from. Either way they are found whatever the working
// directory.
#include <filesystem>
#include <string_view>
#include <system_error>

namespace vkrt::app {

inline std::filesystem::path source_tree_path(std::string_view relative) {
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        const std::filesystem::path bundled = self.parent_path().parent_path() / "share" / "vkrt" / relative;
        if (std::filesystem::exists(bundled, error)) return bundled;
    }
    return std::filesystem::path(VKRT_SOURCE_DIR) / relative;
}

}  // namespace vkrt::app

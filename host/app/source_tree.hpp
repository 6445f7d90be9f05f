#pragma once
// Files the program reads from the source tree it was built from: the benchmark's
// default scenes and the SPD scenes (scenes/), the plot script (scripts/). Named
// from there, they are found whatever the working directory.
#include <filesystem>
#include <string_view>

namespace vkrt::app {

inline std::filesystem::path source_tree_path(std::string_view relative) {
    return std::filesystem::path(VKRT_SOURCE_DIR) / relative;
}

}  // namespace vkrt::app

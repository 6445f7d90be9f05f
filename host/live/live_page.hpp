#pragma once
// The live preview's page, web/live.html, built into the program
// (cmake/EmbedFile.cmake) so that vkrt serves it from anywhere it is installed.
#include <string_view>

namespace vkrt::live {

extern const std::string_view kLivePage;

}  // namespace vkrt::live

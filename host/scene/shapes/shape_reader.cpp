#include "scene/shapes/shape_reader.hpp"

#include <fmt/format.h>

namespace vkrt {

void ShapeReader::warn(const std::string& file, std::vector<std::string>& warnings) const {
    if (zero_area > 0) {
        warnings.push_back(fmt::format("{}: skipped {} triangle{} of zero area (coinciding vertices or all on one "
                                       "line), the first at {}",
                                       file, zero_area, zero_area == 1 ? "" : "s", first_zero_area));
    }
    if (zero_normals > 0) {
        warnings.push_back(fmt::format("{}: {} triangle{} with a zero vertex normal, shaded with the face normal "
                                       "there, the first at {}",
                                       file, zero_normals, zero_normals == 1 ? "" : "s", first_zero_normal));
    }
}

}  // namespace vkrt

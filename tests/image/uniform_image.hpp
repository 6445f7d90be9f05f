#pragma once
// An image of one value in every channel, for the image tests.
#include <cstdint>

#include "image/image.hpp"

namespace vkrt::test {

inline Image uniform_image(std::uint32_t w, std::uint32_t h, float v) {
    Image image(w, h);
    for (float& x : image.rgb) x = v;
    return image;
}

}  // namespace vkrt::test

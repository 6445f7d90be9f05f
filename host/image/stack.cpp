#include "image/stack.hpp"

#include <fmt/format.h>

namespace vkrt {

StackedImage stack_images(const std::vector<Image>& images) {
    if (images.size() < 2) {
        throw ImageError(fmt::format("a stack needs two images or more to estimate a variance from, got {}",
                                     images.size()));
    }
    const Image& first = images.front();
    for (std::size_t k = 1; k < images.size(); ++k) {
        if (images[k].width != first.width || images[k].height != first.height) {
            throw ImageError(fmt::format("image {} is {}x{}, the first {}x{}: a stack's images must be of one size",
                                         k + 1, images[k].width, images[k].height, first.width, first.height));
        }
    }
    const double n = double(images.size());
    StackedImage s{Image(first.width, first.height), Image(first.width, first.height), n - 1.0};
    for (std::size_t i = 0; i < first.rgb.size(); ++i) {
        // Two passes: the mean, then the squared deviations from it (no cancellation).
        double sum = 0.0;
        for (const Image& image : images) sum += double(image.rgb[i]);
        const double mean = sum / n;
        double squares = 0.0;
        for (const Image& image : images) squares += (double(image.rgb[i]) - mean) * (double(image.rgb[i]) - mean);
        s.mean.rgb[i] = static_cast<float>(mean);
        s.variance.rgb[i] = static_cast<float>(squares / (n - 1.0) / n);
    }
    return s;
}

}  // namespace vkrt

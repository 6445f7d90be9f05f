#pragma once
// A statistical test of two Monte Carlo images (docs/decisions/0049-z-test.md): is
// their difference explained by their noise? Each pixel channel's difference over the
// standard deviation its variances give is a Z-score (a t-score where a variance was
// estimated from few degrees of freedom, decision 0051); its two-sided p-value is
// tested at the level that keeps the chance of any false rejection among all of them
// at `alpha` (Šidák's correction, exact for independent pixels). Beside the pixels,
// each channel's image mean is tested the same way, in the same family: a small bias
// spread over the whole image shows there long before any one pixel shows it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "image/image.hpp"

namespace vkrt {

// One image channel's mean difference A - B over the pixel channels tested, its
// standard error from their variances, the Z-score and its two-sided p-value.
struct MeanTest {
    double difference = 0.0;
    double standard_error = 0.0;
    double z = 0.0;
    double p = 1.0;
};

struct ZTestResult {
    double alpha = 0.0;          // the familywise level asked for
    std::size_t tests = 0;       // pixel channels tested
    double level = 0.0;          // each test's level: 1 - (1 - alpha)^(1 / (tests + 3))
    std::size_t rejected = 0;    // pixel channels whose p-value is below `level`
    double min_p = 1.0;          // the smallest p-value of a pixel channel
    double worst_z = 0.0;        // its score (signed: A above B is positive)
    std::uint32_t worst_x = 0, worst_y = 0, worst_channel = 0;
    std::array<MeanTest, 3> means;  // the image means of R, G, B
    std::size_t means_rejected = 0;  // of those, below `level`
    bool rejects() const { return rejected > 0 || means_rejected > 0; }
};

// The variance of each pixel mean of an image, and the degrees of freedom of that
// estimate: infinite (scores taken as normal) for a render's own samples, tens or
// more of them; K - 1 for the spread of K independent images (vkrt stack).
struct PixelVariance {
    const Image* image = nullptr;
    double dof = std::numeric_limits<double>::infinity();
};

// A with its pixel means' variance `var_a`; B likewise, or a reference taken as
// exact (`var_b.image` null). A channel whose variances are infinite (a pixel of
// fewer than two samples) is not tested; one whose variances are both 0 is tested
// exactly: equal values pass, any difference is rejected (p = 0). Where a variance
// has finite degrees of freedom a pixel channel's score is Student's t of the
// smaller degrees of freedom of its two variances; the image means, whose variances
// sum those of thousands of pixels, are taken as normal. The
// images must be of one size. With `p_values`, each pixel channel's p-value (1 where
// untested).
ZTestResult z_test(const Image& a, PixelVariance var_a, const Image& b, PixelVariance var_b, double alpha,
                   Image* p_values = nullptr);

// The same for variances of infinite degrees of freedom: B exact where `var_b` is null.
inline ZTestResult z_test(const Image& a, const Image& var_a, const Image& b, const Image* var_b, double alpha,
                          Image* p_values = nullptr) {
    return z_test(a, PixelVariance{&var_a}, b, PixelVariance{var_b}, alpha, p_values);
}

}  // namespace vkrt

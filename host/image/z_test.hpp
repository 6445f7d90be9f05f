#pragma once
// A statistical test of two Monte Carlo images (docs/decisions/0049-z-test.md): is
// their difference explained by their noise? Each pixel channel's difference over the
// standard deviation its variances give is a Z-score; its two-sided p-value is tested
// at the level that keeps the chance of any false rejection among all of them at
// `alpha` (Šidák's correction, exact for independent pixels).
#include <cstddef>
#include <cstdint>

#include "image/image.hpp"

namespace vkrt {

struct ZTestResult {
    double alpha = 0.0;          // the familywise level asked for
    std::size_t tests = 0;       // pixel channels tested
    double level = 0.0;          // each test's level: 1 - (1 - alpha)^(1 / tests)
    std::size_t rejected = 0;    // pixel channels whose p-value is below `level`
    double min_p = 1.0;          // the smallest p-value
    double worst_z = 0.0;        // its Z-score (signed: A above B is positive)
    std::uint32_t worst_x = 0, worst_y = 0, worst_channel = 0;
    bool rejects() const { return rejected > 0; }
};

// A with the variance of each of its pixel means `var_a`; B likewise, or a reference
// taken as exact (`var_b` null). A channel whose variances are infinite (a pixel of
// fewer than two samples) is not tested; one whose variances are both 0 is tested
// exactly: equal values pass, any difference is rejected (p = 0). The images must be
// of one size. With `p_values`, each pixel channel's p-value (1 where untested).
ZTestResult z_test(const Image& a, const Image& var_a, const Image& b, const Image* var_b, double alpha,
                   Image* p_values = nullptr);

}  // namespace vkrt

#include "image/display.hpp"

#include <algorithm>
#include <cmath>

namespace vkrt {

namespace {

// K. Narkowicz, "ACES Filmic Tone Mapping Curve" (2016): a rational fit,
// x (a x + b) / (x (c x + d) + e), of the ACES reference rendering and output
// transforms. It rises from 0 with a slight toe, passes 0.18 to about 0.27 and
// approaches 2.51 / 2.43 for bright values, which the clamp below takes to 1
// (from about 7.2).
float filmic(float x) {
    const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
    return x * (a * x + b) / (x * (c * x + d) + e);
}

}  // namespace

float display_value(float linear, const Display& display) {
    // exp2 of the exposure in double: exact for whole stops (and 0 changes nothing).
    const float scaled = float(double(linear) * std::exp2(display.exposure));
    // A NaN fails the comparison and shows black; from 1e4 on every curve gives 1
    // (and the filmic fit's products stay finite).
    const float x = scaled > 0.0f ? std::min(scaled, 1.0e4f) : 0.0f;
    return std::clamp(display.tonemap == Tonemap::Filmic ? filmic(x) : x, 0.0f, 1.0f);
}

}  // namespace vkrt

#pragma once
// The environment image as the kernel reads it (kernel/environment.glsl): its
// rotation, texels and sampling distribution, in words of texture_words.
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>

#include "scene/environment.hpp"

namespace vkrt {

// The rotation from world directions to the environment's frame, whose +y is `up`
// and which is turned by `rotation` degrees about it.
glm::dmat3 environment_frame(const Environment& env);

// The weight by which directions are drawn, per texel (x, y), rows from the top:
// the mean luminance over the texel's square of the bilinearly interpolated image
// (its 3 x 3 neighbourhood weighted 1/8, 3/4, 1/8 per axis; longitude wraps,
// latitude stops at the poles) times the sine of the row centre's angle from the
// pole.
std::vector<double> environment_weights(const Environment& env);

// Appends the environment's header, texels (times its intensity) and cumulative
// distributions to `words`, and returns where they start. Sets `sampled` to
// whether any direction carries weight (a black image is never sampled).
std::uint32_t append_environment(const Environment& env, std::vector<std::uint32_t>& words, bool& sampled);

}  // namespace vkrt

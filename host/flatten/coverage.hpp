#pragma once
// Which materials the kernel must test for coverage where a ray meets them
// (kernel/alpha.glsl): those whose alphaMode is not opaque, unless their opacity is
// the same everywhere and the mode makes that opaque: a mask whose alpha reaches its
// cutoff, or a blend of alpha 1, either without a colour texture or with one whose
// every texel has alpha 1 (exporters write BLEND for opaque textures often), and
// on no triangle with a vertex colour's alpha below 1.
#include <cstddef>
#include <vector>

#include "scene/scene.hpp"

namespace vkrt {

// Per material of `scene`: true where its coverage must be tested. Reads each colour
// texture's alpha once.
std::vector<bool> coverage_tested(const Scene& scene);

// Whether every texel of texture t has alpha 1.
bool fully_opaque(const Scene& scene, const TextureImage& t);

}  // namespace vkrt

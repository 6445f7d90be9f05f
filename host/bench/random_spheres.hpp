#pragma once
// The scenes `vkrt bench` generates for its sweeps: random spheres in a cube, seen
// whole by the camera, lit by one point light. Written as scene text that uses the
// loader's random_spheres generator, so they are the same family as
// scenes/gallery/h_random_spheres.json and are validated like every scene.
#include <cstdint>
#include <string>

namespace vkrt::bench {

// The scene text for `count` spheres. Radii shrink as count^(-1/3), so every count
// fills the same share of the cube: the image looks alike from 1 to 1M spheres and
// only the primitive count changes.
std::string random_spheres_scene(std::uint64_t count);

}  // namespace vkrt::bench

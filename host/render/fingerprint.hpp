#pragma once
// A fingerprint of everything that decides a sample's value: the flattened scene
// (camera, image size, seed, settings, materials, lights, primitives) and the
// kernel features. Partial files carry it, so that `vkrt merge` can refuse to add
// up renders of different scenes, sizes, seeds or settings.
#include <cstdint>
#include <string>

#include "flatten/flat_scene.hpp"

namespace vkrt {

// 64-bit FNV-1a over those bytes. The uniform grid is left out: it decides how
// rays find what they hit, not what they hit (tests/grid_image_test.cpp renders
// identical images with and without it), so partials rendered with --grid on, off,
// or on backends that choose differently still merge. So is DEFERRED_SPHERES, the
// order in which brute force tests spheres (tests/kernel_deferred_spheres_test.cpp).
std::uint64_t scene_fingerprint(const FlatScene& scene);

// Sixteen lower-case hex digits, as partial files store it.
std::string format_fingerprint(std::uint64_t fingerprint);

}  // namespace vkrt

#pragma once
// The table of a solid rough glass interface's single-scattering albedo
// E(mu, alpha, eta) that rough glass divides by (shaders/kernel/lobes/rough_glass.glsl):
// ROUGH_GLASS_ETA_KNOTS tables of GGX_TABLE_SIZE^2 knots, each laid out as the rough
// lobe's tables (ggx_albedo.hpp) without their means, as float bits, integrated from
// the kernel's own rough_crossing in the C++ reference. It follows the GGX tables
// (and the sheen's) in table_words. Where glass has a specular layer two more sets of
// tables follow it, laid out alike: D1 and DR, from which the layered interface's
// albedo follows (rough_glass.glsl rough_glass_layered_albedo).
#include <cstdint>
#include <vector>

namespace vkrt {

// Each built once per process on first use, on every core.
const std::vector<std::uint32_t>& rough_glass_albedo_table();
const std::vector<std::uint32_t>& rough_glass_layer_tables();

}  // namespace vkrt

#pragma once
// The table of a solid rough glass interface's single-scattering albedo
// E(mu, alpha, eta) that rough glass divides by (shaders/kernel/lobes/rough_glass.glsl):
// ROUGH_GLASS_ETA_KNOTS tables of GGX_TABLE_SIZE^2 knots, each laid out as the rough
// lobe's tables (ggx_albedo.hpp) without their means, as float bits, integrated from
// the kernel's own rough_crossing in the C++ reference. It follows the GGX tables
// (and the sheen's) in table_words.
#include <cstdint>
#include <vector>

namespace vkrt {

// Built once per process on first use, on every core.
const std::vector<std::uint32_t>& rough_glass_albedo_table();

}  // namespace vkrt

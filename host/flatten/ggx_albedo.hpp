#pragma once
// The tables of the rough lobe's single-scattering albedo that its multiple-scattering
// lobe reads (shaders/kernel/lobes/ggx_multiple.glsl): E(mu, alpha) at
// GGX_TABLE_SIZE^2 knots, mu fastest, then E_avg(alpha) at GGX_TABLE_SIZE knots, as
// float bits, computed from the kernel's own sampling and masking functions
// (ggx.glsl) in the C++ reference.
#include <cstdint>
#include <vector>

namespace vkrt {

// Built once per process on first use, on every core (about 30 ms on two).
const std::vector<std::uint32_t>& ggx_albedo_table();

}  // namespace vkrt

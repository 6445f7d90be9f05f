#pragma once
// The tables of the rough lobe's single-scattering albedos that the lobes beside it
// read (shaders/kernel/lobes/ggx_albedo.glsl): for E(mu, alpha), then for E_s(mu,
// alpha), GGX_TABLE_SIZE^2 knots, mu fastest, then the means over mu at
// GGX_TABLE_SIZE knots of alpha, as float bits, computed from the kernel's own
// sampling, masking and Fresnel functions (ggx.glsl, fresnel.glsl) in the C++ reference.
#include <cstdint>
#include <vector>

namespace vkrt {

// Built once per process on first use, on every core (about 30 ms on two).
const std::vector<std::uint32_t>& ggx_albedo_table();

// The mean 2 int_0^1 E(mu) mu dmu of one row of n knots (mu = (i / (n - 1))^2), as the
// kernel interpolates it: what a table's means hold.
float table_row_mean(const std::uint32_t* row, int n);

}  // namespace vkrt

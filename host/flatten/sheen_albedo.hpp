#pragma once
// The table of the sheen lobe's albedo that the lobes under it read
// (shaders/kernel/lobes/sheen.glsl): E_sheen(mu, alpha) with a colour of 1,
// GGX_TABLE_SIZE^2 knots laid out as each of the rough lobe's tables
// (ggx_albedo.hpp), then the means over mu, as float bits, integrated from the
// kernel's own sheen_value in the C++ reference. It follows those tables in
// table_words (the kernel's SHEEN_TABLE).
#include <cstdint>
#include <vector>

namespace vkrt {

// Built once per process on first use, on every core.
const std::vector<std::uint32_t>& sheen_albedo_table();

}  // namespace vkrt

#pragma once
// Specialization on the host: the scene's feature values folded into the kernel's
// SPIR-V, and the code they switch off removed, before the driver sees it.
//
// Why not leave it to the driver: lavapipe inlines every call of the kernel's
// functions before it drops the branches that the specialization constants switch
// off, and its passes then take seconds over the whole inlined kernel
// (docs/decisions/0012-spirv-specialization-on-host.md). The shader still declares
// its features as specialization constants, and the pipeline still gets them: a
// driver that is given the specialized module finds no constant left to set.
#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace vkrt::gpu {

// `spirv` with each specialization constant named in `values` (by constant_id) set
// to that boolean, every specialization constant frozen (one not named, at its
// default: the caller names them all), spec-constant expressions folded, and dead
// branches, functions and code removed, the calls that can be inlined inlined, and
// the copies that leaves cleaned up (SPIRV-Tools). Empty if SPIRV-Tools rejects
// the module, with the reason in `error`; the caller then uses `spirv` as it is.
// Changes whenever the passes above do, so that SPIR-V cached by an earlier recipe
// is not read back (gpu/pipeline_cache.hpp hashes it into the key).
inline constexpr std::uint32_t kSpecializationRecipe = 4;

std::vector<std::uint32_t> specialize_spirv(std::span<const std::uint32_t> spirv,
                                            const std::unordered_map<std::uint32_t, bool>& values, std::string& error);

}  // namespace vkrt::gpu

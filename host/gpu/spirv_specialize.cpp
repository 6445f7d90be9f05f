#include "gpu/spirv_specialize.hpp"

#include <string>
#include <vector>

#include <spirv-tools/optimizer.hpp>

namespace vkrt::gpu {

namespace {

// spirv-opt -O (SPIRV-Tools 2023.1, Optimizer::RegisterPerformancePasses) in its
// order, without --merge-return.
const std::vector<std::string> kPerformancePassesButMergeReturn = {
    "--wrap-opkill", "--eliminate-dead-branches", "--inline-entry-points-exhaustive",
    "--eliminate-dead-functions", "--eliminate-dead-code-aggressive", "--private-to-local",
    "--eliminate-local-single-block", "--eliminate-local-single-store", "--eliminate-dead-code-aggressive",
    "--scalar-replacement=100", "--convert-local-access-chains", "--eliminate-local-single-block",
    "--eliminate-local-single-store", "--eliminate-dead-code-aggressive", "--ssa-rewrite",
    "--eliminate-dead-code-aggressive", "--ccp", "--eliminate-dead-code-aggressive", "--loop-unroll",
    "--eliminate-dead-branches", "--redundancy-elimination", "--combine-access-chains", "--simplify-instructions",
    "--scalar-replacement=100", "--convert-local-access-chains", "--eliminate-local-single-block",
    "--eliminate-local-single-store", "--eliminate-dead-code-aggressive", "--ssa-rewrite",
    "--eliminate-dead-code-aggressive", "--vector-dce", "--eliminate-dead-inserts", "--eliminate-dead-branches",
    "--simplify-instructions", "--if-conversion", "--copy-propagate-arrays", "--reduce-load-size",
    "--eliminate-dead-code-aggressive", "--merge-blocks", "--redundancy-elimination", "--eliminate-dead-branches",
    "--merge-blocks", "--simplify-instructions",
};

}  // namespace

std::vector<std::uint32_t> specialize_spirv(std::span<const std::uint32_t> spirv,
                                            const std::unordered_map<std::uint32_t, bool>& values, std::string& error) {
    std::unordered_map<std::uint32_t, std::string> defaults;
    for (const auto& [id, on] : values) defaults.emplace(id, on ? "true" : "false");
    spvtools::Optimizer optimizer(SPV_ENV_VULKAN_1_1);
    optimizer.SetMessageConsumer([&](spv_message_level_t level, const char*, const spv_position_t&, const char* text) {
        if (level <= SPV_MSG_ERROR) error += (error.empty() ? "" : "; ") + std::string(text);
    });
    // The constants first, then what they decide: the branches on them, the
    // functions only those branches called, and the code that fed nothing else.
    // Then every call that can be inlined as it stands (a function with a return
    // before its end stays a call), and SPIRV-Tools' performance recipe (spirv-opt
    // -O) but for merge-return: the inlined kernel's local variables become SSA
    // values, constants propagate, redundant code goes. lavapipe's pipeline takes a
    // third of the time and half the memory on that module and renders as fast;
    // merge-return, which would inline the rest, made it render 20-30% slower
    // (decisions 0025, 0037). The result is cached, so SPIRV-Tools pays once per
    // feature set.
    optimizer.RegisterPass(spvtools::CreateSetSpecConstantDefaultValuePass(defaults))
        .RegisterPass(spvtools::CreateFreezeSpecConstantValuePass())
        .RegisterPass(spvtools::CreateFoldSpecConstantOpAndCompositePass())
        .RegisterPass(spvtools::CreateDeadBranchElimPass())
        .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass())
        .RegisterPass(spvtools::CreateAggressiveDCEPass())
        .RegisterPass(spvtools::CreateInlineExhaustivePass())
        .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass());
    if (!optimizer.RegisterPassesFromFlags(kPerformancePassesButMergeReturn)) {
        error = "SPIRV-Tools does not know one of the performance passes";
        return {};
    }
    std::vector<std::uint32_t> out;
    if (!optimizer.Run(spirv.data(), spirv.size(), &out)) {
        if (error.empty()) error = "SPIRV-Tools could not specialize the module";
        return {};
    }
    return out;
}

}  // namespace vkrt::gpu

#include "gpu/spirv_specialize.hpp"

#include <string>
#include <vector>

#include <spirv-tools/optimizer.hpp>

namespace vkrt::gpu {

namespace {

// After inlining, the copies that GLSL's by-value parameters left behind (some
// 6,800 function-local variables in the helmet-sized asset's kernel, each stored
// once or read in one block) are forwarded and removed, and the code they fed
// simplified: the first passes of spirv-opt -O (SPIRV-Tools 2023.1,
// Optimizer::RegisterPerformancePasses) without merge-return, and its clean-ups,
// but not its rewriting of the remaining variables into SSA values
// (--scalar-replacement, --ssa-rewrite and what needs them), which made lavapipe
// render 6-20% slower (decision 0037).
const std::vector<std::string> kCleanUpPasses = {
    "--wrap-opkill", "--eliminate-dead-branches", "--inline-entry-points-exhaustive",
    "--eliminate-dead-functions", "--eliminate-dead-code-aggressive", "--private-to-local",
    "--eliminate-local-single-block", "--eliminate-local-single-store", "--eliminate-dead-code-aggressive",
    "--convert-local-access-chains", "--eliminate-local-single-block", "--eliminate-local-single-store",
    "--eliminate-dead-code-aggressive", "--eliminate-dead-branches", "--simplify-instructions", "--vector-dce",
    "--eliminate-dead-inserts", "--eliminate-dead-code-aggressive", "--merge-blocks",
    "--redundancy-elimination", "--eliminate-dead-code-aggressive",
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
    // before its end stays a call: merge-return, which would inline the rest, made
    // lavapipe render slower, decision 0025), and the copies the inlining left
    // behind cleaned up (kCleanUpPasses): lavapipe then creates the pipeline in half
    // the time and two thirds of the memory, and renders as fast (decision 0037).
    // The result is cached, so SPIRV-Tools pays once per feature set.
    optimizer.RegisterPass(spvtools::CreateSetSpecConstantDefaultValuePass(defaults))
        .RegisterPass(spvtools::CreateFreezeSpecConstantValuePass())
        .RegisterPass(spvtools::CreateFoldSpecConstantOpAndCompositePass())
        .RegisterPass(spvtools::CreateDeadBranchElimPass())
        .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass())
        .RegisterPass(spvtools::CreateAggressiveDCEPass())
        .RegisterPass(spvtools::CreateInlineExhaustivePass())
        .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass());
    if (!optimizer.RegisterPassesFromFlags(kCleanUpPasses)) {
        error = "SPIRV-Tools does not know one of the clean-up passes";
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

#include "gpu/spirv_specialize.hpp"

#include <spirv-tools/optimizer.hpp>

namespace vkrt::gpu {

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
    // before its end stays a call): lavapipe's pipeline takes half the time on the
    // inlined module and runs as fast (decision 0025); the result is cached, so
    // SPIRV-Tools pays once per feature set.
    optimizer.RegisterPass(spvtools::CreateSetSpecConstantDefaultValuePass(defaults))
        .RegisterPass(spvtools::CreateFreezeSpecConstantValuePass())
        .RegisterPass(spvtools::CreateFoldSpecConstantOpAndCompositePass())
        .RegisterPass(spvtools::CreateDeadBranchElimPass())
        .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass())
        .RegisterPass(spvtools::CreateAggressiveDCEPass())
        .RegisterPass(spvtools::CreateInlineExhaustivePass())
        .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass());
    std::vector<std::uint32_t> out;
    if (!optimizer.Run(spirv.data(), spirv.size(), &out)) {
        if (error.empty()) error = "SPIRV-Tools could not specialize the module";
        return {};
    }
    return out;
}

}  // namespace vkrt::gpu

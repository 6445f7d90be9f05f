#pragma once
// The float probe's CPU column: shaders/probe/float_ops.glsl compiled as C++ with GLM,
// under the reference backend's flags (-ffp-contract=off), so the column says what
// `--backend cpu` computes.
#include <vector>

#include <glm/vec4.hpp>

#include "probe/float_cases.hpp"

namespace vkrt::probe {

// One result per case, in order.
std::vector<glm::vec4> run_cpu_float_probe(const std::vector<ProbeCase>& cases);

}  // namespace vkrt::probe

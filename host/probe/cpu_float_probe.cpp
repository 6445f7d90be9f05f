#include "probe/cpu_float_probe.hpp"

#include "kernel/kernel.hpp"

namespace vkrt::probe {

namespace {

using namespace glm;

// Derived from the reference kernel so that float_ops.glsl's calls of unit_vector and
// rng_next are the kernel's own (ray.glsl, rng.glsl), as they are in float_probe.comp.
#define precise
struct CpuProbe : kernel::Kernel {
#include "probe/float_ops.glsl"
};
#undef precise

}  // namespace

std::vector<glm::vec4> run_cpu_float_probe(const std::vector<ProbeCase>& cases) {
    CpuProbe probe;
    std::vector<glm::vec4> results;
    results.reserve(cases.size());
    for (const ProbeCase& c : cases) {
        results.push_back(probe.float_op(c.op, c.arg));
    }
    return results;
}

}  // namespace vkrt::probe

// libFuzzer harness: NFF scenes, plain or gzipped (load_scene on a .nff file).
// Built with -DVKRT_FUZZ=ON and run by scripts/fuzz (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>

#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return vkrt::fuzz::run_one(vkrt::fuzz::Loader::Nff, data, size);
}

// libFuzzer harness: MTL material libraries (named by a fixed OBJ mesh).
// Built with -DVKRT_FUZZ=ON and run by scripts/fuzz (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>

#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return vkrt::fuzz::run_one(vkrt::fuzz::Loader::Mtl, data, size);
}

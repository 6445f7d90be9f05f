// libFuzzer harness: glTF 2.0 files, .glb or .gltf by their first bytes (load_scene).
// Built with -DVKRT_FUZZ=ON and run by scripts/fuzz (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>

#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return vkrt::fuzz::run_one(vkrt::fuzz::Loader::Gltf, data, size);
}

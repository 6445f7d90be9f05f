// tinygltf's implementation compiled into the fuzz build, with the fuzzer's
// coverage and the sanitizers, in place of Debian's uninstrumented shared
// library: the glTF harness then sees inside tinygltf's JSON and .glb chunk
// parsing and its buffer and accessor checks, where a malformed file is met.
// The header is the library's own source, of the same package, and it is built
// as Debian builds it: no TINYGLTF_* option, nlohmann json, stb_image and
// stb_image_write from libstb (whose implementation stays in its library; vkrt
// installs its own image loader and writes no glTF, so stb's code is not run).
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>

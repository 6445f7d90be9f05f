#pragma once
// One fuzz input loaded the way a file of its kind is: the entry point that the
// fuzz harnesses (tests/fuzz/*_fuzz.cpp) and the regression test
// (tests/fuzz/regression_test.cpp) share, so that a crash found by one is replayed
// by the other exactly.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace vkrt::fuzz {

enum class Loader { Json, Nff, Obj, Mtl, Gltf };

// "json", "nff", "obj", "mtl", "gltf": the loader's directory under tests/fuzz/corpus/ and
// tests/fuzz/regressions/.
std::string_view loader_name(Loader loader);

// A directory the inputs are written to. It also holds a small valid mesh.obj
// and mesh.mtl, so that JSON scenes and OBJ files naming them get past the
// reference and on into the mesh and its materials.
class Scratch {
public:
    explicit Scratch(std::filesystem::path dir);

    const std::filesystem::path& dir() const { return dir_; }

    // Loads `bytes` as the loader's input: JSON and NFF as scene files (NFF read
    // from disk, so gzip is detected as for any file), OBJ as a mesh (geometry,
    // then with its MTL materials), MTL as the library of a fixed one-triangle
    // OBJ, glTF as a .glb file when it starts with the binary magic "glTF", else as
    // a .gltf file (whose buffer mesh.bin, an octahedron, lies beside it). Returns
    // the SceneError's message, or nothing when the input loaded.
    // Any other exception is a finding and propagates.
    std::optional<std::string> load(Loader loader, std::string_view bytes) const;

private:
    std::filesystem::path dir_;
};

}  // namespace vkrt::fuzz

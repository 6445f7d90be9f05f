#pragma once
// The scenes `vkrt bench` generates for its sweeps: random spheres in a cube, seen
// whole by the camera, lit by one point light. Written as scene files that use the
// loader's random_spheres generator, so they are the same family as
// scenes/gallery/h_random_spheres.json and load through the path every scene takes.
#include <cstdint>
#include <filesystem>
#include <string>

namespace vkrt::cli {

// The scene text for `count` spheres. Radii shrink as count^(-1/3), so every count
// fills the same share of the cube: the image looks alike from 1 to 1M spheres and
// only the primitive count changes.
std::string random_spheres_scene(std::uint64_t count);

// A directory for generated scenes, removed with everything in it when it goes.
class TempSceneDir {
public:
    TempSceneDir();
    ~TempSceneDir();
    TempSceneDir(const TempSceneDir&) = delete;
    TempSceneDir& operator=(const TempSceneDir&) = delete;

    // Writes `text` to a file called `name` in the directory and returns its path.
    std::filesystem::path write(const std::string& name, const std::string& text) const;

private:
    std::filesystem::path dir_;
};

}  // namespace vkrt::cli

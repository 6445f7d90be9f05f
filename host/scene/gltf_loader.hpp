#pragma once
// glTF 2.0 files (.gltf with its buffers, or .glb) as scenes to render directly:
// the default scene's node hierarchy, its triangle meshes and their materials, its
// first camera and its KHR_lights_punctual lights, rendered in global mode
// (docs/gltf.md has what is read, what is not, and the defaults).
#include <filesystem>
#include <functional>
#include <vector>

#include "scene/scene.hpp"
#include "scene/transform.hpp"

namespace vkrt {

// Throws SceneError, naming the file and the element (e.g.
// "meshes[2].primitives[0].indices"), for anything it cannot read. What it reads but
// cannot render as the file means (textures, metallic materials, light ranges, ...)
// becomes one warning per kind in Scene::warnings.
Scene load_gltf_scene(const std::filesystem::path& file);

// The view of a file without a camera, as glTF viewers frame a model: from its front
// (+z), looking down -z with +y up, 40 degrees high, the sphere around the triangles'
// bounding box filling the narrower of the view's angles for the camera's width and
// height, whatever the model's size or offset. Sets camera.framed.
void frame_scene(Scene& scene);

// The file's meshes with their materials, and its lights, placed by each of
// `placements` (at least one) and appended to `scene` (a JSON scene's "gltf" and
// "instance" objects); its camera and the render defaults are not taken. The file
// is read, and its materials and textures made, once. `after_first`, if given, is
// told how many triangles the first placement added before the others are made.
void add_gltf(const std::filesystem::path& file, const std::vector<Transform>& placements, Scene& scene,
              const std::function<void(std::size_t triangles)>& after_first = {});

}  // namespace vkrt

#pragma once
// The scene format's "instance" object (docs/scene-format.md): one OBJ mesh or glTF
// file placed by many transforms. The file is read once (its materials and textures
// made once); each placement is then a copy of its triangles.
#include "scene/json_reader.hpp"
#include "scene/material_lookup.hpp"
#include "scene/scene.hpp"

namespace vkrt {

// {"type": "instance", "object": O, "transforms": [T, ...]}: O is a "mesh" or a
// "gltf" object, placed by each T (a "transform" object) after O's own "transform",
// if it has one. Fails, naming the field, on another kind of object, an empty or
// overlong list, a placement that flattens the object, and more copied triangles
// than limits::kMaxInstancedTriangles.
void read_instance(const json::Node& n, const MaterialLookup& material, Scene& scene);

}  // namespace vkrt

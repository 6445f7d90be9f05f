#pragma once
// Wavefront OBJ meshes: the "mesh" object of the scene format
// (docs/scene-format.md). Only geometry is read: positions, normals and faces.
// The OBJ's materials (mtllib/usemtl), texture coordinates, groups, smoothing
// groups, lines and points are ignored; the scene object's "material" applies.
#include <filesystem>

#include "scene/indexed_mesh.hpp"
#include "scene/json_reader.hpp"
#include "scene/material_lookup.hpp"
#include "scene/scene.hpp"

namespace vkrt {

// Reads an OBJ file; polygons become triangle fans (v0, vk, vk+1). Throws
// SceneError "<file>: <what>" or "<file>:<line>: <what>" on a file that cannot
// be read, a malformed or non-finite number, a face with fewer than 3 or more
// than 255 vertices, an index out of range, or a file without faces.
IndexedMesh load_obj(const std::filesystem::path& file);

// {"type": "mesh", "file", "material", "smooth", "transform"}: appends the mesh's
// triangles to scene.triangles. "file" is relative to the scene file's directory.
void read_mesh(const json::Node& n, const MaterialLookup& material, Scene& scene);

}  // namespace vkrt

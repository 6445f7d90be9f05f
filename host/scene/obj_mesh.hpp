#pragma once
// Wavefront OBJ meshes: the "mesh" object of the scene format
// (docs/scene-format.md): positions, normals, texture coordinates and faces, and the
// materials of the file's MTL libraries (usemtl) where the scene object gives no
// "material". Groups, smoothing groups, lines and points are ignored.
#include <filesystem>
#include <string>
#include <vector>

#include "scene/indexed_mesh.hpp"
#include "scene/json_reader.hpp"
#include "scene/material_lookup.hpp"
#include "scene/scene.hpp"

namespace vkrt {

// Reads an OBJ file; polygons become triangle fans (v0, vk, vk+1). Throws
// SceneError "<file>: <what>" or "<file>:<line>: <what>" on a file that cannot
// be read, a malformed or non-finite number (v, vn, vt), a face with fewer than 3
// or more than 255 vertices, a face index that is 0 or no integer, an index out of
// range, or a file without faces.
IndexedMesh load_obj(const std::filesystem::path& file);

// The same with the materials of the file's MTL libraries (Kd, Ks, Ns, Ke; read
// relative to the OBJ's directory): every face gets its usemtl's, and a face
// without one is an error. What the materials ask for that vkrt cannot show
// (textures, transparency) is added to `warnings`, once per material and feature.
IndexedMesh load_obj_with_materials(const std::filesystem::path& file, std::vector<std::string>& warnings);

// {"type": "mesh", "file", "material", "smooth", "transform"}: appends the mesh's
// triangles to scene.triangles. "file" is relative to the scene file's directory.
void read_mesh(const json::Node& n, const MaterialLookup& material, Scene& scene);

// Such an object's OBJ file, read, with its materials added to the scene, ready to
// be placed by add_mesh (indexed_mesh.hpp) once or many times; "transform" is left
// to the caller.
struct MeshObject {
    IndexedMesh mesh;
    MeshOptions options;
};
MeshObject read_mesh_object(const json::Node& n, const MaterialLookup& material, Scene& scene);

}  // namespace vkrt

#pragma once
// What the readers of a JSON scene's primitives (host/scene/shapes/<name>.cpp,
// read_shape) share: the materials by name, and the flaws of a file they put up with,
// counted for one warning each rather than one per primitive.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/json_reader.hpp"
#include "scene/material_lookup.hpp"

namespace vkrt {

struct ShapeReader {
    MaterialLookup material;  // a material's name to its index in Scene::materials

    // Triangles of zero area, which are dropped, and zero vertex normals, for which the
    // face normal stands in (as in meshes, indexed_mesh.cpp).
    std::size_t zero_area = 0;
    std::string first_zero_area{};  // the JSON path of the first
    std::size_t zero_normals = 0;  // triangles with one or more
    std::string first_zero_normal{};

    // The index of the material an object names in its "material".
    std::uint32_t material_of(const json::Node& object) const { return material(object.required("material")); }

    // One warning per kind of flaw met in `file`, with how many and where the first is.
    void warn(const std::string& file, std::vector<std::string>& warnings) const;
};

}  // namespace vkrt

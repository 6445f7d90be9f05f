#pragma once
// How object readers outside the JSON loader turn a material name into its index.
#include <cstdint>
#include <functional>

#include "scene/json_reader.hpp"

namespace vkrt {

// Given a node holding a material's name, returns its index in Scene::materials,
// or fails at that node, listing the defined names. The JSON loader owns the name
// table; readers in other files (meshes, generators) get this instead of it.
using MaterialLookup = std::function<std::uint32_t(const json::Node& name)>;

}  // namespace vkrt

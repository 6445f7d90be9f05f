// Every array the kernel reads, declared once. From this list kernel/loads.glsl
// defines the loaders the kernel calls (load_sphere(i), ...), FlatScene
// (host/flatten/flat_scene.hpp) holds one std::vector per array, the reference
// backend's Kernel (host/kernel/kernel.hpp) a span of each, and the Vulkan backend
// packs them all into one scene buffer (host/gpu/scene_pack.hpp), each starting at
// the offset render.comp's `<name>_base()` returns (push constants, by id).
//
//   SCENE_ARRAY(id, name, Element, load, format)
//
// id: dense, 0 to count - 1: the fixed arrays 0 to 7, and each kind of primitive of
// shapes/kinds.glsl, whose arrays follow the materials, 8 + its ID. (An id is where
// the array's start sits among render.comp's push constants; the order of the lines
// is the order in which the Vulkan backend packs them.)
// format: rgba32ui, one 16-byte texel per vec4/uvec4 member of a layout.glsl struct
// (Element_FROM_TEXELS says how to assemble it), or r32ui, one uint per element. The
// r32ui arrays come last. The file that includes this one defines SCENE_ARRAY; it is
// undefined at the end.
SCENE_ARRAY(0, materials, Material, load_material, rgba32ui)
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    SCENE_ARRAY((8 + ID), names, Name, load_##name, rgba32ui)
#include "shapes/kinds.glsl"
SCENE_ARRAY(1, lights, Light, load_light, rgba32ui)
SCENE_ARRAY(2, emitters, Emitter, load_emitter, rgba32ui)          // empty without area lights
SCENE_ARRAY(3, textures, Texture, load_texture, rgba32ui)          // empty without textures
SCENE_ARRAY(4, grid_nodes, uint, load_grid_node, r32ui)            // cells + 1 offsets into grid_refs;
SCENE_ARRAY(5, grid_refs, uint, load_ref, r32ui)                   // both empty without the grid
SCENE_ARRAY(6, texture_words, uint, load_texture_word, r32ui)      // the textures' texels (Texture)
SCENE_ARRAY(7, table_words, uint, load_table_word, r32ui)          // the sRGB table, the environment

#undef SCENE_ARRAY

// Every array the kernel reads, declared once. From this list kernel/loads.glsl
// defines the loaders the kernel calls (load_sphere(i), ...), FlatScene
// (host/flatten/flat_scene.hpp) holds one std::vector per array, the reference
// backend's Kernel (host/kernel/kernel.hpp) a span of each, and the Vulkan backend
// packs them all into one scene buffer (host/gpu/scene_pack.hpp), each starting at
// the offset render.comp's `<name>_base()` returns (push constants, by id).
//
//   SCENE_ARRAY(id, name, Element, load, format)
//
// id: 0, 1, 2, ... in order.
// format: rgba32ui, one 16-byte texel per vec4/uvec4 member of a layout.glsl struct
// (Element_FROM_TEXELS says how to assemble it), or r32ui, one uint per element. The
// r32ui arrays come last. The file that includes this one defines SCENE_ARRAY; it is
// undefined at the end.
SCENE_ARRAY(0, materials, Material, load_material, rgba32ui)
SCENE_ARRAY(1, spheres, Sphere, load_sphere, rgba32ui)
SCENE_ARRAY(2, triangles, Triangle, load_triangle, rgba32ui)
SCENE_ARRAY(3, rings, Ring, load_ring, rgba32ui)
SCENE_ARRAY(4, cylinders, Cylinder, load_cylinder, rgba32ui)
SCENE_ARRAY(5, lights, Light, load_light, rgba32ui)
SCENE_ARRAY(6, emitters, Emitter, load_emitter, rgba32ui)          // empty without area lights
SCENE_ARRAY(7, textures, Texture, load_texture, rgba32ui)         // empty without textures
SCENE_ARRAY(8, grid_nodes, uint, load_grid_node, r32ui)           // cells + 1 offsets into grid_refs;
SCENE_ARRAY(9, grid_refs, uint, load_ref, r32ui)                   // both empty without the grid
SCENE_ARRAY(10, texture_words, uint, load_texture_word, r32ui)     // the textures' texels (Texture)
SCENE_ARRAY(11, table_words, uint, load_table_word, r32ui)         // the sRGB table, the environment

#undef SCENE_ARRAY

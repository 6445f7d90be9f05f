// Every buffer of the kernel, declared once. From this list render.comp declares its
// images, kernel/loads.glsl defines the loaders the kernel calls, FlatScene
// (host/flatten/flat_scene.hpp) holds one array per scene buffer, host/gpu numbers the
// descriptor set and picks each view's format, and the reference backend's Kernel
// (host/kernel/kernel.hpp) holds a span of each scene array. On the device each is a
// storage texel buffer (docs/decisions/0001-texel-buffers.md), image <name>_texels.
//
//   PARAMS_BUFFER(binding, name)                        the one Params (kernel/params.glsl)
//   SCENE_BUFFER(binding, name, Element, load, format)  read only: an array of the flattened
//                                                       scene, read by the kernel as load(i)
//   OUTPUT_BUFFER(binding, name, Element, format)       read and written: one Element per pixel
//
// format: rgba32ui, one texel per vec4/uvec4 member of a layout.glsl struct (which
// says how to assemble it: Element_FROM_TEXELS), or r32ui, one uint per texel.
// Bindings are dense: 0, 1, 2, ... in order. The file that includes this one defines
// the macros it needs; the others expand to nothing, and all three are undefined at
// the end.
#ifndef PARAMS_BUFFER
#define PARAMS_BUFFER(binding, name)
#endif
#ifndef SCENE_BUFFER
#define SCENE_BUFFER(binding, name, Element, load, format)
#endif
#ifndef OUTPUT_BUFFER
#define OUTPUT_BUFFER(binding, name, Element, format)
#endif

PARAMS_BUFFER(0, params)
SCENE_BUFFER(1, materials, Material, load_material, rgba32ui)
SCENE_BUFFER(2, spheres, Sphere, load_sphere, rgba32ui)
SCENE_BUFFER(3, triangles, Triangle, load_triangle, rgba32ui)
SCENE_BUFFER(4, rings, Ring, load_ring, rgba32ui)
SCENE_BUFFER(5, cylinders, Cylinder, load_cylinder, rgba32ui)
SCENE_BUFFER(6, lights, PointLight, load_light, rgba32ui)
SCENE_BUFFER(7, emitters, Emitter, load_emitter, rgba32ui)             // empty without area lights
SCENE_BUFFER(8, grid_cell_starts, uint, load_cell_start, r32ui)        // cells + 1 offsets into grid_refs;
SCENE_BUFFER(9, grid_refs, uint, load_ref, r32ui)                      // both empty without the grid
OUTPUT_BUFFER(10, sums, PixelSum, rgba32ui)
OUTPUT_BUFFER(11, counters, Counters, rgba32ui)

#undef OUTPUT_BUFFER
#undef SCENE_BUFFER
#undef PARAMS_BUFFER

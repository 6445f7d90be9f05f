// The feature set: one entry per part of the kernel that a scene may not need.
// Each side defines FEATURE(id, NAME) before including this file:
//   GLSL   -> a boolean specialization constant with constant_id = id (default true),
//   kernel -> a bool member of the reference Kernel struct,
//   host   -> the Feature enum and its names (host/scene/features.hpp).
// Ids are dense, 0 to count - 1 (host/scene/features.hpp checks).
// A feature that is false is compiled out of the pipeline by the driver, and the
// buffers only it reads are neither built nor uploaded.
FEATURE(0, HAS_SPHERES)
FEATURE(1, HAS_TRIANGLES)
FEATURE(2, HAS_SMOOTH_NORMALS)
FEATURE(3, HAS_POINT_LIGHTS)
FEATURE(4, HAS_SHADOWS)
FEATURE(5, HAS_SPECULAR)
FEATURE(6, HAS_AMBIENT)
FEATURE(7, HAS_EMISSION)
FEATURE(8, HAS_JITTER)
FEATURE(9, HAS_GRID)
FEATURE(10, HAS_RINGS)
FEATURE(11, HAS_CYLINDERS)
FEATURE(12, HAS_AREA_LIGHTS)
FEATURE(13, HAS_REFLECTION)   // mirror rays (material reflect)
FEATURE(14, HAS_REFRACTION)   // refraction rays, and the reflection rays of glass (material transmit)
FEATURE(15, HAS_GLOBAL)       // global illumination (global.glsl) instead of the local ray tree
// With HAS_GRID, the kinds the grid lists. A kind with few primitives is left out of
// the grid and tested once per ray instead (host/scene/scene_gpu.cpp, docs/grid.md).
FEATURE(16, GRID_SPHERES)
FEATURE(17, GRID_TRIANGLES)
FEATURE(18, GRID_RINGS)
FEATURE(19, GRID_CYLINDERS)
// With HAS_GRID: some primitives of the listed kinds are loose, tested once per ray
// instead of listed in cells, because their boxes would stretch the grid's
// (host/accel/grid.cpp, choose_loose). Their references come before cell 0's.
FEATURE(20, GRID_LOOSE)

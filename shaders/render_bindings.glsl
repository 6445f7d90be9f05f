// The descriptor set of render.comp and the choices made per device, declared once:
// render.comp declares each line, host/gpu/vulkan_pipeline.cpp builds the set layout
// and the specialization from them.
//
//   TEXEL_BINDING(binding, name, format, access)  a storage texel buffer, image `name`
//   STORAGE_BINDING(binding, name, access)        a storage buffer, uvec4 `name.texels[]`
//   UNIFORM_BINDING(binding, name)                a uniform buffer, uvec4 `name.texels[]`
//   DEVICE_CHOICE(constant_id, NAME)              a boolean specialization constant
//
// Every binding is always bound. The device choices pick which ones the shader
// reads (host/gpu/data_paths.cpp decides); the others get a small dummy buffer.
// Counted against the guaranteed minimums per stage, the set needs 4 storage images
// (texel buffers count as such; minimum 4), 2 storage buffers (4) and 1 uniform
// buffer (12).
#ifndef TEXEL_BINDING
#define TEXEL_BINDING(binding, name, format, access)
#endif
#ifndef STORAGE_BINDING
#define STORAGE_BINDING(binding, name, access)
#endif
#ifndef UNIFORM_BINDING
#define UNIFORM_BINDING(binding, name)
#endif
#ifndef DEVICE_CHOICE
#define DEVICE_CHOICE(constant_id, name)
#endif

TEXEL_BINDING(0, params_texels, rgba32ui, readonly)   // Params, PARAM_TEXELS texels
UNIFORM_BINDING(1, params_uniform)                    // the same, as a uniform buffer
TEXEL_BINDING(2, scene_texels, rgba32ui, readonly)    // the scene buffer (scene_pack.hpp)
TEXEL_BINDING(3, scene_words, r32ui, readonly)        // its r32ui arrays, from scene_words_start()
TEXEL_BINDING(4, pixel_texels, rgba32ui, restrict)    // PIXEL_TEXELS per pixel of the slab
STORAGE_BINDING(5, scene_storage, readonly)           // the scene buffer as a storage buffer
STORAGE_BINDING(6, pixel_storage, restrict)           // the pixels as a storage buffer

// The device choices' constant ids start at 64, clear of the features' (0 up).
// Scene and pixels in storage buffers instead of texel buffers: where a texel
// buffer would be too small for them (maxTexelBufferElements; at least 65,536 texels).
DEVICE_CHOICE(64, SCENE_IN_STORAGE_BUFFERS)
// Params from the uniform buffer instead of a texel buffer: on GPUs, where uniform
// loads take the constant path (docs/decisions/0001-texel-buffers.md says why not on
// lavapipe).
DEVICE_CHOICE(65, PARAMS_IN_UNIFORM_BUFFER)

#undef DEVICE_CHOICE
#undef UNIFORM_BINDING
#undef STORAGE_BINDING
#undef TEXEL_BINDING

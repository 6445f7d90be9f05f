// The kernel reads the scene through these loaders and only these: one per array of
// kernel/arrays.glsl (load_sphere(i), load_ref(i), ...), over the same arrays on both
// hosts. Each host defines LOAD_ELEMENT(Element, name, i) before including the kernel:
// render.comp assembles element i from the texels of the scene buffer
// (Element_FROM_TEXELS, layout.glsl), the C++ Kernel reads its span.
#define SCENE_ARRAY(id, name, Element, load, format) \
    Element load(uint i) { return LOAD_ELEMENT(Element, name, i); }
#include "arrays.glsl"

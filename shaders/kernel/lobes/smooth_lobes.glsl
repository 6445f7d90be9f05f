// The smooth lobes, one line a lobe: those that next-event estimation and multiple
// importance sampling weigh, sampled together as a mixture (bsdf.glsl). The lobe
// `name` lives in lobes/<name>.glsl, which defines
//
//   Type name_lobe(Material m, float cos_o)   its record for a hit seen from cos_o,
//                                             with a member `float weight`: its share
//                                             of the mixture (0: not drawn)
//   bool name_present(Type l)                 whether name_eval can be nonzero
//   vec3 name_eval(Type l, vec3 n, vec3 wo, vec3 wi)                  the BSDF value
//   float name_pdf(Type l, Basis frame, vec3 wo, vec3 wi, uint hemisphere)
//   vec3 name_sample(Type l, Basis frame, vec3 wo, uint hemisphere, float u1, float u2)
//
// with wo, wi unit and pointing away from the surface, n (frame.n) the shading normal
// on wo's side. A new lobe is its file, an #include in all.glsl and a line here; its
// fields go in material_fields.glsl. Ids are dense from 0, in this order, which is
// also the order of the mixture's sums.
//
// No two lobe records may have the same member types in the same order: SPIRV-Tools'
// --simplify-instructions (host/gpu/spirv_specialize.cpp) takes two such struct types
// for one and writes invalid SPIR-V, which the validation layer of the Vulkan tests
// reports. Order the members differently, as ggx.glsl does.
//
//   SMOOTH_LOBE(id, name, Type, FEATURE)
//
// FEATURE: the feature without which the lobe is always empty (true: none), written
// into every test of the mixture so that the lobes a scene lacks fold away at once
// when the pipeline is specialized.
//
// The file that includes this one defines SMOOTH_LOBE; it is undefined at the end.
SMOOTH_LOBE(0u, diffuse, DiffuseLobe, true)            // Lambertian (diffuse.glsl)
SMOOTH_LOBE(1u, glossy, GlossyLobe, HAS_SPECULAR)      // normalized Phong (glossy.glsl)
SMOOTH_LOBE(2u, ggx, GgxLobe, HAS_MICROFACET)          // GGX microfacet reflection (ggx.glsl)
SMOOTH_LOBE(3u, ggx_multiple, GgxMultipleLobe, HAS_MICROFACET)  // what ggx loses between microfacets (ggx_multiple.glsl)
SMOOTH_LOBE(4u, coat, CoatLobe, HAS_COAT)              // a clear coat over all the others (coat.glsl)
SMOOTH_LOBE(5u, sheen, SheenLobe, HAS_SHEEN)           // sheen, under the coat and over the rest (sheen.glsl)

#undef SMOOTH_LOBE

// Coverage (HAS_ALPHA): glTF's alphaMode, on triangles and quads, the shapes with
// texture coordinates. A surface's opacity at a point is its material's `alpha` times
// its colour texture's alpha there (bilinear, as the colour) times its vertex
// colours' (vertex_data.glsl):
//   ALPHA_MASK   the surface is there where the opacity reaches alpha_cutoff and absent
//                elsewhere: leaves, fences, decals;
//   ALPHA_BLEND  the surface is there with probability equal to the opacity, decided
//                afresh for every ray (stochastic transparency): a path goes through it
//                with probability 1 - opacity, and a shadow ray is blocked with
//                probability opacity, so on average the light through is the blend.
// The test is made where the traversal meets the surface (shapes/triangle.glsl), for
// every ray, shadow rays included, so a cut-out surface casts the shadow of its
// cut-outs. Only triangles whose material is not opaque carry TRIANGLE_ALPHA_TESTED
// (the host decides: host/flatten/flat_scene.cpp), and only they pay for it.
//
// BLEND's decision must be the same each time one ray meets one triangle (the grid
// may test a triangle in every cell it spans), and independent between rays: it is a
// hash of the ray's key and the triangle's index. A ray's key hashes the sample's
// pixel, index and seed with the number of rays the sample traced before it, so both
// backends, and any split of the samples, decide alike. The salt keeps these hashes
// apart from the hash sampler's, which hashes the same three numbers with a slot.

const uint ALPHA_SALT = 0xa1fa5a17u;

uvec4 g_alpha_sample = uvec4(0u);  // pixel, sample index, seed ^ ALPHA_SALT, rays traced so far
uvec4 g_alpha_ray = uvec4(0u);     // the key of the ray being traced

// At the start of a sample.
void alpha_start_sample(Rng rng) {
    g_alpha_sample = uvec4(rng.key.x, rng.key.y, rng.key.z ^ ALPHA_SALT, 0u);
}

// At the start of every trace, closest hit or shadow ray.
void alpha_start_ray() {
    g_alpha_ray = pcg4d(g_alpha_sample);
    g_alpha_sample.w += 1u;
}

// The opacity of material m at texture coordinates uv (before the material's
// transform) where the vertex colours' alpha is vertex_alpha: alpha times the colour
// texture's alpha times vertex_alpha.
float surface_opacity(Material m, vec2 uv, float vertex_alpha) {
    float opacity = m.alpha * vertex_alpha;
    if (HAS_TEXTURES && m.color_map != 0u) {
        opacity *= texture_bilinear(load_texture(m.color_map - 1u), material_uv(m, uv)).a;
    }
    return opacity;
}

// The fraction of the light that m emits at uv which leaves the surface there: 0 or
// 1 for a mask, the opacity for a blend. Next-event estimation weighs a point it draws
// by it; a ray that meets the emitter sees its full emission, having met it with this
// probability (alpha_stops_ray).
float surface_coverage(Material m, vec2 uv, float vertex_alpha) {
    float opacity = surface_opacity(m, uv, vertex_alpha);
    if (m.alpha_mode == ALPHA_MASK) {
        return opacity >= m.alpha_cutoff ? 1.0f : 0.0f;
    }
    return m.alpha_mode == ALPHA_BLEND ? opacity : 1.0f;
}

// The alpha of triangle tri's (index `index`) vertex colours at weights bary: 1 for
// a triangle without them.
float vertex_alpha(Triangle tri, uint index, vec2 bary) {
    return HAS_VERTEX_COLORS && (tri.meta.y & TRIANGLE_COLORS) != 0u ? vertex_color(index, bary).a : 1.0f;
}

// Whether the ray being traced stops at triangle tri (index `index`) where it meets
// it at weights bary and texture coordinates uv.
bool alpha_stops_ray(Triangle tri, uint index, vec2 bary, vec2 uv) {
    Material m = load_material(tri.meta.x);
    float opacity = surface_opacity(m, uv, vertex_alpha(tri, index, bary));
    bool stops;
    if (m.alpha_mode == ALPHA_MASK) {
        stops = opacity >= m.alpha_cutoff;
    } else {
        stops = unit_float(pcg4d(uvec4(g_alpha_ray.x, g_alpha_ray.y, g_alpha_ray.z, index)).x) < opacity;
    }
    return stops;
}

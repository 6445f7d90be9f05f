// Normal maps (HAS_NORMAL_MAPS): a material's texture of tangent-space normals bends
// the shading normal of triangles and quads, and a clear coat's own map the normal
// its coat lies on (coat_normal). The map holds glTF's encoding c of a
// tangent-space normal, decoded here as glTF defines it, after filtering (which
// commutes with the affine map): (2 c - 1) * (scale, scale, 1) with the texture's
// scale (Texture.decode.x), +x toward +u, +y up the image (toward -v, since v runs
// down), +z along the surface normal.
//
// The tangent frame is the file's where a triangle has vertex tangents (glTF's
// TANGENT, HAS_TANGENTS, vertex_data.glsl): the tangent interpolated and made
// perpendicular to the interpolated shading normal (Gram-Schmidt), the bitangent
// cross(n, t) times the tangent's sign w, as glTF defines it. Elsewhere it is derived
// per triangle (docs/decisions/0032-normal-maps.md): the tangent is dp/du of the
// triangle's texture coordinates (after the material's transform), made
// perpendicular likewise; the bitangent is their cross product, its sign from the
// handedness of the coordinates on the face, so that +y points up the image on
// mirrored coordinates too. Those coordinates are the map's own mapping's
// (texture.glsl, slot_corner_uv); the file's tangents belong to TEXCOORD_0, as glTF
// defines them, and orient a map on either mapping.

// A mapped normal is kept at least this cosine toward the viewer (below).
const float MIN_MAPPED_COSINE = 0.01f;

// A bent normal may turn away from the viewer (a steep bump seen at a grazing
// angle); shading would then see its own surface from behind. Its component along wo
// is then replaced by MIN_MAPPED_COSINE: it keeps its lean across the view and turns,
// in the plane of the two, just far enough to face the viewer.
vec3 bent_toward_viewer(vec3 mapped, vec3 wo) {
    float c = dot(mapped, wo);
    if (c < MIN_MAPPED_COSINE) {
        mapped = unit_vector(mapped + (MIN_MAPPED_COSINE - c) * wo);
    }
    return mapped;
}

// hit.normal bent by the normal map `map` (1 + its texture's index) in `slot`
// (MAP_NORMAL or MAP_COAT_NORMAL) of material m, the hit a triangle's or a quad's,
// the map read at its slot's mapping (texture.glsl) and the tangent frame derived
// from it. wo: unit, toward the viewer. Only the shading
// normal bends: the geometric one still offsets rays and decides the faces. A map
// that points straight up (x = y = 0: a flat map, or scale 0) returns hit.normal
// itself, bit for bit; so do coordinates of zero area (no tangent). A back face
// takes the front face's mapped normal, negated.
vec3 normal_from_map(Hit hit, Material m, uint map_index, uint slot, vec3 wo) {
    Texture map = load_texture(map_index - 1u);
    vec3 encoded = vec3(texture_bilinear(map, slot_uv(m, hit_texture_coords(m, hit), slot)));
    float scale = map.decode.x;
    precise vec3 ts = vec3((2.0f * encoded.x - 1.0f) * scale, (2.0f * encoded.y - 1.0f) * scale,
                           2.0f * encoded.z - 1.0f);
    if (ts.x == 0.0f && ts.y == 0.0f) {
        return hit.normal;
    }
    uint index = hit.prim & REF_INDEX_MASK;
    Triangle tri = load_triangle(index);
    float sgn = hit.front_face ? 1.0f : -1.0f;
    vec3 n = sgn * hit.normal;  // the shading normal on the front side
    if (HAS_TANGENTS && (tri.meta.y & TRIANGLE_TANGENTS) != 0u) {
        vec4 given = vertex_tangent(index, hit.bary);
        vec3 t = vec3(given) - dot(vec3(given), n) * n;
        float tt = dot(t, t);
        if (!(tt > 0.0f)) {
            return hit.normal;
        }
        t = t / sqrt(tt);
        return bent_toward_viewer(sgn * unit_vector(ts.x * t + ts.y * (given.w * cross(n, t)) + ts.z * n), wo);
    }
    vec2 t0 = slot_corner_uv(m, tri, index, 0u, slot);
    vec2 t1 = slot_corner_uv(m, tri, index, 1u, slot);
    vec2 t2 = slot_corner_uv(m, tri, index, 2u, slot);
    // Edges from the first corner; a parallelogram's second edge runs p1 to p2, as
    // its coordinates do (triangle_uv).
    bool quad = HAS_QUADS && tri.meta.z != SHAPE_TRIANGLE;
    vec3 e1 = vec3(tri.p1) - vec3(tri.p0);
    vec3 e2 = quad ? vec3(tri.p2) - vec3(tri.p1) : vec3(tri.p2) - vec3(tri.p0);
    vec2 d1 = t1 - t0;
    vec2 d2 = quad ? t2 - t1 : t2 - t0;
    float det = d1.x * d2.y - d2.x * d1.y;
    if (!(abs(det) > 0.0f)) {
        return hit.normal;
    }
    // p = p0 + a e1 + b e2 where uv = t0 + a d1 + b d2: dp/du = (d2.y e1 - d1.y e2) / det.
    vec3 dpdu = (d2.y * e1 - d1.y * e2) / det;
    vec3 t = dpdu - dot(dpdu, n) * n;
    float tt = dot(t, t);
    if (!(tt > 0.0f)) {
        return hit.normal;
    }
    t = t / sqrt(tt);
    // cross(dp/du, dp/dv) = cross(e1, e2) / det, and cross(e1, e2) is the front face's
    // normal: det > 0 means dp/dv runs along cross(n, t), down the image, so the
    // bitangent, up the image, is -cross(n, t).
    vec3 b = (det > 0.0f ? -1.0f : 1.0f) * cross(n, t);
    return bent_toward_viewer(sgn * unit_vector(ts.x * t + ts.y * b + ts.z * n), wo);
}

// The shading normal at a hit: hit.normal (the normal the shape interpolates) bent by
// its material's normal map where it has one and the hit has texture coordinates.
vec3 mapped_normal(Hit hit, vec3 wo) {
    vec3 n = hit.normal;
    if (HAS_NORMAL_MAPS && (hit.prim >> REF_KIND_SHIFT) == REF_TRIANGLE) {
        Material m = load_material(hit.material);
        if (m.normal_map != 0u) {
            n = normal_from_map(hit, m, m.normal_map, MAP_NORMAL, wo);
        }
    }
    return n;
}

// The normal a clear coat (lobes/coat.glsl) lies on, from a hit whose hit.normal is
// not yet mapped: bent by the coat's own normal map where it has one, else
// hit.normal itself. The base's normal map does not bend the coat: glTF's
// KHR_materials_clearcoat gives the coat the surface's normal unless
// clearcoatNormalTexture says otherwise.
vec3 coat_normal(Hit hit, vec3 wo) {
    vec3 n = hit.normal;
    if (HAS_COAT && HAS_NORMAL_MAPS && (hit.prim >> REF_KIND_SHIFT) == REF_TRIANGLE) {
        Material m = load_material(hit.material);
        if (m.coat_normal_map != 0u) {
            n = normal_from_map(hit, m, m.coat_normal_map, MAP_COAT_NORMAL, wo);
        }
    }
    return n;
}

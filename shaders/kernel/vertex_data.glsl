// What a triangle's vertices may carry besides positions, normals and texture
// coordinates: colours (HAS_VERTEX_COLORS, glTF's COLOR_0) and tangents
// (HAS_TANGENTS, glTF's TANGENT). Each is six words a triangle in table_words, in the
// order of the triangles, from its own first word (params): per vertex the half
// floats of (x, y), then (z, w), low half first. Every triangle has its six words, so
// a triangle's index finds them; one without the data (its flag clear in the record's
// meta.y) is never read.
//
// Colours are linear RGBA, interpolated by the hit's barycentric weights. The colour
// multiplies the material's colour (the diffuse colour, or the base colour of both
// lobes) and its alpha the material's opacity (alpha.glsl), as glTF's base colour
// does (texture.glsl, surface_material).
//
// Tangents are glTF's: xyz along +u, w = +-1 the sign of the bitangent, cross(n, t)
// w (normal_map.glsl).
//
// Second texture coordinates (HAS_SECOND_MAPPING; glTF's TEXCOORD_<n> of a material's
// second mapping, texture.glsl) are six words a triangle too, in the same order:
// per vertex the float bits of u, then v. A triangle whose material reads them has
// them (the host copies its first coordinates where the file gives none).

// The four halves of corner `word`.
vec4 corner_halves(uint word) {
    return vec4(unpackHalf2x16(load_table_word(word)), unpackHalf2x16(load_table_word(word + 1u)));
}

// The three corners from word `first` on, interpolated at weights bary (of p1 and p2;
// p0 gets the rest).
vec4 interpolate_corners(uint first, vec2 bary) {
    precise vec4 c = (1.0f - bary.x - bary.y) * corner_halves(first) + bary.x * corner_halves(first + 2u) +
                     bary.y * corner_halves(first + 4u);
    return c;
}

// Texture coordinates at weights (u, v) of a triangle or quad (`quad`) from its
// corners' t0, t1, t2: a parallelogram's weights are half its coordinates along its
// edges (shapes/triangle.glsl, intersect_quad), at which its corners' coordinates
// are extended.
vec2 uv_at_weights(vec2 t0, vec2 t1, vec2 t2, bool quad, float u, float v) {
    return quad ? t0 + (2.0f * u) * (t1 - t0) + (2.0f * v) * (t2 - t1) : t0 + u * (t1 - t0) + v * (t2 - t0);
}

// Corner k (0 to 2) of a triangle record's texture coordinates, which ride in its w
// lanes (shapes/triangle.glsl).
vec2 triangle_uv_corner(Triangle tri, uint k) {
    return k == 0u ? vec2(tri.p0.w, tri.p1.w) : (k == 1u ? vec2(tri.p2.w, tri.n0.w) : vec2(tri.n1.w, tri.n2.w));
}

// Corner k (0 to 2) of triangle `index`'s second texture coordinates.
vec2 second_uv_corner(uint index, uint k) {
    uint word = second_uv_first_word() + 6u * index + 2u * k;
    return vec2(uintBitsToFloat(load_table_word(word)), uintBitsToFloat(load_table_word(word + 1u)));
}

// Triangle `index`'s second texture coordinates at weights bary (as uv_at_weights).
vec2 second_uv(uint index, vec2 bary) {
    bool quad = HAS_QUADS && load_triangle(index).meta.z != SHAPE_TRIANGLE;
    return uv_at_weights(second_uv_corner(index, 0u), second_uv_corner(index, 1u), second_uv_corner(index, 2u), quad,
                         bary.x, bary.y);
}

// Whether triangle `index` has vertex colours.
bool triangle_has_colors(uint index) {
    return HAS_VERTEX_COLORS && (load_triangle(index).meta.y & TRIANGLE_COLORS) != 0u;
}

// The colour of triangle `index` at weights bary.
vec4 vertex_color(uint index, vec2 bary) {
    return interpolate_corners(vertex_color_first_word() + 6u * index, bary);
}

// The tangent of triangle `index` at weights bary: xyz interpolated (not unit), w the
// first corner's sign (glTF gives one sign a triangle).
vec4 vertex_tangent(uint index, vec2 bary) {
    uint first = tangent_first_word() + 6u * index;
    return vec4(vec3(interpolate_corners(first, bary)), corner_halves(first).w < 0.0f ? -1.0f : 1.0f);
}

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

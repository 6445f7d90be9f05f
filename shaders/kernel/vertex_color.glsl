// Vertex colours (HAS_VERTEX_COLORS): glTF's COLOR_0, linear RGBA at each vertex of a
// triangle, interpolated by the hit's barycentric weights. The colour multiplies the
// material's colour (the diffuse colour, or the base colour of both lobes) and its
// alpha the material's opacity (alpha.glsl), as glTF's base colour does
// (texture.glsl, surface_material).
//
// A triangle's three colours are six words of table_words, from
// vertex_color_first_word() on, in the order of the triangles: per vertex the half
// floats (r, g), then (b, a), low half first. Every triangle has its six words, so a
// triangle's index finds them; one without colours (TRIANGLE_COLORS clear in its
// record) is not tinted at all, and its words are never read.

// Whether triangle `index` has vertex colours.
bool triangle_has_colors(uint index) {
    return HAS_VERTEX_COLORS && (load_triangle(index).meta.y & TRIANGLE_COLORS) != 0u;
}

vec4 corner_color(uint word) {
    return vec4(unpackHalf2x16(load_table_word(word)), unpackHalf2x16(load_table_word(word + 1u)));
}

// The colour of triangle `index` at weights bary (of p1 and p2; p0 gets the rest).
vec4 vertex_color(uint index, vec2 bary) {
    uint first = vertex_color_first_word() + 6u * index;
    precise vec4 c = (1.0f - bary.x - bary.y) * corner_color(first) + bary.x * corner_color(first + 2u) +
                     bary.y * corner_color(first + 4u);
    return c;
}

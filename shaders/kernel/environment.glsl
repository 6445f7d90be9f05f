// The environment (HAS_ENVIRONMENT_MAP): an equirectangular image of the radiance
// arriving from infinitely far away, seen by every ray that leaves the scene and,
// in global mode, sampled as a light by its own brightness. Without it the
// background is one colour, background().
//
// The image is held in table_words from environment_first_word() on, as the host
// builds it (host/flatten/environment_table.cpp):
//   0-8    the rotation from world directions to the environment's own frame, rows
//   9, 10  width w and height h in texels
//   12     the texels: linear rgb floats (intensity applied), rows from the top
//   then   the rows' cumulative distribution, h floats, the last exactly 1
//   then   each row's cumulative distribution over its columns, w floats, the last 1
// In its own frame +y is up; the image's left edge looks along -x, its centre along
// +x, its top row up; each column of texels spans 2 pi / w of longitude around the
// up axis (u grows from +x toward +z), each row pi / h of latitude. That is
// Blender's equirectangular mapping, with its z up as our y (a glTF file's axes).
//
// A direction is drawn with the density of a piecewise-constant function over the
// texels: the mean luminance of the bilinearly looked-up image over each texel's
// square (a blend of its 3 x 3 neighbourhood, so the density is positive wherever
// the radiance is) times sin(theta) at the row's centre, which the mapping's
// stretch toward the poles would otherwise overweight (Pharr, Jakob and Humphreys, Physically Based
// Rendering, 4th ed., sections A.5 and 12.5). Arithmetic is `precise` (no fused
// multiply-add), so that both backends get the same bits.

const uint ENV_TEXELS = 12u;  // the first texel's word, after the header

float environment_float(uint i) {
    return uintBitsToFloat(load_table_word(environment_first_word() + i));
}

uint environment_uint(uint i) {
    return load_table_word(environment_first_word() + i);
}

// A world direction in the environment's frame, and back (the rotation's transpose).
vec3 environment_local(vec3 d) {
    precise vec3 l = vec3(environment_float(0u) * d.x + environment_float(1u) * d.y + environment_float(2u) * d.z,
                environment_float(3u) * d.x + environment_float(4u) * d.y + environment_float(5u) * d.z,
                environment_float(6u) * d.x + environment_float(7u) * d.y + environment_float(8u) * d.z);
    return l;
}

vec3 environment_world(vec3 l) {
    precise vec3 d = vec3(environment_float(0u) * l.x + environment_float(3u) * l.y + environment_float(6u) * l.z,
                environment_float(1u) * l.x + environment_float(4u) * l.y + environment_float(7u) * l.z,
                environment_float(2u) * l.x + environment_float(5u) * l.y + environment_float(8u) * l.z);
    return d;
}

// Image coordinates (u, t) in [0, 1]^2 of a unit direction l of the environment's
// frame: u the longitude, 0.5 along +x; t the angle from the up pole over pi. At a
// pole, where the longitude is undefined, and for a direction that is not finite,
// u is 0.5.
vec2 environment_uv(vec3 l) {
    precise float r = sqrt(l.x * l.x + l.z * l.z);
    float theta = upper_half_plane_angle(r, l.y);
    float phi = 0.0f;
    if (r > 0.0f) {
        phi = l.z >= 0.0f ? upper_half_plane_angle(l.z, l.x) : -upper_half_plane_angle(-l.z, l.x);
    }
    precise vec2 uv = vec2(0.5f + phi * (0.5f / PI), theta * (1.0f / PI));
    return vec2(uv.x >= 0.0f && uv.x <= 1.0f ? uv.x : 0.5f, uv.y >= 0.0f && uv.y <= 1.0f ? uv.y : 0.5f);
}

vec3 environment_texel(uint x, uint y, uint w) {
    uint i = ENV_TEXELS + 3u * (y * w + x);
    return vec3(environment_float(i), environment_float(i + 1u), environment_float(i + 2u));
}

// The radiance arriving from direction dir (a unit world vector): the four texels
// around its image position, bilinearly; longitude wraps around, latitude stops
// at the poles' rows.
vec3 environment_radiance(vec3 dir) {
    vec2 uv = environment_uv(environment_local(dir));
    uint w = environment_uint(9u);
    uint h = environment_uint(10u);
    precise vec2 x = vec2(uv.x * float(w), uv.y * float(h)) - vec2(0.5f);
    vec2 f0 = floor(x);
    precise vec2 f = x - f0;
    int x0 = int(f0.x);
    int y0 = int(f0.y);
    uint xa = wrap_index(x0, w, WRAP_REPEAT);
    uint xb = wrap_index(x0 + 1, w, WRAP_REPEAT);
    uint ya = wrap_index(y0, h, WRAP_CLAMP);
    uint yb = wrap_index(y0 + 1, h, WRAP_CLAMP);
    precise vec3 top = mix(environment_texel(xa, ya, w), environment_texel(xb, ya, w), f.x);
    precise vec3 bottom = mix(environment_texel(xa, yb, w), environment_texel(xb, yb, w), f.x);
    precise vec3 c = mix(top, bottom, f.y);
    return c;
}

// What a ray that leaves the scene in direction dir sees.
vec3 sky(vec3 dir) {
    return HAS_ENVIRONMENT_MAP ? environment_radiance(dir) : background();
}

// The word where the rows' cumulative distribution starts, and where row y's does.
uint environment_rows_cdf() {
    return ENV_TEXELS + 3u * environment_uint(9u) * environment_uint(10u);
}

uint environment_row_cdf(uint y) {
    return environment_rows_cdf() + environment_uint(10u) + y * environment_uint(9u);
}

// Entry i of the cumulative distribution starting at word `first`; 0 before the first.
float environment_cdf(uint first, uint i) {
    return i == 0u ? 0.0f : environment_float(first + i - 1u);
}

// The first of the n entries from word `first` that exceeds u in [0, 1); the last
// is 1, so there always is one.
uint environment_search(uint first, uint n, float u) {
    uint lo = 0u;
    uint hi = n - 1u;
    loop_enter();
    while (lo < hi) {
        if (!loop_tick()) {
            break;  // the sample is flagged truncated; any index in range will do
        }
        uint mid = (lo + hi) / 2u;
        if (u < environment_float(first + mid)) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

// The density over solid angle of directions in texel (x, y) whose angle from the
// pole has sine sin_theta: the texel's probability, spread over its share w h of
// the unit square, which the mapping stretches by 2 pi^2 sin(theta).
float environment_texel_pdf(uint x, uint y, float sin_theta) {
    uint w = environment_uint(9u);
    uint h = environment_uint(10u);
    uint rows = environment_rows_cdf();
    uint row = environment_row_cdf(y);
    float p_row = environment_cdf(rows, y + 1u) - environment_cdf(rows, y);
    float p_column = environment_cdf(row, x + 1u) - environment_cdf(row, x);
    precise float p = p_row * p_column * float(w) * float(h);
    precise float density = p / (2.0f * PI * PI * sin_theta);
    return sin_theta > 0.0f ? min(density, INFINITY_T) : 0.0f;
}

// The density with which sample_environment draws the unit world direction dir.
float environment_pdf(vec3 dir) {
    vec3 l = environment_local(dir);
    vec2 uv = environment_uv(l);
    uint w = environment_uint(9u);
    uint h = environment_uint(10u);
    uint x = min(uint(uv.x * float(w)), w - 1u);
    uint y = min(uint(uv.y * float(h)), h - 1u);
    precise float sin_theta = sqrt(l.x * l.x + l.z * l.z);
    return environment_texel_pdf(x, y, sin_theta);
}

struct EnvironmentSample {
    vec3 dir;       // unit, in the world
    vec3 radiance;  // arriving from dir
    float pdf;      // over solid angle
};

// A direction drawn from two uniform numbers in [0, 1): the first picks a row by
// the rows' distribution and, rescaled to the row's share, the latitude within it;
// the second the column and the longitude within it.
EnvironmentSample sample_environment(float u1, float u2) {
    uint w = environment_uint(9u);
    uint h = environment_uint(10u);
    uint rows = environment_rows_cdf();
    uint y = environment_search(rows, h, u1);
    float below = environment_cdf(rows, y);
    precise float fy = min((u1 - below) / (environment_cdf(rows, y + 1u) - below), 0.99999994f);
    uint row = environment_row_cdf(y);
    uint x = environment_search(row, w, u2);
    float left = environment_cdf(row, x);
    precise float fx = min((u2 - left) / (environment_cdf(row, x + 1u) - left), 0.99999994f);
    precise float theta = PI * ((float(y) + fy) / float(h));
    precise float phi = 2.0f * PI * ((float(x) + fx) / float(w) - 0.5f);
    vec2 st = sin_cos(theta);
    vec2 sp = sin_cos(phi);
    precise vec3 l = vec3(sp.y * st.x, st.y, sp.x * st.x);
    vec3 dir = environment_world(l);
    return EnvironmentSample(dir, environment_radiance(dir), environment_texel_pdf(x, y, st.x));
}

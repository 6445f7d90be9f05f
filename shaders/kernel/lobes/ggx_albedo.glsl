// The rough lobe's albedos (ggx.glsl), which the lobes that give back or share what
// it leaves read: the multiple-scattering lobe (ggx_multiple.glsl) and the diffuse
// lobe under it (diffuse.glsl). Tables the host builds from ggx.glsl's own functions
// (host/flatten/ggx_albedo.cpp) and the kernel interpolates:
//
//   E(mu)    the single-scattering albedo from cos(theta_o) = mu with a Fresnel of 1
//   E_s(mu)  the same with the Fresnel (1 - wo.h)^5, Schlick's weight
//
// and their means over the cosine-weighted hemisphere, 2 int_0^1 E(mu) mu dmu. As
// Schlick's Fresnel is f0 + (f90 - f0)(1 - wo.h)^5, the lobe of reflectance f0 (f90 at
// grazing incidence) reflects f0 E + (f90 - f0) E_s by single scattering.

// The tables in table_words from ggx_table_first_word(), for each of E and E_s:
// GGX_TABLE_SIZE^2 values, mu fastest, then GGX_TABLE_SIZE values of the mean, at the knots
// mu = (i / (GGX_TABLE_SIZE - 1))^2 and r = j / (GGX_TABLE_SIZE - 1), alpha = r^2:
// linear in sqrt(mu) and in r, so that the knots crowd where E changes fastest,
// near grazing and for smooth lobes.
float ggx_table_value(uint i) {
    return uintBitsToFloat(load_table_word(ggx_table_first_word() + i));
}

// Linear interpolation between knots of a table axis for x in [0, 1]: the lower knot
// and the weight of the upper one.
uint ggx_table_knot(float x, INOUT(float) t) {
    float s = clamp(x, 0.0f, 1.0f) * float(GGX_TABLE_SIZE - 1u);
    uint k = min(uint(s), GGX_TABLE_SIZE - 2u);
    t = s - float(k);
    return k;
}

const uint GGX_SCHLICK_TABLE = GGX_TABLE_SIZE * GGX_TABLE_SIZE + GGX_TABLE_SIZE;
// With HAS_SHEEN a third table follows, laid out alike: the sheen lobe's albedo with
// a colour of 1 (sheen.glsl), at alpha = the square of the sheen roughness.
const uint SHEEN_TABLE = 2u * GGX_SCHLICK_TABLE;

// Bilinear in sqrt(mu) and sqrt(alpha), from the table at word `table`.
float ggx_table_lookup(uint table, float mu, float alpha) {
    float tm = 0.0f;
    float tr = 0.0f;
    uint i = ggx_table_knot(sqrt(max(mu, 0.0f)), tm);
    uint j = ggx_table_knot(sqrt(alpha), tr);
    uint n = GGX_TABLE_SIZE;
    float low = mix(ggx_table_value(table + j * n + i), ggx_table_value(table + j * n + i + 1u), tm);
    float high = mix(ggx_table_value(table + (j + 1u) * n + i), ggx_table_value(table + (j + 1u) * n + i + 1u), tm);
    return mix(low, high, tr);
}

float ggx_table_mean(uint table, float alpha) {
    float tr = 0.0f;
    uint j = ggx_table_knot(sqrt(alpha), tr);
    uint base = table + GGX_TABLE_SIZE * GGX_TABLE_SIZE;
    return mix(ggx_table_value(base + j), ggx_table_value(base + j + 1u), tr);
}

float ggx_albedo(float mu, float alpha) {
    return ggx_table_lookup(0u, mu, alpha);
}

float ggx_mean_albedo(float alpha) {
    return ggx_table_mean(0u, alpha);
}

// F_ms of Kulla and Conty: the Fresnel of light that leaves after bouncing between
// microfacets, F_avg^2 E_avg / (1 - F_avg (1 - E_avg)), F_avg = f0 + (f90 - f0) / 21
// the mean of Schlick's Fresnel over the cosine-weighted hemisphere.
vec3 ggx_multiple_fresnel(vec3 f0, float f90, float e_avg) {
    vec3 f_avg = f0 + (vec3(f90) - f0) * (1.0f / 21.0f);
    return f_avg * f_avg * e_avg / (vec3(1.0f) - f_avg * (1.0f - e_avg));
}

// What the rough lobe of reflectance f0 (f90) reflects from cos(theta) = mu, single
// and multiple scattering together.
vec3 ggx_reflectance(vec3 f0, float f90, float mu, float alpha) {
    float e = ggx_albedo(mu, alpha);
    float e_s = ggx_table_lookup(GGX_SCHLICK_TABLE, mu, alpha);
    vec3 f_ms = ggx_multiple_fresnel(f0, f90, ggx_mean_albedo(alpha));
    return f0 * e + (vec3(f90) - f0) * e_s + f_ms * (1.0f - e);
}

// Its mean over the cosine-weighted hemisphere.
vec3 ggx_mean_reflectance(vec3 f0, float f90, float alpha) {
    float e_avg = ggx_mean_albedo(alpha);
    float e_s_avg = ggx_table_mean(GGX_SCHLICK_TABLE, alpha);
    return f0 * e_avg + (vec3(f90) - f0) * e_s_avg + ggx_multiple_fresnel(f0, f90, e_avg) * (1.0f - e_avg);
}

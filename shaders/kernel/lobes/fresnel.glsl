// What the lobes share: a colour's selection weight, and Schlick's approximation of
// the Fresnel reflectance (Schlick, "An Inexpensive BRDF Model for Physically-based
// Rendering", 1994), F = f0 + (f90 - f0)(1 - cos)^5 for the cosine cos_d between the
// direction and the (micro)surface normal, f90 = 1 but where glTF's
// KHR_materials_specular lowers a dielectric's (HAS_DIELECTRIC_SPECULAR).

float mean3(vec3 v) {
    return (v.x + v.y + v.z) * (1.0f / 3.0f);
}

float max3(vec3 v) {
    return max(v.x, max(v.y, v.z));
}

// (1 - cos_d)^5, cos_d clamped to [0, 1].
float schlick_scalar(float cos_d) {
    float m = clamp(1.0f - cos_d, 0.0f, 1.0f);
    float m2 = m * m;
    return m2 * m2 * m;
}

vec3 fresnel_schlick(vec3 f0, float f90, float cos_d) {
    precise vec3 f = f0 + (vec3(f90) - f0) * schlick_scalar(cos_d);
    return f;
}

vec3 fresnel_schlick(vec3 f0, float cos_d) {
    return fresnel_schlick(f0, 1.0f, cos_d);
}

// The GGX lobe's f90 of material m: 1 without HAS_DIELECTRIC_SPECULAR.
float material_f90(Material m) {
    return HAS_DIELECTRIC_SPECULAR ? m.ggx_f90 : 1.0f;
}

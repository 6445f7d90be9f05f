// The paper's local reflection term for one light direction, shared by point lights
// (shade.glsl) and area lights (area_lights.glsl): kd * diffuse * cos(theta) + ks *
// specular * cos(alpha)^shininess, with alpha between the light direction mirrored
// about the normal and the direction to the eye. `diffuse` is kd * diffuse already;
// cos_theta = dot(normal, l) > 0.
vec3 phong_term(Material m, vec3 diffuse, vec3 normal, vec3 l, float cos_theta, vec3 to_eye) {
    vec3 term = diffuse * cos_theta;
    if (HAS_SPECULAR) {
        vec3 mirrored = (2.0f * cos_theta) * normal - l;
        float cos_alpha = dot(mirrored, to_eye);
        // pow(0, 0) is undefined in GLSL: no highlight where cos(alpha) <= 0.
        if (cos_alpha > 0.0f) {
            term += m.specular * (m.ks * power(cos_alpha, m.shininess));
        }
    }
    return term;
}

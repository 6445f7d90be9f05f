// Local illumination as the paper defines it (docs/architecture.md, "Numbers and conventions"):
// per point light, colour * intensity * (kd * diffuse * cos(theta) + ks * specular *
// cos(alpha)^shininess), with alpha between the mirrored light vector and the eye
// vector; plus ambient * kd * diffuse, plus the material's own emission seen from
// its front face, plus the light of emissive primitives (area_lights.glsl). Lights
// below the surface get no shadow ray (the SPD rule; visibility.glsl).
// The paper's convention has no fall-off with distance, and the other kinds keep
// it: a spot light is a point light times its cone factor (lights.glsl), a
// directional light one at infinity, theta and alpha taken with its direction.

vec3 shade_local(Ray ray, Hit hit, INOUT(Rng) rng, INOUT(uint) shadow_rays) {
    Material m = surface_material(hit);
    vec3 diffuse = m.diffuse * m.kd;
    vec3 color = vec3(0.0f);
    if (HAS_EMISSION && hit.front_face) {
        color += m.emission;
    }
    if (HAS_AMBIENT) {
        color += ambient_light() * diffuse;
    }
    if (HAS_POINT_LIGHTS) {
        precise vec3 p = ray.origin + hit.t * ray.dir;
        vec3 shadow_origin = shadow_ray_origin(p, hit);
        vec3 to_eye = -ray.dir;
        loop_enter();
        for (uint i = 0u; i < light_count(); ++i) {
            if (!loop_tick()) {
                break;
            }
            Light light = load_light(i);
            vec3 to_light = toward_light(light, p);
            float dist = length(to_light);
            vec3 l = to_light / dist;
            float cone = HAS_DIRECTED_LIGHTS ? cone_factor(light, l) : 1.0f;
            if (cone > 0.0f && light_reaches(hit, shadow_origin, l, light.position, true, shadow_rays)) {
                color += vec3(light.radiance) * cone * phong_term(m, diffuse, hit.normal, l, dot(hit.normal, l), to_eye);
            }
        }
    }
    if (HAS_AREA_LIGHTS) {
        color += shade_area_lights(ray, hit, m, rng, shadow_rays);
    }
    return color;
}

// Direct light from the area lights (the emissive primitives) at a hit, in local
// mode: an estimate with render.light_samples points y drawn by sample_light
// (emitters.glsl), each with its density p over solid angle, one shadow ray each:
//
//   L = 1/N * sum  Le(y) * (kd diffuse cos(theta) + ks specular cos(alpha)^shininess)
//                  / (pi p)        [0 where y is hidden or faces away]
//
// theta between the normal and the direction l to y, alpha as for point lights
// (shade.glsl); emission leaves the front face only. For a point drawn uniformly on
// an area A, 1 / p is cos(theta') A / r^2, with theta' between y's front-face normal
// and -l and r the distance.
//
// Why 1/pi. The paper's point light adds intensity * diffuse * cos(theta) with no
// fall-off: that is the radiance of a Lambertian surface of albedo `diffuse` under an
// irradiance of pi * intensity * cos(theta). Read that way, a patch dA of an area light
// of radiance Le, which gives the irradiance Le cos(theta) cos(theta') dA / r^2, is a
// point light of intensity Le cos(theta') dA / (pi r^2), and the diffuse part of the
// sum is exactly (diffuse / pi) * irradiance, the physical radiance of the surface. A
// white plane under a light that fills its sky then shows the light's own radiance,
// as it must; without the 1/pi it would be pi times brighter than its light.
// Point lights keep the paper's convention unchanged.

vec3 shade_area_lights(Ray ray, Hit hit, Material m, INOUT(Rng) rng, INOUT(uint) shadow_rays) {
    precise vec3 p = ray.origin + hit.t * ray.dir;
    vec3 shadow_origin = shadow_ray_origin(p, hit);
    vec3 to_eye = -ray.dir;
    vec3 diffuse = m.diffuse * m.kd;
    // A surface that reflects nothing (a lamp is often black) gets nothing from any
    // light: spare it the shadow rays. Colours are >= 0, so a zero sum means all zero.
    float reflects = diffuse.x + diffuse.y + diffuse.z;
    if (HAS_SPECULAR) {
        reflects += (m.specular.x + m.specular.y + m.specular.z) * m.ks;
    }
    if (!(reflects > 0.0f)) {
        return vec3(0.0f);
    }
    uint samples = light_samples();
    vec3 sum = vec3(0.0f);
    loop_enter();
    for (uint i = 0u; i < samples; ++i) {
        if (!loop_tick()) {
            break;
        }
        // Drawn before any test, so every light sample takes the same numbers.
        LightSample y = sample_light(shadow_origin, rng);
        vec3 to_light = y.position - shadow_origin;
        vec3 l = to_light / sqrt(dot(to_light, to_light));
        // The emitter's front must face the point (visibility.glsl tests the rest).
        bool facing = y.pdf > 0.0f && -dot(y.normal, l) > 0.0f;
        if (light_reaches(hit, shadow_origin, l, vec4(y.position, 1.0f), facing, shadow_rays)) {
            sum += y.emission * phong_term(m, diffuse, hit.normal, l, dot(hit.normal, l), to_eye) / y.pdf;
        }
    }
    return sum * (1.0f / (PI * float(max(samples, 1u))));
}

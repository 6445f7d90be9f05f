// Global illumination (render.mode "global"): one Monte Carlo sample of the radiance
// reaching the eye along a ray, by the paper's estimator or by path tracing
// (estimator() and hemisphere_rule(); next-event estimation is HAS_NEXT_EVENT). GLSL has
// no recursion: every bounce is one iteration of a loop, and one tick of the
// invocation's loop budget.
//
// max_bounces counts scattering events after the first hit: with k, light is
// gathered at the first hit and at up to k further surfaces, so a closed furnace of
// albedo rho and emission Le shows Le (1 - rho^(k+1)) / (1 - rho).
//
// Radiance units: global mode is physical. A point light of intensity I lights a
// surface with irradiance I cos(theta) / r^2, whose Lambertian radiance is then
// rho / pi * I cos(theta) / r^2 (local mode keeps the paper's convention, without
// the fall-off and the 1/pi). A spot light is a point light times its cone factor
// (lights.glsl); a directional light of irradiance E (its colour * intensity) gives
// E cos(theta), with no fall-off. Emitters are seen, and light, from their front face.

// The point a ray hits, rounded once (precise: no fused multiply-add) as in local
// mode. A function because glslang 11 crashes on a `precise` local inside
// path_sample's loop.
vec3 hit_point(Ray ray, float t) {
    precise vec3 p = ray.origin + t * ray.dir;
    return p;
}

// The power heuristic (Veach, 1997, beta = 2) for a sample drawn with density
// pdf_this that the other technique would have drawn with pdf_other. Written with
// the ratio so that neither density is squared: both can be as large as INFINITY_T.
float power_heuristic(float pdf_this, float pdf_other) {
    if (!(pdf_this > 0.0f)) {
        return 0.0f;
    }
    float r = min(pdf_other / pdf_this, 1.0e18f);
    return 1.0f / (1.0f + r * r);
}

// Traces a path's next ray into `hit`, its shading normal normal-mapped (and the
// normal its clear coat lies on into coat_n, normal_map.glsl), and weighs
// the path's throughput by what the medium it crossed let through (`media`, the
// medium the ray travels in). When it leaves the scene, adds what the sky sends along
// it weighed by that throughput and returns false; notes the eye ray's hit
// (note_first_hit). pdf_prev is the density
// with which the ray was drawn by sampling the smooth lobes, 0 otherwise: such a
// ray that finds the environment is weighed against next-event estimation's
// drawing it (the power heuristic, as for emitters).
bool path_hit(Ray ray, uint bounce, uvec4 media, float pdf_prev, INOUT(vec3) beta, INOUT(SampleResult) s,
              INOUT(Hit) hit, INOUT(vec3) coat_n) {
    hit = closest_hit(ray, INFINITY_T);
    if (HAS_ABSORPTION) {
        beta *= medium_transmittance(media, hit.t);
    }
    if (!(hit.t < INFINITY_T)) {
        float w = 1.0f;
        if (HAS_ENVIRONMENT_MAP && pdf_prev > 0.0f && environment_choice() > 0.0f) {
            w = power_heuristic(pdf_prev, environment_choice() * environment_pdf(ray.dir));
        }
        s.radiance += beta * sky(ray.dir) * w;
        return false;
    }
    coat_n = HAS_COAT ? coat_normal(hit, -ray.dir) : vec3(0.0f);
    hit.normal = mapped_normal(hit, -ray.dir);
    if (bounce == 0u) {
        note_first_hit(hit, s);
    }
    return true;
}

// Russian roulette starts at this bounce: the first few bounces carry most of the
// light, and ending them at random would only add noise.
const uint ROULETTE_START = 3u;

// Direct light at a path vertex through its smooth lobes: every light of the
// scene's `lights` (the only way to reach one: no path can hit a point, nor come
// from exactly one direction) and, with next-event estimation (HAS_NEXT_EVENT), one
// point on the area lights or one direction of the environment, weighted by the
// power heuristic against the BSDF sampling that could have found it too (whose
// hits are weighted to match in path_hit and path_sample). p_smooth is the probability of
// picking the smooth group, part of the BSDF sampling's density; `slot` is the
// bounce's first slot (constants.glsl). The shadow rays cross the medium the path
// arrived in (`media`), whose transmittance weighs what they bring.
vec3 next_event(Hit hit, vec3 p, vec3 wo, Lobes lobes, Basis frame, float p_smooth, uint slot, uvec4 media,
                INOUT(Rng) rng, INOUT(SampleResult) s) {
    vec3 sum = vec3(0.0f);
    vec3 shadow_origin = shadow_ray_origin(p, hit);
    if (HAS_POINT_LIGHTS) {
        loop_enter();
        for (uint i = 0u; i < light_count(); ++i) {
            if (!loop_tick()) {
                break;
            }
            Light light = load_light(i);
            vec3 to_light = toward_light(light, p);
            // A directional light's vector is its unit direction: r2 is 1, to rounding,
            // and the light does not fall off.
            float r2 = dot(to_light, to_light);
            vec3 l = to_light / sqrt(r2);
            float cone = HAS_DIRECTED_LIGHTS ? cone_factor(light, l) : 1.0f;
            if (cone > 0.0f && light_reaches(hit, shadow_origin, l, light.position, true, s.shadow_rays)) {
                vec3 radiance = vec3(light.radiance);
                if (HAS_ABSORPTION) {
                    bool directional = HAS_DIRECTED_LIGHTS && light.position.w == 0.0f;
                    radiance *= medium_transmittance(media, directional ? INFINITY_T : sqrt(r2));
                }
                sum += eval_smooth(lobes, hit.normal, wo, l) * radiance * (dot(hit.normal, l) * cone / r2);
            }
        }
    }
    if (HAS_NEXT_EVENT) {
        // One slot, one shadow ray: its first number picks the environment with
        // probability environment_choice() and, rescaled to its share, draws with the
        // second as sample_light does (for a choice of 0, exactly the number drawn).
        rng_seek(rng, slot + SLOT_LIGHT);
        vec2 u = rng_2d(rng);
        float p_env = HAS_ENVIRONMENT_MAP ? environment_choice() : 0.0f;
        if (u.x < p_env) {
            EnvironmentSample e = sample_environment(min(u.x / p_env, 0.99999994f), u.y);
            float pdf = p_env * e.pdf;
            if (pdf > 0.0f && light_reaches(hit, shadow_origin, e.dir, vec4(e.dir, 0.0f), true, s.shadow_rays)) {
                float pdf_bsdf = p_smooth * pdf_smooth(lobes, frame, wo, e.dir, hemisphere_rule());
                vec3 radiance = HAS_ABSORPTION ? e.radiance * medium_transmittance(media, INFINITY_T) : e.radiance;
                sum += eval_smooth(lobes, hit.normal, wo, e.dir) * radiance *
                       (dot(hit.normal, e.dir) * power_heuristic(pdf, pdf_bsdf) / pdf);
            }
        } else if (HAS_AREA_LIGHTS) {
            // Drawn from the shadow ray's origin, which is also the origin of the bounce
            // ray whose hit on a light light_pdf_of_hit weighs: the same point, the same
            // choice of technique.
            u.x = min((u.x - p_env) / (1.0f - p_env), 0.99999994f);
            LightSample y = sample_light_from(shadow_origin, u);
            y.pdf *= 1.0f - p_env;
            vec3 to_light = y.position - shadow_origin;
            float distance = sqrt(dot(to_light, to_light));
            vec3 l = to_light / distance;
            bool facing = y.pdf > 0.0f && -dot(y.normal, l) > 0.0f;
            if (light_reaches(hit, shadow_origin, l, vec4(y.position, 1.0f), facing, s.shadow_rays)) {
                float pdf_bsdf = p_smooth * pdf_smooth(lobes, frame, wo, l, hemisphere_rule());
                vec3 radiance = HAS_ABSORPTION ? y.emission * medium_transmittance(media, distance) : y.emission;
                sum += eval_smooth(lobes, hit.normal, wo, l) * radiance *
                       (dot(hit.normal, l) * power_heuristic(y.pdf, pdf_bsdf) / y.pdf);
            }
        }
    }
    return sum;
}

// The ray leaving a mirror or glass hit, and the factor the path's throughput takes:
// mirror: reflect / P(mirror); glass: its colour / P(glass), reflected with the
// Fresnel reflectance's probability (which cancels it from the weight; with a
// specular layer, the layer's, lobes/glass.glsl glass_split) and refracted otherwise,
// or through a thin wall sent on straight; with "fresnel": false always refracted
// (total internal reflection reflects). `pick` (uniform in [0, total)) chose the group, u.x decides within
// smooth glass; rough glass (lobes/rough_glass.glsl) draws its microfacet by u and decides by where pick fell in
// the glass's share. A refraction updates the media the path is in (lobes/glass.glsl).
Ray scatter_delta(Ray ray, Hit hit, vec3 p, Lobes lobes, float total, float pick, vec2 u, INOUT(vec3) beta,
                  INOUT(uvec4) media) {
    Ray mirrored = Ray(offset_ray_origin(p, hit.geo_normal), mirror_direction(ray.dir, hit.normal));
    // Guarded so that a pick rounded up to `total` never lands on a group of weight 0.
    bool mirror = lobes.glass.weight == 0.0f ||
                  (lobes.mirror.weight > 0.0f && pick < smooth_weight(lobes) + lobes.mirror.weight);
    if (mirror) {
        note_decision(DECISION_MIRROR);
        beta *= lobes.mirror.color * (total / lobes.mirror.weight);
        return mirrored;
    }
    // A thin wall is an interface from air into the glass, whichever side is hit.
    float eta = lobes.glass.thin ? 1.0f / lobes.glass.ior : interface_eta(media, lobes.glass.ior, hit.front_face);
    // Between equal indices there is no interface, rough or not: the smooth glass's eta 1 goes on straight.
    if (HAS_ROUGH_GLASS && lobes.glass.alpha > 0.0f && eta != 1.0f) {
        float split = (pick - smooth_weight(lobes) - lobes.mirror.weight) / lobes.glass.weight;
        return rough_glass_scatter(ray, hit, p, lobes.glass, eta, clamp(split, 0.0f, 1.0f), u,
                                   total / lobes.glass.weight, beta, media);
    }
    Refraction r = refract_fresnel(ray.dir, hit.normal, eta);
    GlassSplit crossing = glass_split(lobes.glass, r.total ? 1.0f : (lobes.glass.fresnel ? r.reflectance : 0.0f), eta);
    bool reflects = u.x < crossing.p_reflect;
    note_decision(reflects ? DECISION_GLASS_REFLECTS : DECISION_GLASS_REFRACTS);
    beta *= (reflects ? lobes.glass.reflected * crossing.tint : lobes.glass.color) * (total / lobes.glass.weight);
    if (reflects) {
        return mirrored;
    }
    if (lobes.glass.thin) {
        return Ray(offset_ray_origin(p, -hit.geo_normal), ray.dir);
    }
    media = media_after_refraction(media, hit.material, hit.front_face);
    return Ray(offset_ray_origin(p, -hit.geo_normal), r.dir);
}

// Unbiased path tracing with a throughput loop: emission counted where a path meets
// an emitter's front face, one lobe group sampled per bounce, next-event estimation
// with multiple importance sampling when HAS_NEXT_EVENT, Russian roulette from
// ROULETTE_START on (survival probability: the throughput's largest channel, at most
// 0.95, and the throughput divided by it).
void path_sample(Ray eye, INOUT(Rng) rng, INOUT(SampleResult) s) {
    Ray ray = eye;
    vec3 beta = vec3(1.0f);
    // The solid-angle density of the last bounce when it sampled the smooth lobes;
    // 0 after the eye or a delta lobe, whose hits on an emitter count in full.
    float pdf_prev = 0.0f;
    uint hemisphere = hemisphere_rule();
    uvec4 media = uvec4(0u);  // in air
    loop_enter();
    for (uint bounce = 0u; loop_tick(); bounce += 1u) {
        Hit hit;
        vec3 coat_n;
        if (!path_hit(ray, bounce, media, pdf_prev, beta, s, hit, coat_n)) {
            return;
        }
        Material m = surface_material(hit);
        if (HAS_EMISSION && hit.front_face) {
            float w = 1.0f;
            if (HAS_NEXT_EVENT && HAS_AREA_LIGHTS && pdf_prev > 0.0f) {
                float p_area = 1.0f - (HAS_ENVIRONMENT_MAP ? environment_choice() : 0.0f);
                w = power_heuristic(pdf_prev, p_area * light_pdf_of_hit(ray, hit));
            }
            s.radiance += beta * m.emission * w;
        }
        if (bounce >= max_bounces()) {
            return;
        }
        CHECK(is_unit(ray.dir) && is_unit(hit.normal));
        Lobes lobes = material_lobes(m, hit.normal, coat_n, -ray.dir);
        float total = lobes_total(lobes);
        if (!(total > 0.0f)) {
            return;
        }
        vec3 p = hit_point(ray, hit.t);
        vec3 wo = -ray.dir;
        Basis frame = basis_around(hit.normal);
        float w_smooth = smooth_weight(lobes);
        float p_smooth = w_smooth / total;
        uint slot = SLOT_PATH + bounce * BOUNCE_SLOTS;
        if ((HAS_POINT_LIGHTS || HAS_NEXT_EVENT) && w_smooth > 0.0f) {
            s.radiance += beta * next_event(hit, p, wo, lobes, frame, p_smooth, slot, media, rng, s);
        }
        rng_seek(rng, slot + SLOT_LOBE);
        float pick = rng_1d(rng) * total;
        rng_seek(rng, slot + SLOT_DIRECTION);
        vec2 u = rng_2d(rng);
        if (pick < w_smooth || !(w_smooth < total)) {
            note_decision(DECISION_SMOOTH_LOBES);
            vec3 wi = sample_smooth(lobes, frame, wo, hemisphere, pick / w_smooth, u.x, u.y);
            CHECK(is_unit(wi));
            float cos_theta = dot(wi, hit.normal);
            float pdf = p_smooth * pdf_smooth(lobes, frame, wo, wi, hemisphere);
            // Below the surface the lobes are zero: the sample adds nothing, the path ends.
            if (!(cos_theta > 0.0f && dot(wi, hit.geo_normal) > 0.0f && pdf > 0.0f)) {
                return;
            }
            beta *= eval_smooth(lobes, hit.normal, wo, wi) * (cos_theta / pdf);
            CHECK(is_weight(beta));
            pdf_prev = pdf;
            ray = Ray(offset_ray_origin(p, hit.geo_normal), wi);
        } else {
            ray = scatter_delta(ray, hit, p, lobes, total, pick, u, beta, media);
            pdf_prev = 0.0f;
            // Rough glass ends the path with a direction on the wrong side of the surface.
            if (HAS_ROUGH_GLASS && !any(greaterThan(beta, vec3(0.0f)))) {
                return;
            }
        }
        if (bounce + 1u >= ROULETTE_START) {
            float survive = min(max(beta.x, max(beta.y, beta.z)), 0.95f);
            rng_seek(rng, slot + SLOT_ROULETTE);
            if (!(rng_1d(rng) < survive)) {
                note_decision(DECISION_ROULETTE_ENDED);
                s.roulette = 1u;
                return;
            }
            beta /= survive;
        }
        s.bounce_rays += 1u;
    }
}

// The paper's gl(): follows random bounces from a ray until it meets a light (an
// emitter's front face, or the background when nothing is hit) and returns its
// radiance attenuated by kd * diffuse of every surface on the way, or 0 after
// `bounces` surfaces without one. Directions are drawn with the hemisphere rule and
// not weighted by any density: the paper's estimator, as written.
vec3 paper_gl(Ray start, uint bounces, INOUT(Rng) rng, INOUT(SampleResult) s) {
    Ray ray = start;
    vec3 attenuation = vec3(1.0f);
    loop_enter();
    for (uint i = 0u; i < bounces; ++i) {
        if (!loop_tick()) {
            break;
        }
        s.bounce_rays += 1u;
        Hit hit = closest_hit(ray, INFINITY_T);
        if (!(hit.t < INFINITY_T)) {
            return attenuation * sky(ray.dir);
        }
        hit.normal = mapped_normal(hit, -ray.dir);
        Material m = surface_material(hit);
        if (HAS_EMISSION && hit.front_face && any(greaterThan(m.emission, vec3(0.0f)))) {
            return attenuation * m.emission;
        }
        attenuation *= m.diffuse * m.kd;
        vec2 u = rng_2d(rng);
        vec3 d = from_basis(basis_around(hit.normal), sample_hemisphere(hemisphere_rule(), u.x, u.y));
        if (!any(greaterThan(attenuation, vec3(0.0f))) || !(dot(d, hit.geo_normal) > 0.0f)) {
            return vec3(0.0f);
        }
        vec3 p = hit_point(ray, hit.t);
        ray = Ray(offset_ray_origin(p, hit.geo_normal), d);
    }
    return vec3(0.0f);
}

// The paper's estimator. The eye ray follows mirrors and glass (a lobe group picked
// as in path_sample) to the first surface where it picks the smooth group; seeing a
// light on the way returns its radiance. There one direction d is drawn, the paper's
// local term (kd diffuse cos(theta) + ks specular cos(alpha)^shininess, as for a
// point light in local mode) is taken toward d and multiplied by gl(d). A sample
// whose gl() is 0 is dropped: left out of the pixel's average altogether (its N
// decreases), which is what biases the estimator; the Counters count them.
void paper_sample(Ray eye, INOUT(Rng) rng, INOUT(SampleResult) s) {
    Ray ray = eye;
    vec3 beta = vec3(1.0f);
    uvec4 media = uvec4(0u);  // in air
    loop_enter();
    for (uint bounce = 0u; loop_tick(); bounce += 1u) {
        Hit hit;
        vec3 coat_n;
        if (!path_hit(ray, bounce, media, 0.0f, beta, s, hit, coat_n)) {
            return;
        }
        Material m = surface_material(hit);
        if (HAS_EMISSION && hit.front_face && any(greaterThan(m.emission, vec3(0.0f)))) {
            s.radiance += beta * m.emission;
            return;
        }
        CHECK(is_unit(ray.dir) && is_unit(hit.normal));
        Lobes lobes = material_lobes(m, hit.normal, coat_n, -ray.dir);
        float total = lobes_total(lobes);
        if (!(total > 0.0f)) {
            return;  // a black surface: its local term, and the sample, is 0
        }
        if (bounce >= max_bounces()) {
            s.dropped = true;  // no bounce left for gl(): it returns 0
            return;
        }
        vec3 p = hit_point(ray, hit.t);
        float w_smooth = smooth_weight(lobes);
        // Drawn one statement each: C++ leaves the order of a call's arguments open.
        float pick = rng_1d(rng) * total;
        vec2 u = rng_2d(rng);
        if (pick < w_smooth || !(w_smooth < total)) {
            note_decision(DECISION_SMOOTH_LOBES);
            vec3 d = from_basis(basis_around(hit.normal), sample_hemisphere(hemisphere_rule(), u.x, u.y));
            float cos_theta = dot(d, hit.normal);
            vec3 g = vec3(0.0f);
            if (cos_theta > 0.0f && dot(d, hit.geo_normal) > 0.0f) {
                g = paper_gl(Ray(offset_ray_origin(p, hit.geo_normal), d), max_bounces() - bounce, rng, s);
            }
            if (!any(greaterThan(g, vec3(0.0f)))) {
                s.dropped = true;
                return;
            }
            vec3 local = phong_term(m, lobes.diffuse.albedo, hit.normal, d, cos_theta, -ray.dir);
            // The smooth lobes carry smooth_share of a material that is partly glass.
            s.radiance += beta * (total / w_smooth) * lobes.smooth_share * local * g;
            return;
        }
        ray = scatter_delta(ray, hit, p, lobes, total, pick, u, beta, media);
        s.bounce_rays += 1u;
    }
}

void global_sample(Ray eye, INOUT(Rng) rng, INOUT(SampleResult) s) {
    if (estimator() == ESTIMATOR_PAPER) {
        paper_sample(eye, rng, s);
    } else {
        path_sample(eye, rng, s);
    }
}

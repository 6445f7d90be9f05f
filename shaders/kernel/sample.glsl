// One sample of one pixel: the unit of work of one invocation (docs/architecture.md), and the
// single entry point that both the compute shader and the reference renderer call.

// A ray waiting to be traced, with the factor its radiance is weighed by in the
// pixel, its generation (0 for the eye ray) and the glass it is inside
// (lobes/glass.glsl's media; 0 for air).
struct PendingRay {
    Ray ray;
    vec3 weight;
    uint depth;
    uvec4 media;
};

// The rays of the reflection/refraction tree still to trace. GLSL has no recursion,
// so the tree is walked depth first by a loop that goes on with one child of each
// hit and stacks the other: the stack holds at most one ray per generation, so
// max_depth up to RAY_STACK_SIZE never overflows it (nor does any depth of mirrors
// alone, which never branch); beyond that a ray that finds it full is dropped and
// counted.
struct RayQueue {
    PendingRay next;   // the ray traced after this hit, when has_next
    bool has_next;
    uint top;
    PendingRay stack[RAY_STACK_SIZE];
};

// Queues a secondary ray, unless its weight is below the threshold
// (min_ray_weight(); 0 keeps every ray, as the SPD rules ask). True if queued.
bool queue_ray(PendingRay r, INOUT(RayQueue) q, INOUT(SampleResult) s) {
    bool light = max(r.weight.x, max(r.weight.y, r.weight.z)) < min_ray_weight();
    note_decision(light ? DECISION_RAY_TOO_LIGHT : DECISION_RAY_QUEUED);
    if (light) {
        s.dropped_weight += 1u;
        return false;
    }
    if (!q.has_next) {
        q.next = r;
        q.has_next = true;
    } else if (q.top < RAY_STACK_SIZE) {
        q.stack[q.top] = r;
        q.top += 1u;
    } else {
        s.dropped_stack += 1u;
        return false;
    }
    return true;
}

// The children of a hit on a mirror or glass: a reflection ray when the material
// reflects or transmits (the SPD rule: glass reflects too), a refraction ray when it
// transmits and the light is not totally reflected. Without Fresnel weighting the
// weights are the material's reflect and transmit colours (the paper's and the
// SPD's model; total internal reflection sends transmit's share along the
// reflection); with it, glass splits transmit by the Fresnel reflectance R:
// reflect + R * transmit reflected, (1 - R) * transmit refracted.
void spawn_children(PendingRay cur, Hit hit, INOUT(RayQueue) q, INOUT(SampleResult) s) {
    Material m = load_material(hit.material);
    vec3 reflect_weight = m.mirror;
    vec3 transmit = m.transmit;
    // A metallic-roughness material's glass is global mode's: here its diffuse lobe shades it.
    bool transmits = HAS_REFRACTION && !(m.ggx_alpha > 0.0f) && any(greaterThan(transmit, vec3(0.0f)));
    bool reflects = (HAS_REFLECTION && any(greaterThan(reflect_weight, vec3(0.0f)))) || transmits;
    if (!reflects || cur.depth >= max_depth()) {
        return;
    }
    precise vec3 p = cur.ray.origin + hit.t * cur.ray.dir;
    uint depth = cur.depth + 1u;
    if (transmits) {
        // Entering through the front face goes from the ray's medium into the
        // material; leaving through the back face goes the other way.
        float ior = m.ior;
        Refraction r = refract_fresnel(cur.ray.dir, hit.normal, interface_eta(cur.media, ior, hit.front_face));
        note_decision(r.total ? DECISION_TOTAL_REFLECTION : DECISION_REFRACTED);
        bool fresnel = m.fresnel != 0u;
        float share = r.total ? 1.0f : (fresnel ? r.reflectance : 0.0f);
        reflect_weight += share * transmit;
        if (!r.total) {
            Ray refracted = Ray(offset_ray_origin(p, -hit.geo_normal), r.dir);
            vec3 w = cur.weight * transmit * (fresnel ? 1.0f - r.reflectance : 1.0f);
            uvec4 media = media_after_refraction(cur.media, hit.material, hit.front_face);
            if (queue_ray(PendingRay(refracted, w, depth, media), q, s)) {
                s.refraction_rays += 1u;
            }
        }
    }
    Ray mirrored = Ray(offset_ray_origin(p, hit.geo_normal), mirror_direction(cur.ray.dir, hit.normal));
    if (queue_ray(PendingRay(mirrored, cur.weight * reflect_weight, depth, cur.media), q, s)) {
        s.reflection_rays += 1u;
    }
}

// Traces one ray of the tree and adds its weighed local shading, or the background.
Hit trace_and_shade(PendingRay r, INOUT(Rng) rng, INOUT(SampleResult) s) {
    Hit hit = closest_hit(r.ray, INFINITY_T);
    if (hit.t < INFINITY_T) {
        // Shading, and the mirror and refraction rays it spawns, see the mapped normal.
        hit.normal = mapped_normal(hit, -r.ray.dir);
        if (r.depth == 0u) {
            note_first_hit(hit, s);
        }
        s.radiance += r.weight * shade_local(r.ray, hit, rng, s.shadow_rays);
    } else {
        s.radiance += r.weight * sky(r.ray.dir);
    }
    return hit;
}

// The whole tree below the eye ray, depth first.
void trace_ray_tree(PendingRay eye, INOUT(Rng) rng, INOUT(SampleResult) s) {
    PendingRay cur = eye;
    RayQueue q;
    q.next = eye;
    q.top = 0u;
    loop_enter();
    while (loop_tick()) {
        q.has_next = false;
        Hit hit = trace_and_shade(cur, rng, s);
        if (hit.t < INFINITY_T) {
            spawn_children(cur, hit, q, s);
        }
        if (q.has_next) {
            cur = q.next;
        } else if (q.top > 0u) {
            q.top -= 1u;
            cur = q.stack[q.top];
        } else {
            break;
        }
    }
}

SampleResult render_sample(uint px, uint py, uint sample_index) {
    work_reset();
    SampleResult s = SampleResult(vec3(0.0f), 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, false, false, vec3(0.0f),
                                  vec3(0.0f), 0.0f);
    Rng rng = rng_start(py * image_width() + px, sample_index, sample_seed());
    if (HAS_ALPHA) {
        alpha_start_sample(rng);
    }
    vec2 sub = subpixel_position(sample_index, rng);
    vec2 lens = lens_position(rng);
    rng_seek(rng, SLOT_PATH);
    PendingRay eye = PendingRay(camera_ray(float(px) + sub.x, float(py) + sub.y, lens), vec3(1.0f), 0u, uvec4(0u));
    // A scene without mirrors or glass skips the tree's loop and its stack.
    if (HAS_GLOBAL) {
        global_sample(eye.ray, rng, s);
    } else if (HAS_REFLECTION || HAS_REFRACTION) {
        trace_ray_tree(eye, rng, s);
    } else {
        trace_and_shade(eye, rng, s);
    }
    s.decisions = g_decisions;
    s.cells_visited = g_cells_visited;
    s.intersection_tests = g_intersection_tests;
    s.truncated = budget_exhausted() || driver_cut_loops();
    return s;
}

// Adds a sample to its pixel's sums (sums.glsl). Truncated, non-finite and dropped
// (paper estimator) samples add no radiance and are not counted in the sums' sample
// count, only in their counters, so the host can report them and the average stays
// that of the good samples.
void accumulate_sample(SampleResult s, INOUT(PixelSum) sum, INOUT(Counters) counters) {
    counters.rays[RAYS_EYE] += 1u;
    counters.rays[RAYS_SHADOW] += s.shadow_rays;
    counters.rays[RAYS_REFLECTION] += s.reflection_rays;
    counters.rays[RAYS_REFRACTION] += s.refraction_rays;
    counters.work[WORK_CELLS] += s.cells_visited;
    counters.work[WORK_TESTS] += s.intersection_tests;
    counters.tree[TREE_EYE_HITS] += s.eye_hits;
    counters.tree[TREE_DROPPED_WEIGHT] += s.dropped_weight;
    counters.tree[TREE_DROPPED_STACK] += s.dropped_stack;
    counters.tree[TREE_DECISIONS] += s.decisions;   // wraps; a sum, so any split adds up alike
    counters.paths[PATHS_BOUNCE_RAYS] += s.bounce_rays;
    counters.paths[PATHS_ROULETTE] += s.roulette;
    float total = s.radiance.x + s.radiance.y + s.radiance.z;
    if (s.truncated) {
        counters.work[WORK_TRUNCATED] += 1u;
    } else if (s.dropped) {
        counters.paths[PATHS_PAPER_DROPPED] += 1u;
    } else if (!is_finite_bits(total)) {
        counters.work[WORK_NONFINITE] += 1u;
    } else {
        add_sample(sum, s.radiance, HAS_SQUARES);
    }
}

// Adds a sample's eye-ray hit to its pixel's render passes (HAS_PASSES): every
// sample whose eye ray hit a surface, whatever became of its radiance.
void accumulate_passes(SampleResult s, INOUT(PassSums) passes) {
    if (s.eye_hits != 0u) {
        add_first_hit(passes, s.first_albedo, s.first_normal, s.first_depth);
    }
}

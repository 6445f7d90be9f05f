// One sample of one pixel: the unit of work of one invocation (DESIGN.md), and the
// single entry point that both the compute shader and the reference renderer call.

struct SampleResult {
    vec3 radiance;
    uint shadow_rays;
    bool truncated;   // the loop budget ran out: the radiance is incomplete
};

SampleResult render_sample(uint px, uint py, uint sample_index) {
    g_loop_iterations = 0u;
    Rng rng = rng_start(py * params.image.x + px, sample_index, params.image.w);
    vec2 sub = subpixel_position(sample_index, rng);
    Ray ray = camera_ray(float(px) + sub.x, float(py) + sub.y);
    uint shadow_rays = 0u;
    vec3 radiance = vec3(params.background);
    Hit hit = closest_hit(ray, INFINITY_T);
    if (hit.t < INFINITY_T) {
        radiance = shade_local(ray, hit, shadow_rays);
    }
    return SampleResult(radiance, shadow_rays, budget_exhausted());
}

// Adds a sample to its pixel's running sums. Truncated or non-finite samples add no
// radiance and are not counted in accum's sample count, only in their counters, so
// the host can report them and the average stays that of the good samples.
void accumulate_sample(SampleResult s, INOUT(vec4) accum, INOUT(uvec4) counters) {
    counters[COUNTER_EYE_RAYS] += 1u;
    counters[COUNTER_SHADOW_RAYS] += s.shadow_rays;
    float sum = s.radiance.x + s.radiance.y + s.radiance.z;
    if (s.truncated) {
        counters[COUNTER_TRUNCATED] += 1u;
    } else if (isnan(sum) || isinf(sum)) {
        counters[COUNTER_NONFINITE] += 1u;
    } else {
        accum += vec4(s.radiance, 1.0f);
    }
}

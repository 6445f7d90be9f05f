// One sample of one pixel: the unit of work of one invocation (DESIGN.md), and the
// single entry point that both the compute shader and the reference renderer call.

struct SampleResult {
    vec3 radiance;
    uint shadow_rays;
    uint cells_visited;
    uint intersection_tests;
    bool truncated;   // the loop budget ran out: the radiance is incomplete
};

SampleResult render_sample(uint px, uint py, uint sample_index) {
    work_reset();
    Rng rng = rng_start(py * params.image.x + px, sample_index, params.image.w);
    vec2 sub = subpixel_position(sample_index, rng);
    Ray ray = camera_ray(float(px) + sub.x, float(py) + sub.y);
    uint shadow_rays = 0u;
    vec3 radiance = vec3(params.background);
    Hit hit = closest_hit(ray, INFINITY_T);
    if (hit.t < INFINITY_T) {
        radiance = shade_local(ray, hit, rng, shadow_rays);
    }
    return SampleResult(radiance, shadow_rays, g_cells_visited, g_intersection_tests, budget_exhausted());
}

// Adds a sample to its pixel's running sums. Truncated or non-finite samples add no
// radiance and are not counted in accum's sample count, only in their counters, so
// the host can report them and the average stays that of the good samples.
void accumulate_sample(SampleResult s, INOUT(vec4) accum, INOUT(Counters) counters) {
    counters.rays[RAYS_EYE] += 1u;
    counters.rays[RAYS_SHADOW] += s.shadow_rays;
    counters.work[WORK_CELLS] += s.cells_visited;
    counters.work[WORK_TESTS] += s.intersection_tests;
    float sum = s.radiance.x + s.radiance.y + s.radiance.z;
    if (s.truncated) {
        counters.work[WORK_TRUNCATED] += 1u;
    } else if (isnan(sum) || isinf(sum)) {
        counters.work[WORK_NONFINITE] += 1u;
    } else {
        accum += vec4(s.radiance, 1.0f);
    }
}

// What one sample of one pixel returns (sample.glsl, global.glsl): its radiance and
// what it did, for the per-pixel Counters.

struct SampleResult {
    vec3 radiance;
    uint shadow_rays;
    uint reflection_rays;
    uint refraction_rays;
    uint eye_hits;         // 1 when the eye ray hit something
    uint dropped_weight;   // secondary rays left out for their low weight
    uint dropped_stack;    // secondary rays left out because the stack was full
    uint decisions;        // the hash of its decisions (budget.glsl)
    uint cells_visited;
    uint intersection_tests;
    uint bounce_rays;      // global mode: rays traced after a scattering event
    uint roulette;         // global mode: 1 when Russian roulette ended the path
    bool dropped;          // the paper estimator's gl() was 0: not part of the average
    bool truncated;   // the loop budget ran out: the radiance is incomplete
    // The eye ray's hit, for the render passes (HAS_PASSES; when eye_hits is 1): its
    // base colour, shading normal and distance from the eye.
    vec3 first_albedo;
    vec3 first_normal;
    float first_depth;
};

// Notes the eye ray's hit for the render passes: `hit` with its shading normal.
void note_first_hit(Hit hit, INOUT(SampleResult) s) {
    s.eye_hits = 1u;
    if (HAS_PASSES) {
        s.first_albedo = surface_base_colour(hit);
        s.first_normal = hit.normal;
        s.first_depth = hit.t;
    }
}

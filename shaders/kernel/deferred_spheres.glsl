// Brute force's sphere loop for rays that need the nearest hit, on SIMD hardware that
// runs both sides of a branch (docs/decisions/0003-deferred-sphere-tests.md): spheres
// the ray starts near, which need the error-free test, are set aside and tested after
// the loop. Included by traversal.glsl before brute_force_trace; the feature
// DEFERRED_SPHERES turns it on.

// Few spheres need the error-free test for any one ray: the one it leaves, and
// neighbours touching it. Four are kept at a time, by selects rather than an indexed
// array (which lavapipe keeps in memory), and tested after the loop; a ray that met
// more loops again for the next four. The host turns DEFERRED_SPHERES on from 8
// spheres: below that the loops after the sphere loop cost more than they save. Shadow
// rays need no error-free c (sphere_blocks) and test every sphere in place.
struct DeferredSpheres {
    uint count;   // near spheres met so far in this pass of the loop
    uint first;   // the count at which this pass's slots start: 0, 4, 8, ...
    uvec4 slots;  // near spheres first to first + 3
};

// One test of a brute-force loop: the rounded-c test, or the sphere deferred.
void test_sphere_or_defer(Ray ray, uint index, INOUT(Nearest) nearest, INOUT(DeferredSpheres) deferred) {
    g_intersection_tests += 1u;
    Sphere s = load_sphere(index);
    SphereSetup setup = sphere_setup(ray, vec3(s.center_radius), s.center_radius.w);
    if (sphere_needs_exact_c(setup)) {
        uint k = deferred.count - deferred.first;   // wraps to a large number before `first`
        deferred.slots.x = k == 0u ? index : deferred.slots.x;
        deferred.slots.y = k == 1u ? index : deferred.slots.y;
        deferred.slots.z = k == 2u ? index : deferred.slots.z;
        deferred.slots.w = k == 3u ? index : deferred.slots.w;
        deferred.count += 1u;
    } else {
        set_sphere_nearest(index, sphere_rounded_c_test(ray, setup, 0.0f, nearest.t), nearest);
    }
}

// The error-free test of a deferred sphere (counted when it was deferred).
void test_sphere_exact(Ray ray, uint index, INOUT(Nearest) nearest) {
    Sphere s = load_sphere(index);
    vec3 center = vec3(s.center_radius);
    SphereSetup setup = sphere_setup(ray, center, s.center_radius.w);
    set_sphere_nearest(index, sphere_exact_c_test(ray, center, s.center_radius.w, setup, 0.0f, nearest.t),
                       nearest);
}

// This pass's deferred spheres, error-free. A loop rather than four tests in a row:
// lavapipe would make all four for every ray, and most rays have one (the sphere
// they leave) or none (eye rays). Bottom-tested: one pass, masked, when no lane has
// any.
void test_deferred_slots(Ray ray, DeferredSpheres deferred, INOUT(Nearest) nearest) {
    uint n = deferred.count > deferred.first ? min(deferred.count - deferred.first, 4u) : 0u;
    uint k = 0u;
    loop_enter();
    do {
        if (k < n) {
            uvec4 s = deferred.slots;
            test_sphere_exact(ray, k == 0u ? s.x : (k == 1u ? s.y : (k == 2u ? s.z : s.w)), nearest);
        }
        k += 1u;
    } while (k < n && loop_tick());
}

// The brute-force sphere loop of a ray that needs its nearest hit. A second pass only
// for a ray that met more than four near spheres: it counts every sphere again, tests
// again those it does not defer, and keeps the next four of those it does.
void trace_spheres_deferring_near_ones(Ray ray, INOUT(Nearest) nearest) {
    DeferredSpheres deferred = DeferredSpheres(0u, 0u, uvec4(0u));
    loop_enter();
    do {
        deferred.count = 0u;
        loop_enter();
        for (uint i = 0u; i < sphere_count() && loop_tick(); ++i) {
            test_sphere_or_defer(ray, i, nearest, deferred);
        }
        if (!budget_exhausted()) {
            test_deferred_slots(ray, deferred, nearest);
        }
        deferred.first += 4u;
    } while (deferred.count > deferred.first && loop_tick());
}

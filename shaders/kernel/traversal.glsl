// Visibility queries over the scene: the closest hit along a ray, and whether
// anything blocks a shadow ray. With HAS_GRID they walk the uniform grid
// (grid.glsl); without it they test every primitive (brute force), which is faster
// for scenes of a few primitives (the host decides: host/accel/accel_policy.hpp).
// Every primitive test is one budgeted loop iteration and one counted test.
//
// Each loop tests one kind of primitive only. SIMD hardware runs both sides of a
// branch whose condition differs between lanes (lavapipe does so for every branch),
// so a loop over mixed kinds would pay for a sphere test and a triangle test on
// every iteration. The grid therefore lists each cell's primitives grouped by kind,
// spheres, triangles, rings, cylinders (host/accel/grid.cpp), and the kernel walks
// them in one loop per kind, each stopping at the first reference of another kind.
// A kind the scene lacks is compiled out with its HAS_ feature.

// The nearest hit so far: the primitive's reference and its distance.
struct Nearest {
    float t;          // the bound for further tests: t_max until something is hit
                      // (a shadow ray's sphere blocker leaves it: the trace ends there)
    uint ref;         // REF_NONE until something is hit
    TriangleHit tri;  // barycentrics, when ref is a triangle
    uint part;        // CYLINDER_SIDE, _BASE_CAP or _TOP_CAP, when ref is a cylinder
};

void set_sphere_nearest(uint index, float t, INOUT(Nearest) nearest) {
    if (t < nearest.t) {
        nearest.t = t;
        nearest.ref = (REF_SPHERE << REF_KIND_SHIFT) | index;
    }
}

void test_sphere(Ray ray, uint index, INOUT(Nearest) nearest) {
    g_intersection_tests += 1u;
    vec4 s = load_sphere(index).center_radius;
    set_sphere_nearest(index, intersect_sphere(ray, vec3(s), s.w, 0.0f, nearest.t), nearest);
}

// A shadow ray's sphere test: whether the sphere blocks it, not where (sphere_blocks).
// A blocker sets only the reference; the trace ends there.
void test_sphere_blocks(Ray ray, uint index, INOUT(Nearest) nearest) {
    g_intersection_tests += 1u;
    vec4 s = load_sphere(index).center_radius;
    if (sphere_blocks(ray, vec3(s), s.w, nearest.t)) {
        nearest.ref = (REF_SPHERE << REF_KIND_SHIFT) | index;
    }
}

// The sphere test for the ray's question: where it first meets the sphere, or, with
// any_hit, whether it meets it at all. The sphere is read inside each test: read by the
// caller and passed in, the CPU backend's sphere loops ran up to 1.1x slower.
void test_sphere_for(Ray ray, uint index, bool any_hit, INOUT(Nearest) nearest) {
    if (any_hit) {
        test_sphere_blocks(ray, index, nearest);
    } else {
        test_sphere(ray, index, nearest);
    }
}

void test_triangle(Ray ray, uint index, INOUT(Nearest) nearest) {
    g_intersection_tests += 1u;
    Triangle tri = load_triangle(index);
    vec3 p0 = vec3(tri.p0);
    vec3 p1 = vec3(tri.p1);
    vec3 p2 = vec3(tri.p2);
    TriangleHit th;
    if (HAS_QUADS) {
        // One test for both shapes, the fourth vertex picked by a select: SIMD
        // hardware would run both tests on a branch.
        precise vec3 p3 = tri.meta.z == SHAPE_TRIANGLE ? p2 : p0 + (p2 - p1);
        th = intersect_quad(ray, p0, p1, p2, p3, 0.0f, nearest.t);
    } else {
        th = intersect_triangle(ray, p0, p1, p2, 0.0f, nearest.t);
    }
    if (th.t < nearest.t) {
        nearest.t = th.t;
        nearest.ref = (REF_TRIANGLE << REF_KIND_SHIFT) | index;
        nearest.tri = th;
    }
}

void test_ring(Ray ray, uint index, INOUT(Nearest) nearest) {
    g_intersection_tests += 1u;
    Ring r = load_ring(index);
    float t = intersect_ring(ray, vec3(r.center_inner), vec3(r.normal_outer), r.center_inner.w,
                             r.normal_outer.w, 0.0f, nearest.t);
    if (t < nearest.t) {
        nearest.t = t;
        nearest.ref = (REF_RING << REF_KIND_SHIFT) | index;
    }
}

void test_cylinder(Ray ray, uint index, INOUT(Nearest) nearest) {
    g_intersection_tests += 1u;
    Cylinder c = load_cylinder(index);
    CylinderHit ch = intersect_cylinder(ray, vec3(c.base_radius), vec3(c.top_capped), c.base_radius.w,
                                        c.top_capped.w != 0.0f, 0.0f, nearest.t);
    if (ch.t < nearest.t) {
        nearest.t = ch.t;
        nearest.ref = (REF_CYLINDER << REF_KIND_SHIFT) | index;
        nearest.part = ch.part;
    }
}

// The reference after i in a cell whose references end before `end`, or REF_NONE
// past them. The fetch is clamped into the cell because SIMD hardware fetches for
// every lane, whichever value the select keeps.
uint next_ref(INOUT(uint) i, uint end) {
    i += 1u;
    uint ref = load_ref(min(i, end - 1u));
    return i < end ? ref : REF_NONE;
}

// True when `any_hit` is set (a shadow ray) and something was hit: the trace is over.
bool blocker_found(bool any_hit, Nearest nearest) {
    return any_hit && nearest.ref != REF_NONE;
}

// True once the trace can end early: the loop budget ran out, or a blocker was found.
bool trace_done(bool any_hit, Nearest nearest) {
    return budget_exhausted() || blocker_found(any_hit, nearest);
}

// Every loop of the traversal leaves at one place only: its condition, which ticks
// the budget and asks whether a shadow ray found its blocker. Written with a break at
// the top for the budget and a return after the test for the blocker, the same loops,
// making the same tests, ran slower on lavapipe
// (docs/decisions/0017-loop-shapes-for-simd.md).

// Tests the primitives listed for one grid cell, references i to end - 1 (i < end):
// its spheres, triangles, rings and cylinders, in that order, one loop per kind the
// list may hold (with_: constants at each call, so the compilers drop the others).
// The grid's loose primitives are such a list too, tested before the walk.
// False means "stop the walk": the loop budget ran out, or `any_hit` is set and
// something was hit.
//
// The loops check their condition at the bottom: a loop that checks first runs its
// body once more on SIMD hardware, with every lane masked off, to find that all
// lanes are done (lavapipe does, see budget.glsl); here that would be one wasted
// primitive test per kind and cell. The first test of each loop needs no tick: a
// loop reached with the budget spent tests one primitive and stops.
bool test_cell(Ray ray, uint i, uint end, bool any_hit, bool with_spheres, bool with_triangles, bool with_rings,
               bool with_cylinders, INOUT(Nearest) nearest) {
    uint ref = load_ref(i);
    if (with_spheres && (ref >> REF_KIND_SHIFT) == REF_SPHERE) {
        loop_enter();
        do {
            test_sphere_for(ray, ref & REF_INDEX_MASK, any_hit, nearest);
            ref = next_ref(i, end);
        } while (loop_tick() && (ref >> REF_KIND_SHIFT) == REF_SPHERE && !blocker_found(any_hit, nearest));
        if (trace_done(any_hit, nearest)) {
            return false;
        }
    }
    if (with_triangles && (ref >> REF_KIND_SHIFT) == REF_TRIANGLE) {
        loop_enter();
        do {
            test_triangle(ray, ref & REF_INDEX_MASK, nearest);
            ref = next_ref(i, end);
        } while (loop_tick() && (ref >> REF_KIND_SHIFT) == REF_TRIANGLE && !blocker_found(any_hit, nearest));
        if (trace_done(any_hit, nearest)) {
            return false;
        }
    }
    if (with_rings && (ref >> REF_KIND_SHIFT) == REF_RING) {
        loop_enter();
        do {
            test_ring(ray, ref & REF_INDEX_MASK, nearest);
            ref = next_ref(i, end);
        } while (loop_tick() && (ref >> REF_KIND_SHIFT) == REF_RING && !blocker_found(any_hit, nearest));
        if (trace_done(any_hit, nearest)) {
            return false;
        }
    }
    if (with_cylinders && (ref >> REF_KIND_SHIFT) == REF_CYLINDER) {
        loop_enter();
        do {
            test_cylinder(ray, ref & REF_INDEX_MASK, nearest);
            ref = next_ref(i, end);
        } while (loop_tick() && (ref >> REF_KIND_SHIFT) == REF_CYLINDER && !blocker_found(any_hit, nearest));
        if (trace_done(any_hit, nearest)) {
            return false;
        }
    }
    return true;
}

// True once the nearest hit so far lies within the current cell: the walk can stop.
HOT bool grid_cell_done(vec3 t_next, Nearest nearest) {
    return nearest.t <= min(t_next.x, min(t_next.y, t_next.z));
}

// Moves the walk past the current cell: false when it must stop instead (budget,
// a hit within the cell, or the ray leaves the grid).
HOT bool grid_advance(Ray ray, INOUT(GridWalk) w, Nearest nearest) {
    return loop_tick() && !grid_cell_done(w.t_next, nearest) && grid_walk_step(ray, w);
}

// Walks the grid along the ray. closest_hit (any_hit false) stops once the nearest
// hit so far lies within the current cell: a primitive found in a cell may lie
// beyond it (it spans several cells) while a nearer one waits in the next cell, so a
// hit beyond the cell's exit is only kept as the bound for the tests that follow.
// The result is the nearest hit among the primitives tested, which is the
// brute-force result: every primitive the ray meets before that hit lies in a cell
// the walk visited. occluded (any_hit true) stops at the first hit of any kind.
//
// Empty cells are stepped through in a loop of their own, before the cell's tests
// ("speculative" traversal, after Aila & Laine, "Understanding the Efficiency of Ray
// Traversal on GPUs", 2009). On SIMD hardware the lanes of a vector run each loop as
// often as the busiest lane needs, and a loop's body runs at least once, masked, even
// when no lane needs it (lavapipe also runs both sides of every branch). Walking one
// cell per iteration therefore paid for a primitive test of every kind in every cell,
// empty or not; now every lane still walking reaches a cell with something to test
// first. The cells visited, the tests made and the result are the same as walking one
// cell at a time (docs/decisions/0017-loop-shapes-for-simd.md).
void grid_trace(Ray ray, bool any_hit, INOUT(Nearest) nearest) {
    GridWalk w = grid_walk_start(ray, nearest.t);
    if (!w.inside) {
        return;
    }
    bool walking = true;
    loop_enter();
    do {
        loop_enter();
        while (walking && w.start == w.end) {
            g_cells_visited += 1u;
            walking = grid_advance(ray, w, nearest);
        }
        if (walking) {
            g_cells_visited += 1u;
            walking = test_cell(ray, w.start, w.end, any_hit, GRID_SPHERES, GRID_TRIANGLES, GRID_RINGS,
                                GRID_CYLINDERS, nearest) &&
                      grid_advance(ray, w, nearest);
        }
    } while (walking);
}

#include "deferred_spheres.glsl"

// Every primitive, one loop per kind: scenes too small to gain from the grid. Shadow
// rays (any_hit) never defer a sphere and take the in-place loop.
void brute_force_trace(Ray ray, bool any_hit, INOUT(Nearest) nearest) {
    if (HAS_SPHERES && DEFERRED_SPHERES && !any_hit) {
        trace_spheres_deferring_near_ones(ray, nearest);
        if (trace_done(any_hit, nearest)) {
            return;
        }
    }
    if (HAS_SPHERES && (!DEFERRED_SPHERES || any_hit)) {
        loop_enter();
        for (uint i = 0u; i < sphere_count() && loop_tick() && !blocker_found(any_hit, nearest); ++i) {
            test_sphere_for(ray, i, any_hit, nearest);
        }
        if (trace_done(any_hit, nearest)) {
            return;
        }
    }
    if (HAS_TRIANGLES) {
        loop_enter();
        for (uint i = 0u; i < triangle_count() && loop_tick() && !blocker_found(any_hit, nearest); ++i) {
            test_triangle(ray, i, nearest);
        }
        if (trace_done(any_hit, nearest)) {
            return;
        }
    }
    if (HAS_RINGS) {
        loop_enter();
        for (uint i = 0u; i < ring_count() && loop_tick() && !blocker_found(any_hit, nearest); ++i) {
            test_ring(ray, i, nearest);
        }
        if (trace_done(any_hit, nearest)) {
            return;
        }
    }
    if (HAS_CYLINDERS) {
        loop_enter();
        for (uint i = 0u; i < cylinder_count() && loop_tick() && !blocker_found(any_hit, nearest); ++i) {
            test_cylinder(ray, i, nearest);
        }
    }
}

// The grid's loose primitives (references 0 to cell 0's start, grouped by kind like a
// cell's) come first: a hit among them bounds the walk, and ends a shadow ray at once.
// One list for a kind with few primitives and for the few whose boxes would stretch
// the grid, rather than a loop over each such kind's array: every copy of a loop
// lavapipe inlines costs it time when it creates the pipeline (docs/grid.md).
Nearest trace(Ray ray, float t_max, bool any_hit) {
    Nearest nearest = Nearest(t_max, REF_NONE, TriangleHit(INFINITY_T, 0.0f, 0.0f), CYLINDER_SIDE);
    if (HAS_GRID) {
        uint loose = (LOOSE_SPHERES || LOOSE_TRIANGLES || LOOSE_RINGS || LOOSE_CYLINDERS) ? load_grid_node(0u) : 0u;
        if (loose != 0u) {   // test_cell needs a reference to test (the reference's tests turn every feature on)
            test_cell(ray, 0u, loose, any_hit, LOOSE_SPHERES, LOOSE_TRIANGLES, LOOSE_RINGS, LOOSE_CYLINDERS, nearest);
        }
        if (!blocker_found(any_hit, nearest)) {
            grid_trace(ray, any_hit, nearest);
        }
    } else {
        brute_force_trace(ray, any_hit, nearest);
    }
    return nearest;
}

Hit sphere_hit(Ray ray, uint index, float t) {
    Sphere s = load_sphere(index);
    vec3 center = vec3(s.center_radius);
    precise vec3 p = ray.origin + t * ray.dir;
    // Normalized, not divided by the radius: far from the origin p carries the
    // rounding of its magnitude, and (p - c) / r drifts off unit length.
    vec3 n = unit_vector(p - center);
    bool front = dot(n, ray.dir) < 0.0f;
    vec3 facing = front ? n : -n;
    return Hit(t, facing, facing, vec3(0.0f), s.meta.x, front, (REF_SPHERE << REF_KIND_SHIFT) | index, vec2(0.0f));
}

// The texture coordinates at a hit of weights u (of p1) and v (of p2). A
// parallelogram's weights are half its coordinates along its edges
// (intersect_quad), at which its corners' coordinates are extended.
vec2 triangle_uv(Triangle tri, float u, float v) {
    vec2 t0 = vec2(tri.p0.w, tri.p1.w);
    vec2 t1 = vec2(tri.p2.w, tri.n0.w);
    vec2 t2 = vec2(tri.n1.w, tri.n2.w);
    if (HAS_QUADS && tri.meta.z != SHAPE_TRIANGLE) {
        return t0 + (2.0f * u) * (t1 - t0) + (2.0f * v) * (t2 - t1);
    }
    return t0 + u * (t1 - t0) + v * (t2 - t0);
}

Hit triangle_hit(Ray ray, uint index, TriangleHit th) {
    Triangle tri = load_triangle(index);
    vec3 ng = triangle_face_normal(vec3(tri.p0), vec3(tri.p1), vec3(tri.p2));
    vec3 ns = ng;
    if (HAS_SMOOTH_NORMALS && tri.meta.y != 0u) {
        ns = interpolate_normal(vec3(tri.n0), vec3(tri.n1), vec3(tri.n2), th.u, th.v, ng);
    }
    bool front = dot(ng, ray.dir) < 0.0f;
    vec3 g = front ? ng : -ng;
    // The shading normal must lie on the viewer's side of the surface too.
    bool flip = dot(ns, g) < 0.0f;
    note_decision(flip ? DECISION_NORMAL_FLIPPED : DECISION_NORMAL_KEPT);
    vec3 s = flip ? -ns : ns;
    vec3 lift = vec3(0.0f);
    if (HAS_TERMINATOR && tri.meta.y != 0u) {
        lift = terminator_lift(tri, th.u, th.v, flip ? -1.0f : 1.0f, g);
    }
    vec2 uv = vec2(0.0f);
    if (HAS_TEXTURES) {
        uv = triangle_uv(tri, th.u, th.v);
    }
    return Hit(th.t, s, g, lift, tri.meta.x, front, (REF_TRIANGLE << REF_KIND_SHIFT) | index, uv);
}

// Rings and cylinders have no shading normals of their own: both normals are the
// geometric one, turned toward the ray; the front face is the ring's given normal
// side and the cylinder's outside. An open cylinder seen from within is its back face.
Hit ring_hit(Ray ray, uint index, float t) {
    Ring r = load_ring(index);
    vec3 n = vec3(r.normal_outer);
    bool front = dot(n, ray.dir) < 0.0f;
    vec3 facing = front ? n : -n;
    return Hit(t, facing, facing, vec3(0.0f), r.meta.x, front, (REF_RING << REF_KIND_SHIFT) | index, vec2(0.0f));
}

Hit cylinder_hit(Ray ray, uint index, float t, uint part) {
    Cylinder c = load_cylinder(index);
    precise vec3 p = ray.origin + t * ray.dir;
    vec3 n = cylinder_normal(vec3(c.base_radius), vec3(c.top_capped), p, part);
    bool front = dot(n, ray.dir) < 0.0f;
    vec3 facing = front ? n : -n;
    return Hit(t, facing, facing, vec3(0.0f), c.meta.x, front, (REF_CYLINDER << REF_KIND_SHIFT) | index, vec2(0.0f));
}

Hit make_hit(Ray ray, Nearest nearest) {
    if (nearest.ref == REF_NONE) {
        return no_hit();
    }
    uint index = nearest.ref & REF_INDEX_MASK;
    uint kind = nearest.ref >> REF_KIND_SHIFT;
    if (kind == REF_SPHERE) {
        return sphere_hit(ray, index, nearest.t);
    }
    if (HAS_RINGS && kind == REF_RING) {
        return ring_hit(ray, index, nearest.t);
    }
    if (HAS_CYLINDERS && kind == REF_CYLINDER) {
        return cylinder_hit(ray, index, nearest.t, nearest.part);
    }
    return triangle_hit(ray, index, nearest.tri);
}

// The closest hit with t in (0, t_max).
Hit closest_hit(Ray ray, float t_max) {
    Nearest nearest = trace(ray, t_max, false);
    Hit hit = make_hit(ray, nearest);
    // What was hit, which part of it (a cylinder's side or cap), and from which side:
    // near wall or far wall, outside or in, are decisions too.
    note_decision(nearest.ref);
    if (HAS_CYLINDERS && (nearest.ref >> REF_KIND_SHIFT) == REF_CYLINDER) {
        note_decision(nearest.part);
    }
    note_decision(hit.front_face ? DECISION_FRONT_FACE : DECISION_BACK_FACE);
    return hit;
}

// True when anything lies on the ray with t in (0, t_max): shadow rays stop at the
// first blocker, whichever it is and wherever on the ray it lies.
bool occluded(Ray ray, float t_max) {
    bool blocked = trace(ray, t_max, true).ref != REF_NONE;
    note_decision(blocked ? DECISION_BLOCKED : DECISION_UNBLOCKED);
    return blocked;
}

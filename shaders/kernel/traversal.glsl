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
// in the order of shapes/kinds.glsl (host/accel/grid.cpp), and the kernel walks them
// in one loop per kind, each stopping at the first reference of another kind. A kind
// the scene lacks is compiled out with its feature. The loops and the dispatch to a
// kind's hit record are generated from that table; each kind's tests and hit record
// live in its file, shapes/<name>.glsl.

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

// Tests the primitives listed for one grid cell, references i to end - 1 (i < end),
// kind by kind in the order of shapes/kinds.glsl, one loop per kind the list may hold
// (`loose`: the grid's loose list rather than a cell; a constant at each call, so the
// compilers drop the loops of the kinds it cannot hold). The grid's loose primitives
// are such a list too, tested before the walk. False means "stop the walk": the loop
// budget ran out, or `any_hit` is set and something was hit.
//
// The loops check their condition at the bottom: a loop that checks first runs its
// body once more on SIMD hardware, with every lane masked off, to find that all
// lanes are done (lavapipe does, see budget.glsl); here that would be one wasted
// primitive test per kind and cell. The first test of each loop needs no tick: a
// loop reached with the budget spent tests one primitive and stops.
bool test_cell(Ray ray, uint i, uint end, bool any_hit, bool loose, INOUT(Nearest) nearest) {
    uint ref = load_ref(i);
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS)                                           \
    if ((loose ? LOOSE_##NAMES : GRID_##NAMES) && (ref >> REF_KIND_SHIFT) == REF_##NAME) {                  \
        loop_enter();                                                                                       \
        do {                                                                                                \
            test_##name(ray, ref & REF_INDEX_MASK, any_hit, nearest);                                       \
            ref = next_ref(i, end);                                                                         \
        } while (loop_tick() && (ref >> REF_KIND_SHIFT) == REF_##NAME && !blocker_found(any_hit, nearest)); \
        if (trace_done(any_hit, nearest)) {                                                                 \
            return false;                                                                                   \
        }                                                                                                   \
    }
#include "shapes/kinds.glsl"
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
            walking = test_cell(ray, w.start, w.end, any_hit, false, nearest) && grid_advance(ray, w, nearest);
        }
    } while (walking);
}

#include "deferred_spheres.glsl"

// Whether brute force tests a kind in its own loop, in place: all but the spheres of
// a closest-hit ray when DEFERRED_SPHERES has them traced apart.
bool tested_in_place(uint kind, bool any_hit) {
    return kind != REF_SPHERE || !DEFERRED_SPHERES || any_hit;
}

// Every primitive, one loop per kind: scenes too small to gain from the grid. Shadow
// rays (any_hit) never defer a sphere and take the in-place loop.
void brute_force_trace(Ray ray, bool any_hit, INOUT(Nearest) nearest) {
    if (HAS_SPHERES && DEFERRED_SPHERES && !any_hit) {
        trace_spheres_deferring_near_ones(ray, nearest);
        if (trace_done(any_hit, nearest)) {
            return;
        }
    }
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS)                                       \
    if (HAS_##NAMES && tested_in_place(REF_##NAME, any_hit)) {                                          \
        loop_enter();                                                                                   \
        for (uint i = 0u; i < name##_count() && loop_tick() && !blocker_found(any_hit, nearest); ++i) { \
            test_##name(ray, i, any_hit, nearest);                                                      \
        }                                                                                               \
        if (trace_done(any_hit, nearest)) {                                                             \
            return;                                                                                     \
        }                                                                                               \
    }
#include "shapes/kinds.glsl"
}

// Whether the grid may have loose primitives, of any kind.
bool may_have_loose() {
    bool any = false;
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) any = any || LOOSE_##NAMES;
#include "shapes/kinds.glsl"
    return any;
}

// The grid's loose primitives (references 0 to cell 0's start, grouped by kind like a
// cell's) come first: a hit among them bounds the walk, and ends a shadow ray at once.
// One list for a kind with few primitives and for the few whose boxes would stretch
// the grid, rather than a loop over each such kind's array: every copy of a loop
// lavapipe inlines costs it time when it creates the pipeline (docs/grid.md).
Nearest trace(Ray ray, float t_max, bool any_hit) {
    Nearest nearest = Nearest(t_max, REF_NONE, vec2(0.0f), 0u);
    if (HAS_ALPHA) {
        alpha_start_ray();
    }
    if (HAS_GRID) {
        uint loose_end = may_have_loose() ? load_grid_node(0u) : 0u;
        if (loose_end != 0u) {   // test_cell needs a reference to test (the reference's tests turn every feature on)
            test_cell(ray, 0u, loose_end, any_hit, true, nearest);
        }
        if (!blocker_found(any_hit, nearest)) {
            grid_trace(ray, any_hit, nearest);
        }
    } else {
        brute_force_trace(ray, any_hit, nearest);
    }
    return nearest;
}

// The hit record of the nearest hit, by its kind (shapes/<name>.glsl, <name>_hit).
Hit make_hit(Ray ray, Nearest nearest) {
    if (nearest.ref == REF_NONE) {
        return no_hit();
    }
    uint index = nearest.ref & REF_INDEX_MASK;
    uint kind = nearest.ref >> REF_KIND_SHIFT;
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    if (HAS_##NAMES && kind == REF_##NAME) {                      \
        return name##_hit(ray, index, nearest);                   \
    }
#include "shapes/kinds.glsl"
    return no_hit();
}

// The closest hit with t in (0, t_max).
Hit closest_hit(Ray ray, float t_max) {
    Nearest nearest = trace(ray, t_max, false);
    Hit hit = make_hit(ray, nearest);
    // What was hit, which part of it (a cylinder's side or cap), and from which side:
    // near wall or far wall, outside or in, are decisions too.
    note_decision(nearest.ref);
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS)                \
    if (HAS_##NAMES && PARTS && (nearest.ref >> REF_KIND_SHIFT) == REF_##NAME) { \
        note_decision(nearest.part);                                             \
    }
#include "shapes/kinds.glsl"
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

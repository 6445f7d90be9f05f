// Uniform grid traversal: 3D-DDA (Amanatides & Woo, "A Fast Voxel Traversal Algorithm
// for Ray Tracing", 1987). The host (host/accel/grid.cpp) lists in each cell every
// primitive whose bounding box, slightly padded, overlaps it; the kernel walks the
// cells a ray pierces, front to back.
//
// Robustness, as the walk is written:
// - A direction component below GRID_PARALLEL in magnitude is treated as zero: the
//   ray never crosses a cell boundary on that axis. This makes +0, -0, denormals
//   (which lavapipe may flush) and tiny values all behave alike on both backends and
//   keeps 1/d finite. Over any distance a float ray can span, such a ray moves less
//   than the padding of the primitives' boxes, so no hit is lost.
// - Rays with a NaN or infinite component, and rays that miss the box, visit no cell.
// - Each step moves one cell index by one in the direction of the ray and the walk
//   stops when an index leaves the grid, so it ends after at most nx + ny + nz steps
//   whatever the input. The loop budget is only a backstop.
// - Cell boundaries are computed from the cell index each step (not accumulated), so
//   the walk does not drift on long rays.

const float GRID_PARALLEL = 1.0e-20f;

struct GridWalk {
    ivec3 cell;
    ivec3 step;     // -1, 0 or +1 per axis
    vec3 inv_dir;   // 1 / dir, 0 on parallel axes
    vec3 t_next;    // ray parameter where the ray leaves the cell on each axis
    float t_end;    // where the ray leaves the grid box, or its own end
    bool inside;    // false: the ray has no part inside the box and visits no cell
};

// Where the ray leaves the current cell on each axis. Written on whole vectors, not
// per axis: a vector component picked by a run-time index (cell[axis]) makes lavapipe
// spill the vector to memory, once per lane. Recomputing an axis whose cell did not
// change gives the same value again.
vec3 grid_t_next(Ray ray, GridWalk w) {
    vec3 boundary = vec3(w.cell + max(w.step, ivec3(0)));   // the far face in the ray's direction
    precise vec3 x = grid_min() + boundary * grid_cell();
    precise vec3 t = (x - ray.origin) * w.inv_dir;
    return mix(t, vec3(INFINITY_T), equal(w.step, ivec3(0)));
}

// Clips the ray (0, t_max) to the grid box (the slab test) and finds the first cell.
GridWalk grid_walk_start(Ray ray, float t_max) {
    GridWalk w = GridWalk(ivec3(0), ivec3(0), vec3(0.0f), vec3(INFINITY_T), 0.0f, false);
    float sum = ray.origin.x + ray.origin.y + ray.origin.z + ray.dir.x + ray.dir.y + ray.dir.z;
    if (!is_finite_bits(sum)) {
        return w;
    }
    vec3 lo = grid_min();
    vec3 hi = grid_max();
    bvec3 parallel = lessThan(abs(ray.dir), vec3(GRID_PARALLEL));
    // A ray parallel to a slab lies inside it for all t, or never: outside when its
    // distance beyond the slab, picked on the parallel axes only, is positive.
    vec3 beyond = max(lo - ray.origin, ray.origin - hi);
    if (any(greaterThan(mix(vec3(-1.0f), beyond, parallel), vec3(0.0f)))) {
        return w;
    }
    w.inv_dir = mix(vec3(1.0f) / ray.dir, vec3(0.0f), parallel);
    w.step = mix(ivec3(sign(ray.dir)), ivec3(0), parallel);
    vec3 t_lo = (lo - ray.origin) * w.inv_dir;
    vec3 t_hi = (hi - ray.origin) * w.inv_dir;
    vec3 t_near = mix(min(t_lo, t_hi), vec3(0.0f), parallel);
    vec3 t_far = mix(max(t_lo, t_hi), vec3(INFINITY_T), parallel);
    float t_start = max(0.0f, max(t_near.x, max(t_near.y, t_near.z)));
    float t_end = min(t_max, min(t_far.x, min(t_far.y, t_far.z)));
    if (!(t_start <= t_end)) {
        return w;
    }
    precise vec3 p = ray.origin + t_start * ray.dir;
    ivec3 res = ivec3(grid_resolution());
    // The clamp absorbs rounding: p may land a hair outside the box or the cell. A
    // cell entered too early costs a few tests; one entered too late is covered by
    // the padding of the boxes the host binned.
    // Clamped while still float: converting a float beyond int's range is undefined.
    w.cell = ivec3(clamp(floor((p - lo) * grid_inv_cell()), vec3(0.0f), vec3(res - 1)));
    w.t_next = grid_t_next(ray, w);
    w.t_end = t_end;
    w.inside = true;
    return w;
}

// Moves to the next cell, across the face the ray meets first (on a tie, x before y
// before z: either order visits cells the ray touches); false when the walk has left
// the grid or passed t_end.
bool grid_walk_step(Ray ray, INOUT(GridWalk) w) {
    float t = min(w.t_next.x, min(w.t_next.y, w.t_next.z));
    if (!(t < w.t_end)) {
        return false;
    }
    bool x = w.t_next.x == t;
    bool y = !x && w.t_next.y == t;
    bool z = !x && !y;
    w.cell += mix(ivec3(0), w.step, bvec3(x, y, z));
    if (any(lessThan(w.cell, ivec3(0))) || any(greaterThanEqual(w.cell, ivec3(grid_resolution())))) {
        return false;
    }
    w.t_next = grid_t_next(ray, w);
    return true;
}

uint grid_cell_index(ivec3 cell) {
    return (uint(cell.z) * grid_resolution().y + uint(cell.y)) * grid_resolution().x + uint(cell.x);
}

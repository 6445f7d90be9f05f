// Grid traversal. The host (host/accel/grid.cpp, grid_split.cpp) builds a uniform
// grid of root cells by Woo's rule and splits each crowded cell into 4 x 4 x 4
// children, again and again where primitives gather (docs/grid.md); a grid whose
// cells are never split is the uniform grid of the paper's Fig. 7. The walk is the
// irregular grid's (Perard-Gayot, Kalojanov & Slusallek, "GPU Ray Tracing using
// Irregular Grids", 2017): find the leaf cell that holds a point, test its
// primitives, leave its box through the face the ray meets first, and find the cell
// beyond. No stack: locating a cell descends from its root cell by the bits of the
// point's fine coordinates (constants.glsl), one node per level.
//
// Robustness, as the walk is written:
// - A direction component below GRID_PARALLEL in magnitude is treated as zero: the
//   ray never crosses a cell boundary on that axis. This makes +0, -0, denormals
//   (which lavapipe may flush) and tiny values all behave alike on both backends and
//   keeps 1/d finite. Over any distance a float ray can span, such a ray moves less
//   than the padding of the primitives' boxes, so no hit is lost.
// - Rays with a NaN or infinite component, and rays that miss the box, visit no cell.
// - The cell beyond an exit face is found in integers on the exit axis (the face's
//   fine coordinate, or the one before it), so the walk cannot stay in a cell it
//   leaves. On the other axes the point where the ray leaves is looked up, and taken
//   no further back than the last lookup: a point rounded back across a face finds,
//   at worst, a cell the ray meets only within rounding, which it then leaves on the
//   next step; one rounded ahead skips a sliver within rounding of the cell found,
//   which the padding of the boxes covers. The sum over axes of step * fine
//   coordinate grows every step, so the walk ends whatever the input; the loop
//   budget is only a backstop.
// - Cell faces are computed from fine coordinates each step (not accumulated), so
//   the walk does not drift on long rays.

const float GRID_PARALLEL = 1.0e-20f;

// Per axis, b where c holds, else a: mix() written out, which the glm of the
// reference backend runs as a generic call, as it does greaterThan() and equal().
HOT uvec3 grid_select(uvec3 a, uvec3 b, bvec3 c) {
    return uvec3(c.x ? b.x : a.x, c.y ? b.y : a.y, c.z ? b.z : a.z);
}
HOT vec3 grid_select_float(vec3 a, vec3 b, bvec3 c) {
    return vec3(c.x ? b.x : a.x, c.y ? b.y : a.y, c.z ? b.z : a.z);
}

struct GridWalk {
    uvec3 at;       // the fine coordinates the current cell was found at
    uvec3 lo;       // the current cell: fine coordinates [lo, hi) per axis
    uvec3 hi;
    uint start;     // its references: grid_refs[start, end)
    uint end;
    ivec3 step;     // -1, 0 or +1 per axis
    bvec3 ahead;    // step > 0
    bvec3 still;    // step == 0
    vec3 inv_dir;   // 1 / dir, 0 on parallel axes
    vec3 t_next;    // ray parameter where the ray leaves the cell on each axis
    float t_end;    // where the ray leaves the grid box, or its own end
    bool inside;    // false: the ray has no part inside the box and visits no cell
};

// The fine coordinate of position p on one axis, clamped into the grid. Taken within
// p's root cell, so that the fraction keeps the precision of the cell, not of the
// grid's box. Per axis, on scalars: GCC leaves glm's vector clamp and floor as calls.
// Clamped first, then truncated: for values at or above 0 that is the floor, and the
// reference backend's floor() is a library call on a baseline x86-64.
HOT uint grid_fine_axis(float p, float lo, float cell, float inv_cell, uint res) {
    precise int root = int(min(max((p - lo) * inv_cell, 0.0f), float(int(res) - 1)));
    precise float root_lo = lo + float(root) * cell;
    precise int f = int(min(max((p - root_lo) * (inv_cell * GRID_FINE), 0.0f), GRID_FINE - 1.0f));
    return (uint(root) << GRID_FRACTION_BITS) | uint(f);
}

HOT uvec3 grid_fine(vec3 p) {
    vec3 lo = grid_min();
    vec3 cell = grid_cell();
    vec3 inv = grid_inv_cell();
    uvec3 res = grid_resolution();
    return uvec3(grid_fine_axis(p.x, lo.x, cell.x, inv.x, res.x), grid_fine_axis(p.y, lo.y, cell.y, inv.y, res.y),
                 grid_fine_axis(p.z, lo.z, cell.z, inv.z, res.z));
}

// Where fine coordinates v lie in space: the root cell's corner plus the fraction.
// In a grid without splits every face is a root cell's, with no fraction to add.
// Converted through int, which every coordinate fits: a CPU converts signed
// integers to float in one vector instruction, unsigned ones one at a time.
HOT vec3 grid_position(uvec3 v) {
    precise vec3 root_lo = grid_min() + vec3(ivec3(v >> GRID_FRACTION_BITS)) * grid_cell();
    if (!GRID_SPLIT) {
        return root_lo;
    }
    precise vec3 x = root_lo + vec3(ivec3(v & uvec3(uint(GRID_FINE) - 1u))) * (grid_cell() * (1.0f / GRID_FINE));
    return x;
}

// Finds the leaf cell holding fine coordinates v (inside the grid): its box and its
// references. Descends from the root cell, two bits of each coordinate per level.
HOT void grid_locate(uvec3 v, INOUT(GridWalk) w) {
    uvec3 res = grid_resolution();
    uvec3 root = v >> GRID_FRACTION_BITS;
    uint node = (root.z * res.y + root.y) * res.x + root.x;
    uint word = load_grid_node(node);
    uint shift = GRID_FRACTION_BITS;
    for (uint level = 0u; GRID_SPLIT && level < GRID_MAX_LEVELS && (word & GRID_INNER) != 0u; ++level) {
        shift -= GRID_SPLIT_BITS;
        uvec3 child = (v >> shift) & uvec3((1u << GRID_SPLIT_BITS) - 1u);
        node = load_ref(word & ~GRID_INNER) + (((child.z << GRID_SPLIT_BITS) | child.y) << GRID_SPLIT_BITS | child.x);
        word = load_grid_node(node);
    }
    bool leaf = (word & GRID_INNER) == 0u;   // the host never nests deeper; a bad node holds nothing
    w.start = leaf ? word : 0u;
    w.end = leaf ? load_grid_node(node + 1u) & ~GRID_INNER : 0u;
    w.lo = (v >> shift) << shift;
    w.hi = w.lo + uvec3(1u << shift);
}

// Where the ray leaves the current cell on each axis. Written on whole vectors, not
// per axis: a vector component picked by a run-time index (cell[axis]) makes lavapipe
// spill the vector to memory, once per lane.
HOT vec3 grid_t_next(Ray ray, GridWalk w) {
    uvec3 face = grid_select(w.lo, w.hi, w.ahead);   // the far face in the ray's direction
    precise vec3 t = (grid_position(face) - ray.origin) * w.inv_dir;
    return grid_select_float(t, vec3(INFINITY_T), w.still);
}

// The fine coordinates of the point ray(t). Its rounding grows with its magnitude,
// the width of the root cell it is measured from and the distance the ray has
// travelled; the host pads every box by more than that (Grid::rounding_pad).
HOT uvec3 grid_fine_at(Ray ray, float t) {
    precise vec3 p = ray.origin + t * ray.dir;
    return grid_fine(p);
}

// Clips the ray (0, t_max) to the grid box (the slab test) and finds the first cell.
GridWalk grid_walk_start(Ray ray, float t_max) {
    GridWalk w = GridWalk(uvec3(0u), uvec3(0u), uvec3(0u), 0u, 0u, ivec3(0), bvec3(false), bvec3(true), vec3(0.0f),
                          vec3(INFINITY_T), 0.0f, false);
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
    w.ahead = greaterThan(w.step, ivec3(0));
    w.still = parallel;
    vec3 t_lo = (lo - ray.origin) * w.inv_dir;
    vec3 t_hi = (hi - ray.origin) * w.inv_dir;
    vec3 t_near = mix(min(t_lo, t_hi), vec3(0.0f), parallel);
    vec3 t_far = mix(max(t_lo, t_hi), vec3(INFINITY_T), parallel);
    float t_start = max(0.0f, max(t_near.x, max(t_near.y, t_near.z)));
    float t_end = min(t_max, min(t_far.x, min(t_far.y, t_far.z)));
    if (!(t_start <= t_end)) {
        return w;
    }
    // The clamp in grid_fine absorbs rounding: the point may land a hair outside the
    // box. A cell entered too early costs a few tests; one entered too late is
    // covered by the padding of the boxes the host binned.
    w.at = grid_fine_at(ray, t_start);
    grid_locate(w.at, w);
    w.t_next = grid_t_next(ray, w);
    w.t_end = t_end;
    w.inside = true;
    return w;
}

// Moves to the next cell, across the face the ray meets first (on a tie, x before y
// before z: the lookup a little ahead then finds the cell past the others too);
// false when the walk has left the grid or passed t_end.
HOT bool grid_walk_step(Ray ray, INOUT(GridWalk) w) {
    float t = min(w.t_next.x, min(w.t_next.y, w.t_next.z));
    if (!(t < w.t_end)) {
        return false;
    }
    bool x = w.t_next.x == t;
    bool y = !x && w.t_next.y == t;
    bool z = !x && !y;
    bvec3 exit_axis = bvec3(x, y, z);
    bvec3 ahead = w.ahead;
    // Leaving the grid: the exit face is the grid's own.
    uvec3 face = grid_select(w.lo, w.hi, ahead);
    uvec3 outer = grid_select(uvec3(0u), grid_resolution() << GRID_FRACTION_BITS, ahead);
    if ((x && face.x == outer.x) || (y && face.y == outer.y) || (z && face.z == outer.z)) {
        return false;
    }
    // Past the face on the exit axis. On the others, in a uniform grid, where the
    // last lookup was: every cell across the face is the same size and holds the
    // whole face. Where cells are split, the one across may be smaller, and the place
    // is where the ray leaves, but never behind the last lookup.
    uvec3 across = grid_select(w.lo - uvec3(1u), w.hi, ahead);
    uvec3 at = w.at;
    if (GRID_SPLIT) {
        uvec3 leaving = grid_fine_at(ray, t);
        leaving = grid_select(min(leaving, at), max(leaving, at), ahead);
        at = grid_select(leaving, at, w.still);
    }
    w.at = grid_select(at, across, exit_axis);
    grid_locate(w.at, w);
    w.t_next = grid_t_next(ray, w);
    return true;
}

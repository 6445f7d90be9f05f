// Constants shared by both hosts.

// Lanes of the per-pixel counter buffer. Counting per pixel, not with atomics, keeps
// the hot path contention-free; the host sums the lanes after read-back.
const uint COUNTER_EYE_RAYS = 0u;
const uint COUNTER_SHADOW_RAYS = 1u;
const uint COUNTER_TRUNCATED = 2u;   // samples stopped by the loop budget
const uint COUNTER_NONFINITE = 3u;   // samples discarded for a NaN or infinite value

// Mesa's lavapipe stops an invocation's loops silently after 65,535 iterations in
// total (DESIGN.md). The kernel counts its own iterations the way lavapipe does
// (budget.glsl) against a budget below that cap, with room to spare.
const uint DEFAULT_LOOP_BUDGET = 60000u;

const float INFINITY_T = 3.0e38f;   // "no hit yet"; finite so comparisons stay ordered

// Shadow rays stop this fraction short of their light, so that a light placed exactly
// on a surface (a lamp on the ceiling) is not shadowed by the surface it sits on,
// whose hit distance rounds to either side of the light's.
const float SHADOW_RAY_END = 0.9999f;

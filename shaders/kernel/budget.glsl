// The per-invocation loop budget (DESIGN.md, "Bounded work per invocation").
// lavapipe counts every evaluation of a loop's condition, so a loop that runs n times
// costs n + 1 (measured: 22,000 lights with one-sphere shadow rays, three counts a
// light, were cut silently). The kernel counts the same way: loop_enter() before
// every loop, loop_tick() at the top of every iteration, stopping when it returns
// false; the sample is then flagged as truncated instead of silently wrong.

uint g_loop_iterations = 0u;
// Work done for the stats report (Counters.work); not a limit.
uint g_cells_visited = 0u;
uint g_intersection_tests = 0u;

void work_reset() {
    g_loop_iterations = 0u;
    g_cells_visited = 0u;
    g_intersection_tests = 0u;
}

void loop_enter() {
    g_loop_iterations += 1u;
}

bool loop_tick() {
    g_loop_iterations += 1u;
    return g_loop_iterations <= params.limits.x;
}

bool budget_exhausted() {
    return g_loop_iterations > params.limits.x;
}

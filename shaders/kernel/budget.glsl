// The per-invocation loop budget (DESIGN.md, "Bounded work per invocation").
// Every kernel loop calls loop_tick() once per iteration and stops when it returns
// false; the sample is then flagged as truncated instead of silently wrong.

uint g_loop_iterations = 0u;

bool loop_tick() {
    g_loop_iterations += 1u;
    return g_loop_iterations <= params.limits.x;
}

bool budget_exhausted() {
    return g_loop_iterations > params.limits.x;
}

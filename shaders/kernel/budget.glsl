// The per-invocation loop budget (docs/architecture.md, "Bounded work per invocation").
// lavapipe counts every evaluation of a loop's condition, so a loop that runs n times
// costs n + 1 (measured: 22,000 lights with one-sphere shadow rays, three counts a
// light, were cut silently). The kernel counts the same way: loop_enter() before
// every loop, loop_tick() once per iteration (at the top, or in the condition of a
// loop that tests at the bottom), stopping when it returns false; the sample is then
// flagged as truncated instead of silently wrong.

uint g_loop_iterations = 0u;
// Work done for the stats report (Counters.work); not a limit.
uint g_cells_visited = 0u;
uint g_intersection_tests = 0u;
// A hash of every discrete decision the sample took (what each ray hit, whether a
// light faced the surface, whether a shadow ray was blocked, total internal
// reflection, a ray dropped): two backends whose images differ at a pixel but whose
// decisions hashed alike differ by arithmetic alone; otherwise by a decision flip
// (tests/crosscheck/crosscheck_test.cpp tells the two apart).
const uint DECISIONS_START = 2166136261u;   // the FNV-1a offset basis
uint g_decisions = DECISIONS_START;

void work_reset() {
    g_loop_iterations = 0u;
    g_cells_visited = 0u;
    g_intersection_tests = 0u;
    g_decisions = DECISIONS_START;
}

// One FNV-1a step per decision: integer-only, so both backends hash alike.
void note_decision(uint value) {
    g_decisions = (g_decisions ^ value) * 16777619u;
}

void loop_enter() {
    g_loop_iterations += 1u;
}

bool loop_tick() {
    g_loop_iterations += 1u;
    return g_loop_iterations <= loop_budget();
}

bool budget_exhausted() {
    return g_loop_iterations > loop_budget();
}

// True when the driver's own loop cap may have cut this invocation's loops: its
// vector's counter is spent (a lane that had finished is flagged too). lavapipe
// keeps one counter for the whole shader run of an 8-lane vector and counts every
// iteration in which any lane is active, while the budget above counts each
// invocation's own iterations: where the lanes take different paths through nested
// loops (a ray tree whose lanes reflect at different depths over a brute-force
// loop), the vector's count passes 65,535 before any lane's passes the budget, and
// lavapipe ends the loops without a word (docs/architecture.md). Once its counter is
// spent, every loop stops after one iteration, so this loop, which must run twice,
// runs once. Its trip count comes from the params, which the compilers cannot see,
// so it is not unrolled away. Always false on the reference, which has no such cap.
bool driver_cut_loops() {
    uint want = min(loop_budget(), 2u);
    uint runs = 0u;
    do {
        runs += 1u;
    } while (runs < want);
    return runs < want;
}

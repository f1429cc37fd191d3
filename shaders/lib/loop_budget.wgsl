// plait::loop_budget — did lavapipe's loop budget run out? llvmpipe gives
// each group of 8 invocations (a 4×2 block of fragments, or 8 consecutive
// compute invocations) one budget of 65,535 loop iterations for all its
// loops; once it is spent every loop exits after its current iteration,
// silently. A shader whose loops run a data-sized number of times calls this
// at its end and counts itself in an `incomplete` overflow word when it
// returns true (docs/design.md, "Loop budgets").
#define_import_path plait::loop_budget

// A last loop of `laps` iterations (at least 2) that completes only while
// budget is left. `laps` must be a value the compiler cannot know (a
// texture's size, a uniform): a constant loop would be unrolled and cost
// nothing. Conservative: true also when the budget ran out exactly here.
fn loop_budget_spent(laps: u32) -> bool {
    let want = max(laps, 2u);
    var done = 0u;
    for (var q = 0u; q < want; q++) {
        done += 1u;
    }
    return done < want;
}

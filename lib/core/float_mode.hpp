#pragma once
// The floating-point mode of the simulation threads: subnormal numbers (magnitudes below 2.2e-308) are
// flushed to zero, as results (FTZ) and as operands (DAZ).
//
// Why: an operation on a subnormal costs ~100 cycles on x86 instead of ~4. The higher Gear derivatives of a
// fragment in free flight decay geometrically step by step, reach the subnormals after some thousand steps and
// linger there, so the corrector's loop slowed the paper-scale explosion by ~9 %. Nothing physical lives 300
// orders of magnitude below the scales of a run (positions ~1e-2 m, Gear terms ~1e-12 m), and the mode is
// deterministic: the same bits on every run and thread count (tools set it on every thread).
namespace frac {

// Sets the mode on the calling thread (threads started later by it inherit it). Returns false where the
// target has no such mode (then nothing changes).
bool flush_subnormals_to_zero();

}  // namespace frac

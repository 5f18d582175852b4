#pragma once
// FRACTURE_VECTOR_KERNEL marks a hot loop written for the vectoriser (arrays in, arrays out, no branch, no
// indirect load). GCC then builds it twice, for AVX2 and for the baseline x86-64 (SSE2), and picks one when
// the program loads (target_clones, an ifunc). AVX2 without FMA: every operation is the same IEEE-754 add,
// multiply, divide or square root, rounded the same way, in the same order, as in the baseline version, so
// both give the same bits (a build for FMA might contract a·b + c into one rounding: it is not a target
// here). Elsewhere (another compiler or architecture) it is nothing: one version.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define FRACTURE_VECTOR_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define FRACTURE_VECTOR_KERNEL
#endif

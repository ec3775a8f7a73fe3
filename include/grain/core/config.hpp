#pragma once
/// \file config.hpp
/// Compiler hints used by the hot loops.
///
/// `GRAIN_INLINE` marks the small functions of the per-contact pipeline (the composed
/// `Interaction::evaluate` and the model functions it calls) that must be inlined into the force
/// loop: the compiler's own heuristics stop inlining a deep template chain early, and a call per
/// contact then costs a third of the contact law. Expands to `[[gnu::always_inline]] inline` on
/// GCC and Clang, to `inline` elsewhere. `GRAIN_INLINE_LAMBDA` does the same for a lambda (placed
/// after its parameter list).

#if defined(__GNUC__) || defined(__clang__)
#define GRAIN_INLINE [[gnu::always_inline]] inline
#define GRAIN_INLINE_LAMBDA __attribute__((always_inline))
/// Keeps a function out of line (one copy of a large inlined body, called rarely).
#define GRAIN_NOINLINE [[gnu::noinline]]
/// Hints that the cache line at address p will be read (w = 0) or written (w = 1) soon.
#define GRAIN_PREFETCH(p, w) __builtin_prefetch((p), (w))
#else
#define GRAIN_INLINE inline
#define GRAIN_INLINE_LAMBDA
#define GRAIN_NOINLINE
#define GRAIN_PREFETCH(p, w) ((void)(p))
#endif

// Inlining hints for the per-byte paths, and nothing where the compiler does not understand them.
//   TRIONET_ALWAYS_INLINE  a bulk loop, or a thin wrapper of one, that must be inlined into its one caller so
//                          that its state stays in registers (the bulk receive and relay paths)
//   TRIONET_NOINLINE       a cold helper kept out of line so that it is not copied into every caller
//   TRIONET_LIKELY(x)      a condition that holds on the hot path, so the compiler lays that path out straight
//   TRIONET_FAST_PATH      a per-byte fast path that a caller's loop should inline when compiled for speed;
//                          with -Os it stays one out-of-line function (smaller firmware)
#pragma once

#if defined(__GNUC__)
#define TRIONET_ALWAYS_INLINE [[gnu::always_inline]]
#define TRIONET_NOINLINE [[gnu::noinline]]
#define TRIONET_LIKELY(x) __builtin_expect(!!(x), 1)
#if defined(__OPTIMIZE_SIZE__)
#define TRIONET_FAST_PATH
#else
#define TRIONET_FAST_PATH [[gnu::always_inline]]
#endif
#else
#define TRIONET_FAST_PATH
#define TRIONET_ALWAYS_INLINE
#define TRIONET_NOINLINE
#define TRIONET_LIKELY(x) (x)
#endif

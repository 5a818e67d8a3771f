// The library's macros: inlining hints for the per-byte paths, and the precondition hook.
//
//   TRIONET_ALWAYS_INLINE  a per-byte fast path, or a thin wrapper of one, inlined into its caller so that its
//                          state stays in registers
//   TRIONET_NOINLINE       a cold helper kept out of line so that it is not copied into every caller
//   TRIONET_LIKELY(x)      a condition that holds on the hot path, so the compiler lays that path out straight
//   TRIONET_ASSERT(cond)   checks a documented precondition of a call (an index in range, a call made in the
//                          state it needs). A no-op unless the user defines it before including any trionet
//                          header, as libcanard's CANARD_ASSERT: e.g. -DTRIONET_ASSERT(c)=assert(c) in a
//                          debug build, or a firmware's own fault handler. Bad wire data never reaches it: the
//                          library drops, classifies and counts that; only misuse of the API does.
#pragma once

#if defined(__GNUC__)
#define TRIONET_ALWAYS_INLINE [[gnu::always_inline]]
#define TRIONET_NOINLINE [[gnu::noinline]]
#define TRIONET_LIKELY(x) __builtin_expect(!!(x), 1)
#else
#define TRIONET_ALWAYS_INLINE
#define TRIONET_NOINLINE
#define TRIONET_LIKELY(x) (x)
#endif

#ifndef TRIONET_ASSERT
// The condition is not evaluated (sizeof), so the default costs nothing and keeps its names used.
#define TRIONET_ASSERT(cond) static_cast<void>(sizeof((cond) ? 1 : 0))
#endif

// Inlining hints for the per-byte paths, and nothing where the compiler does not understand them.
//   TRIONET_ALWAYS_INLINE  a bulk loop, or a thin wrapper of one, that must be inlined into its one caller so
//                          that its state stays in registers (the bulk receive and relay paths)
//   TRIONET_NOINLINE       a cold helper kept out of line so that it is not copied into every caller
#pragma once

#if defined(__GNUC__)
#define TRIONET_ALWAYS_INLINE [[gnu::always_inline]]
#define TRIONET_NOINLINE [[gnu::noinline]]
#else
#define TRIONET_ALWAYS_INLINE
#define TRIONET_NOINLINE
#endif

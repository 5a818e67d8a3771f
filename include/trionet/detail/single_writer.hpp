// A value that one side of a node writes and both sides read: the building block of the nodes' concurrency
// contract (docs/design.md, "Contexts").
//
// A node has two sides: the link side (the UART or CAN interrupt: receive, transmit, idle line) and the
// program side (the main loop or one RTOS task: PRINT#, SEND, GET#, NETSTAT, counters). Every variable that
// both sides touch is a `single_writer`: only its owning side stores to it, the other side only loads it.
// So nothing needs a lock, interrupt masking or an atomic read-modify-write: an increment is a load and a
// store by the one writer. On a Cortex-M0+ (no LDREX/STREX) every operation here is a plain load or store
// (a `dmb` for `acquire`/`release`), and no `__atomic_*` library routine is linked (the firmware build checks).
// On a host the same code is correct between two threads, which is how the contract is tested (with
// ThreadSanitizer).
//
// Cost: sizeof(T); loads and stores only.
#pragma once

#include <atomic>
#include <type_traits>

#include "trionet/detail/attributes.hpp"

namespace trionet::detail {

/// A value written by one side only and read by both (see the file comment). Copying copies the value, so a
/// node that holds one stays copyable; copy a node only while neither side is running.
template <class T>
class single_writer {
  static_assert(std::is_integral_v<T> && sizeof(T) <= 4, "a single-writer value is an integer of 1..4 bytes");

 public:
  /// Zero.
  constexpr single_writer() noexcept : value_(T{}) {}
  /// Starts at `value`.
  constexpr explicit single_writer(T value) noexcept : value_(value) {}
  /// Copies the value (relaxed).
  single_writer(const single_writer& other) noexcept : value_(other.load()) {}
  /// Copies the value (relaxed).
  single_writer& operator=(const single_writer& other) noexcept {
    store(other.load());
    return *this;
  }
  ~single_writer() = default;

  /// The value now, for either side. Orders nothing else.
  TRIONET_ALWAYS_INLINE T load() const noexcept { return value_.load(std::memory_order_relaxed); }
  /// The value now, and everything the writer did before it `release`d this value is visible after.
  T acquire() const noexcept { return value_.load(std::memory_order_acquire); }
  /// Writer only: a new value (for counters and flags that order nothing else).
  TRIONET_ALWAYS_INLINE void store(T value) noexcept { value_.store(value, std::memory_order_relaxed); }
  /// Writer only: a new value, after everything written before it (e.g. the bytes that an index publishes).
  void release(T value) noexcept { value_.store(value, std::memory_order_release); }
  /// Writer only: adds `n` (wrapping): a load and a store, not a read-modify-write instruction.
  TRIONET_ALWAYS_INLINE void add(T n) noexcept { store(static_cast<T>(load() + n)); }
  /// Writer only: adds one (wrapping).
  TRIONET_ALWAYS_INLINE void increment() noexcept { add(T{1}); }

 private:
  std::atomic<T> value_;
};

/// A request from one side that the other side carries out: the one thing both sides write, as a handshake.
/// The asking side only `raise`s it, the other side only `lower`s it, once it has done what was asked, and it
/// does nothing else between doing it and lowering the flag, so a request that comes meanwhile is served
/// by what it did (a node's `clear_counters`: the link side clears its counters). Cost: 1 byte.
class request_flag {
 public:
  /// Not raised.
  constexpr request_flag() noexcept : raised_(false) {}
  /// Copies the flag.
  request_flag(const request_flag& other) noexcept : raised_(other.raised_.load(std::memory_order_relaxed)) {}
  /// Copies the flag.
  request_flag& operator=(const request_flag& other) noexcept {
    raised_.store(other.raised_.load(std::memory_order_relaxed), std::memory_order_relaxed);
    return *this;
  }
  ~request_flag() = default;

  /// The asking side: asks, after everything it stored before, and before anything it does after (a full
  /// barrier: on a host the serving thread sees the request from its next look on).
  void raise() noexcept { raised_.store(true, std::memory_order_seq_cst); }
  /// The serving side: true while a request waits (one load: for its hot paths).
  TRIONET_ALWAYS_INLINE bool waiting() const noexcept { return raised_.load(std::memory_order_relaxed); }
  /// Either side: true while a request waits; once it is false, what the serving side did before it lowered
  /// the flag is visible.
  bool raised() const noexcept { return raised_.load(std::memory_order_acquire); }
  /// The serving side: the request is done, after everything stored before.
  void lower() noexcept { raised_.store(false, std::memory_order_release); }

 private:
  std::atomic<bool> raised_;
};

}  // namespace trionet::detail

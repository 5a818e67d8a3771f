// VR(): the global variables of a Motion Coordinator that the network writes without the user program.
//
// Both the fibre ring (direct variable transfer, docs/protocol.md 1.6) and the CAN VR exchange (2.2) write
// VR() through the same hook, `vr_store`, so that one write policy governs every network write.
//
// Sides: a node calls `write` on its link side (the interrupt that receives; the policy callback runs there
// too), while the program reads and writes VR() in its own context. A value is 64 bits, which a 32-bit core
// cannot store or load at once, so `vr_table` keeps each value as two 32-bit words and one sequence number
// for the table: the link side makes it odd while it writes; the program side reads both words and then the
// sequence number again, and reads again if the network wrote meanwhile; the program side's own write checks
// the sequence number after its two words and writes again if the network wrote meanwhile (its value is then
// the later one). So no value is ever seen or left half-written, without a lock or interrupt masking.
// Cost: `vr_table<N>` is N values plus a sequence number and two pointers; `write` is O(1); a program-side
// access is O(1), repeated only when a network write falls inside it.
#pragma once

#include <cstddef>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

// ThreadSanitizer builds (see vr_table): GCC says so with __SANITIZE_THREAD__, clang with __has_feature.
#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define TRIONET_THREAD_SANITIZER 1
#endif
#endif

#include "trionet/detail/attributes.hpp"
#include "trionet/q32.hpp"

namespace trionet {

/// What became of a VR write that arrived from the network.
enum class vr_write_status : std::uint8_t {
  ok,                  ///< VR(vr) now holds the value
  refused,             ///< the node's write policy refused this vr; nothing changed
  out_of_range,        ///< vr is past the end of the VR table; nothing changed
  value_out_of_range,  ///< the table's value type cannot hold the value (a Q32.32 table); nothing changed
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(vr_write_status status) noexcept {
  switch (status) {
    case vr_write_status::ok:
      return "ok";
    case vr_write_status::refused:
      return "refused";
    case vr_write_status::out_of_range:
      return "out_of_range";
    case vr_write_status::value_out_of_range:
      return "value_out_of_range";
  }
  return "unknown";
}

/// A VR value exactly as the network carried it: Q32.32 from the ring (docs/protocol.md 1.3), or sign,
/// integer part and ten-thousandths from CAN (2.2). A store converts it to its own representation, so a node
/// itself does no floating-point arithmetic.
struct network_value {
  /// How the value is held.
  enum class encoding : std::uint8_t {
    q32,      ///< Q32.32, from the ring
    decimal,  ///< sign, integer part and ten-thousandths, from CAN
  };
  encoding kind = encoding::q32;  ///< which of the fields below hold the value
  bool negative = false;              ///< decimal: the sign
  std::uint16_t ten_thousandths = 0;  ///< decimal: fraction of the magnitude, 0..9999
  std::uint32_t integer = 0;          ///< decimal: integer part of the magnitude
  std::int64_t q32 = 0;               ///< q32: value * 2^32

  /// A Q32.32 value (`raw` = value * 2^32).
  static constexpr network_value from_q32(std::int64_t raw) noexcept {
    network_value v;
    v.q32 = raw;
    return v;
  }
  /// A decimal value: sign, integer part and ten-thousandths (0..9999) of the magnitude.
  static constexpr network_value from_decimal(bool negative, std::uint32_t integer,
                                              std::uint16_t ten_thousandths) noexcept {
    network_value v;
    v.kind = encoding::decimal;
    v.negative = negative;
    v.integer = integer;
    v.ten_thousandths = ten_thousandths;
    return v;
  }

  /// As a double (a software routine on a core without a double-precision FPU). Q32.32 is exact while
  /// |value| < 2^21; a decimal gives the double nearest to it.
  constexpr double to_double() const noexcept {
    if (kind == encoding::q32) return q32_to_double(q32);
    return trionet::to_double(decimal{negative, integer, ten_thousandths});
  }

  /// As Q32.32 with integer arithmetic only: exact for ring values; a decimal is rounded to the nearest
  /// 2^-32 (ties away from zero). `out_of_range` outside [-2^31, 2^31 - 2^-32], `fraction_out_of_range` for a
  /// fraction above 9999.
  [[nodiscard]] constexpr q32_result to_q32() const noexcept {
    if (kind == encoding::q32) return {q32_status::ok, q32};
    return q32_from_decimal(decimal{negative, integer, ten_thousandths});
  }
};

/// The port through which a node writes VR() from the network. Implement it to map network writes onto
/// your own variables; `vr_table` is the ready-made implementation.
class vr_store {
 public:
  /// The network writes `value` to VR(`vr`): stores it (`ok`) or says why not.
  [[nodiscard]] virtual vr_write_status write(std::uint16_t vr, const network_value& value) noexcept = 0;

 protected:
  constexpr vr_store() = default;
  /// Copyable by the implementations only.
  vr_store(const vr_store&) = default;
  /// Copyable by the implementations only.
  vr_store& operator=(const vr_store&) = default;
  ~vr_store() = default;
};

/// Write policy hook of a table whose values are `Value`: return false to refuse a network write to `vr`
/// (in range of the table). `context` is the pointer given to the table with the policy.
template <class Value>
using vr_write_policy_for = bool (*)(void* context, std::uint16_t vr, Value value) noexcept;
/// The write policy of a table of doubles (the default).
using vr_write_policy = vr_write_policy_for<double>;

/// A table of `Size` VRs, initially 0. Default policy: accept every vr < Size (docs/protocol.md 1.6).
/// `Value` is `double` (the default: what BASIC's VR() holds; needs floating point) or `std::int64_t`
/// (Q32.32, integer arithmetic only, for cores without an FPU: a CAN value of 2^31 or more is then
/// `value_out_of_range`). `write` is the link side's; `get`, `set` and `[]` are the program side's (see the
/// file comment).
template <std::size_t Size, class Value = double>
class vr_table final : public vr_store {
  static_assert(Size > 0 && Size <= 16384, "a VR table holds 1..16384 variables (14-bit vr on the ring)");
  static_assert(std::is_same_v<Value, double> || std::is_same_v<Value, std::int64_t>,
                "VR values are double or Q32.32 (std::int64_t)");

 public:
  /// All VRs 0, the default policy.
  constexpr vr_table() noexcept = default;
  /// All VRs 0; `policy` (with `context`) decides which network writes to accept.
  constexpr explicit vr_table(vr_write_policy_for<Value> policy, void* context = nullptr) noexcept
      : policy_(policy), context_(context) {}

  /// Link side: a write from the network, through the policy.
  [[nodiscard]] vr_write_status write(std::uint16_t vr, const network_value& value) noexcept override {
    if (vr >= Size) return vr_write_status::out_of_range;
    Value converted{};
    if constexpr (std::is_same_v<Value, double>) {
      converted = value.to_double();
    } else {
      const q32_result q = value.to_q32();
      if (!q) return vr_write_status::value_out_of_range;
      converted = q.raw;
    }
    if (policy_ != nullptr && !policy_(context_, vr, converted)) return vr_write_status::refused;
    const std::uint32_t s = sequence_.load(relaxed);
    sequence_.store(s + 1u, relaxed);  // odd: a write is under way
    fence(std::memory_order_seq_cst);  // before the words (and see `set`)
    store_words(values_[vr], converted);
    sequence_.store(s + 2u, release);
    return vr_write_status::ok;
  }

  /// Program side: VR(vr), never half-written. `vr` must be < Size.
  TRIONET_NOINLINE Value get(std::size_t vr) const noexcept {
    for (;;) {
      const std::uint32_t before = sequence_.load(acquire);
      const std::uint32_t low = values_[vr].low.load(relaxed);
      const std::uint32_t high = values_[vr].high.load(relaxed);
      fence(std::memory_order_acquire);  // the words before the second look
      if ((before & 1u) == 0 && sequence_.load(relaxed) == before) return join(low, high);
    }
  }
  /// Program side: VR(vr) = value, as BASIC does; if the network writes at the same time, the value left is
  /// one of the two, whole. `vr` must be < Size.
  TRIONET_NOINLINE void set(std::size_t vr, Value value) noexcept {
    for (;;) {
      const std::uint32_t before = sequence_.load(relaxed);
      if ((before & 1u) != 0) continue;  // another core is writing (never on one core: the ISR runs to its end)
      store_words(values_[vr], value);
      // The words before the look at the sequence number, as `write` marks it before its words: either this
      // look sees a network write that began meanwhile, or that write's words come after these.
      fence(std::memory_order_seq_cst);
      if (sequence_.load(relaxed) == before) return;
    }
  }

  /// Program side: VR(vr) as BASIC writes it: `vr[i] = x`, `vr[i] += x`, `Value x = vr[i]`.
  class reference {
   public:
    /// The value (`get`).
    operator Value() const noexcept { return table_->get(vr_); }  // NOLINT: a proxy converts implicitly
    /// Writes (`set`).
    reference& operator=(Value value) noexcept {
      table_->set(vr_, value);
      return *this;
    }
    /// Copies another VR's value.
    reference& operator=(const reference& other) noexcept { return *this = static_cast<Value>(other); }
    /// Adds to the value (a read and a write: a network write between them is overwritten).
    reference& operator+=(Value delta) noexcept { return *this = static_cast<Value>(*this) + delta; }
    /// Subtracts from the value (a read and a write, as `+=`).
    reference& operator-=(Value delta) noexcept { return *this = static_cast<Value>(*this) - delta; }
    /// A copy refers to the same VR.
    reference(const reference&) noexcept = default;
    ~reference() = default;

   private:
    friend class vr_table;
    reference(vr_table* table, std::size_t index) noexcept : table_(table), vr_(index) {}
    vr_table* table_;
    std::size_t vr_;
  };

  /// Program side: VR(vr), read and written through `get` and `set`. `vr` must be < Size.
  reference operator[](std::size_t vr) noexcept { return reference(this, vr); }
  /// Program side: VR(vr) (`get`). `vr` must be < Size.
  Value operator[](std::size_t vr) const noexcept { return get(vr); }
  /// The number of VRs.
  static constexpr std::size_t size() noexcept { return Size; }

 private:
  struct words {
    std::atomic<std::uint32_t> low{0};
    std::atomic<std::uint32_t> high{0};
  };

#if defined(__SANITIZE_THREAD__) || defined(TRIONET_THREAD_SANITIZER)
  // ThreadSanitizer does not model fences (GCC refuses them under -fsanitize=thread): there every access is
  // sequentially consistent instead, which orders at least as much, and the fences go.
  static constexpr std::memory_order relaxed = std::memory_order_seq_cst;
  static constexpr std::memory_order acquire = std::memory_order_seq_cst;
  static constexpr std::memory_order release = std::memory_order_seq_cst;
  static void fence(std::memory_order) noexcept {}
#else
  static constexpr std::memory_order relaxed = std::memory_order_relaxed;
  static constexpr std::memory_order acquire = std::memory_order_acquire;
  static constexpr std::memory_order release = std::memory_order_release;
  static void fence(std::memory_order order) noexcept { std::atomic_thread_fence(order); }
#endif

  static void store_words(words& to, Value value) noexcept {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    to.low.store(static_cast<std::uint32_t>(bits), relaxed);
    to.high.store(static_cast<std::uint32_t>(bits >> 32), relaxed);
  }
  static Value join(std::uint32_t low, std::uint32_t high) noexcept {
    const std::uint64_t bits = (std::uint64_t{high} << 32) | low;
    Value value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }

  // The small members first: near the object's start, they are one instruction away on a Cortex-M0+.
  std::atomic<std::uint32_t> sequence_{0};  // odd while the link side writes
  vr_write_policy_for<Value> policy_ = nullptr;
  void* context_ = nullptr;
  words values_[Size]{};
};

}  // namespace trionet

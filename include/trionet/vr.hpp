// VR(): the global variables of a Motion Coordinator that the network writes without the user program.
//
// Both the fibre ring (direct variable transfer, PROTOCOL.md 1.6) and the CAN VR exchange (2.2) write
// VR() through the same hook, `vr_store`, so that one write policy governs every network write.
// Cost: `vr_table<N>` is N values plus two pointers; `write` is O(1) and may be called from an ISR
// (the policy callback then runs in that context too).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace trionet {

/// What became of a VR write that arrived from the network.
enum class vr_write : std::uint8_t {
  written,             ///< VR(vr) now holds the value
  refused,             ///< the node's write policy refused this vr; nothing changed
  out_of_range,        ///< vr is past the end of the VR table; nothing changed
  value_out_of_range,  ///< the table's value type cannot hold the value (a Q32.32 table); nothing changed
};

/// A VR value exactly as the network carried it: Q32.32 from the ring (PROTOCOL.md 1.3), or sign, integer
/// part and ten-thousandths from CAN (2.2). A store converts it to its own representation, so a node itself
/// does no floating-point arithmetic.
struct network_value {
  enum class encoding : std::uint8_t { q32, decimal };
  encoding kind = encoding::q32;
  bool negative = false;              ///< decimal: the sign
  std::uint16_t ten_thousandths = 0;  ///< decimal: fraction of the magnitude, 0..9999
  std::uint32_t integer = 0;          ///< decimal: integer part of the magnitude
  std::int64_t q32 = 0;               ///< q32: value * 2^32

  static constexpr network_value from_q32(std::int64_t raw) noexcept {
    network_value v;
    v.q32 = raw;
    return v;
  }
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
    if (kind == encoding::q32) return static_cast<double>(q32) / 4294967296.0;
    // integer * 10000 + fraction < 2^53 is exact, so this is the correctly rounded decimal.
    const double magnitude =
        static_cast<double>(static_cast<std::uint64_t>(integer) * 10000u + ten_thousandths) / 10000.0;
    return negative ? -magnitude : magnitude;
  }

  /// As Q32.32 with integer arithmetic only: exact for ring values; a decimal is rounded to the nearest
  /// 2^-32 (ties away from zero). False when the value is outside [-2^31, 2^31 - 2^-32] (or the fraction
  /// is not 0..9999).
  constexpr bool to_q32(std::int64_t& raw) const noexcept {
    if (kind == encoding::q32) {
      raw = q32;
      return true;
    }
    if (ten_thousandths > 9999 || integer > 0x80000000u) return false;
    // (t * 2^32 + 5000) / 10000 with 2^32 = 429496 * 10000 + 7296, so the part left to divide is
    // n = t * 7296 + 5000 < 2^27. floor(n / 10000) in 32-bit arithmetic only (no division or 64-bit multiply
    // routine on a core without them): (n >> 11) * 13422 >> 16 is within one of it, then one correction.
    const std::uint32_t n = static_cast<std::uint32_t>(ten_thousandths) * 7296u + 5000u;
    std::uint32_t quotient = ((n >> 11) * 13422u) >> 16;
    if (quotient * 10000u > n) {
      --quotient;
    } else if (n - quotient * 10000u >= 10000u) {
      ++quotient;
    }
    const std::uint32_t fraction = static_cast<std::uint32_t>(ten_thousandths) * 429496u + quotient;
    const std::uint64_t magnitude = (static_cast<std::uint64_t>(integer) << 32) | fraction;
    if (!negative) {
      if (integer == 0x80000000u) return false;  // 2^31 and above
      raw = static_cast<std::int64_t>(magnitude);
    } else {
      if (integer == 0x80000000u && fraction != 0) return false;  // below -2^31
      raw = integer == 0x80000000u ? INT64_MIN : -static_cast<std::int64_t>(magnitude);
    }
    return true;
  }
};

/// The port through which a node writes VR() from the network. Implement it to map network writes onto
/// your own variables; `vr_table` is the ready-made implementation.
class vr_store {
 public:
  [[nodiscard]] virtual vr_write write(std::uint16_t vr, const network_value& value) noexcept = 0;

 protected:
  constexpr vr_store() = default;
  vr_store(const vr_store&) = default;
  vr_store& operator=(const vr_store&) = default;
  ~vr_store() = default;
};

/// Write policy hook of a table whose values are `Value`: return false to refuse a network write to `vr`
/// (in range of the table). `context` is the pointer given to the table with the policy.
template <class Value>
using vr_write_policy_for = bool (*)(void* context, std::uint16_t vr, Value value) noexcept;
using vr_write_policy = vr_write_policy_for<double>;

/// A table of `Size` VRs, initially 0. Default policy: accept every vr < Size (PROTOCOL.md 1.6).
/// `Value` is `double` (the default: what BASIC's VR() holds; needs floating point) or `std::int64_t`
/// (Q32.32, integer arithmetic only, for cores without an FPU: a CAN value of 2^31 or more is then
/// `value_out_of_range`).
template <std::size_t Size, class Value = double>
class vr_table final : public vr_store {
  static_assert(Size > 0 && Size <= 16384, "a VR table holds 1..16384 variables (14-bit vr on the ring)");
  static_assert(std::is_same_v<Value, double> || std::is_same_v<Value, std::int64_t>,
                "VR values are double or Q32.32 (std::int64_t)");

 public:
  constexpr vr_table() noexcept = default;
  constexpr explicit vr_table(vr_write_policy_for<Value> policy, void* context = nullptr) noexcept
      : policy_(policy), context_(context) {}

  [[nodiscard]] vr_write write(std::uint16_t vr, const network_value& value) noexcept override {
    if (vr >= Size) return vr_write::out_of_range;
    Value converted{};
    if constexpr (std::is_same_v<Value, double>) {
      converted = value.to_double();
    } else if (!value.to_q32(converted)) {
      return vr_write::value_out_of_range;
    }
    if (policy_ != nullptr && !policy_(context_, vr, converted)) return vr_write::refused;
    values_[vr] = converted;
    return vr_write::written;
  }

  /// The program's own access, as VR(vr) in BASIC. `vr` must be < Size.
  Value& operator[](std::size_t vr) noexcept { return values_[vr]; }
  Value operator[](std::size_t vr) const noexcept { return values_[vr]; }
  static constexpr std::size_t size() noexcept { return Size; }

 private:
  Value values_[Size] = {};
  vr_write_policy_for<Value> policy_ = nullptr;
  void* context_ = nullptr;
};

}  // namespace trionet

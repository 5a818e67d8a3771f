// VR(): the global variables of a Motion Coordinator that the network writes without the user program.
//
// Both the fibre ring (direct variable transfer, PROTOCOL.md 1.6) and the CAN VR exchange (2.2) write
// VR() through the same hook, `vr_store`, so that one write policy governs every network write.
// Cost: `vr_table<N>` is N doubles plus two pointers; `write` is O(1) and may be called from an ISR
// (the policy callback then runs in that context too).
#pragma once

#include <cstddef>
#include <cstdint>

namespace trionet {

/// What became of a VR write that arrived from the network.
enum class vr_write : std::uint8_t {
  written,       ///< VR(vr) now holds the value
  refused,       ///< the node's write policy refused this vr; nothing changed
  out_of_range,  ///< vr is past the end of the VR table; nothing changed
};

/// The port through which a node writes VR() from the network. Implement it to map network writes onto
/// your own variables; `vr_table` is the ready-made implementation.
class vr_store {
 public:
  [[nodiscard]] virtual vr_write write(std::uint16_t vr, double value) noexcept = 0;

 protected:
  vr_store() = default;
  vr_store(const vr_store&) = default;
  vr_store& operator=(const vr_store&) = default;
  ~vr_store() = default;
};

/// Write policy hook: return false to refuse a network write to `vr` (in range of the table).
/// `context` is the pointer given to the table with the policy.
using vr_write_policy = bool (*)(void* context, std::uint16_t vr, double value) noexcept;

/// A table of `Size` VRs (doubles, initially 0). Default policy: accept every vr < Size
/// (PROTOCOL.md 1.6). Values from the ring are Q32.32; a double holds them exactly while
/// |value| < 2^21, and to 53 significant bits beyond that.
template <std::size_t Size>
class vr_table final : public vr_store {
  static_assert(Size > 0 && Size <= 16384, "a VR table holds 1..16384 variables (14-bit vr on the ring)");

 public:
  vr_table() = default;
  explicit vr_table(vr_write_policy policy, void* context = nullptr) noexcept
      : policy_(policy), context_(context) {}

  [[nodiscard]] vr_write write(std::uint16_t vr, double value) noexcept override {
    if (vr >= Size) return vr_write::out_of_range;
    if (policy_ != nullptr && !policy_(context_, vr, value)) return vr_write::refused;
    values_[vr] = value;
    return vr_write::written;
  }

  /// The program's own access, as VR(vr) in BASIC. `vr` must be < Size.
  double& operator[](std::size_t vr) noexcept { return values_[vr]; }
  double operator[](std::size_t vr) const noexcept { return values_[vr]; }
  static constexpr std::size_t size() noexcept { return Size; }

 private:
  double values_[Size] = {};
  vr_write_policy policy_ = nullptr;
  void* context_ = nullptr;
};

}  // namespace trionet

// The Genius bus controller role (docs/protocol.md 3.4, docs/genius.md): a `genius::device` whose turn data
// is every device's outputs, one block per device (Start of block to its SBA) in one broadcast transmission
// per scan, and which collects every device's inputs (the broadcasts the devices send at their turns).
//
//   program: set_outputs(sba, bytes) ... publish_outputs() --> turn data: Start | block to 0 | block to 3 | ... | Stop
//   link side: the device core (its turn, collisions, deliveries) unchanged
//   program: collect() --> the inputs of SBA s, the latest broadcast heard from s
//
// It is the device core plus two tables that only the program side touches: the link side is exactly the
// device's (docs/design.md, "Contexts"). Cost: the device (turn data 3 x 31 x (OutputCapacity + 2) bytes: a
// block for each of the 31 other SBAs) plus 32 x (OutputCapacity + InputCapacity + 6) bytes of tables;
// `publish_outputs` O(outputs), `collect` O(the deliveries waiting). No heap.
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/genius/device.hpp"
#include "trionet/span.hpp"

namespace trionet::genius {

/// What became of outputs set (misuse of the API; nothing changes unless `ok`).
enum class outputs_status : std::uint8_t {
  ok,                   ///< stored: the next `publish_outputs` sends them
  sba_out_of_range,     ///< SBA > 31
  too_long,             ///< more bytes than OutputCapacity
  own_sba,              ///< the controller's own SBA
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(outputs_status value) noexcept {
  switch (value) {
    case outputs_status::ok:
      return "ok";
    case outputs_status::sba_out_of_range:
      return "sba_out_of_range";
    case outputs_status::too_long:
      return "too_long";
    case outputs_status::own_sba:
      return "own_sba";
  }
  return "unknown";
}

/// A bus controller: the device core `Device` with outputs of up to `OutputCapacity` bytes to each other SBA
/// and inputs of up to `InputCapacity` bytes from each. `Device` must hold a turn of 31 blocks.
template <std::size_t OutputCapacity = 16, std::size_t InputCapacity = 16,
          class Device = device<31 * (OutputCapacity + 2), 256>>
class bus_controller : public Device {
  static_assert(OutputCapacity >= 1 && OutputCapacity <= 255, "a block carries 1..255 bytes");
  static_assert(InputCapacity >= 1 && InputCapacity <= 255, "a delivery carries at most 255 bytes");
  static_assert(Device::turn_capacity >= 31 * (OutputCapacity + 2),
                "the device core's turn data must hold a block of OutputCapacity bytes for 31 devices");

 public:
  using Device::Device;

  static constexpr std::size_t output_capacity = OutputCapacity;  ///< bytes of outputs per device
  static constexpr std::size_t input_capacity = InputCapacity;    ///< bytes of inputs kept per device

  /// Program side: the outputs of SBA `sba` (empty: none, it gets no block). Sent from the next
  /// `publish_outputs` on.
  outputs_status set_outputs(std::uint8_t sba, byte_view outputs) noexcept {
    if (sba > max_sba) return outputs_status::sba_out_of_range;
    if (sba == this->sba()) return outputs_status::own_sba;
    if (outputs.size() > OutputCapacity) return outputs_status::too_long;
    for (std::size_t i = 0; i < outputs.size(); ++i) outputs_[sba][i] = outputs[i];
    output_length_[sba] = static_cast<std::uint8_t>(outputs.size());
    return outputs_status::ok;
  }

  /// Program side: the outputs set for SBA `sba` (empty if none or out of range).
  [[nodiscard]] byte_view outputs(std::uint8_t sba) const noexcept {
    if (sba > max_sba) return {};
    return byte_view(outputs_[sba], output_length_[sba]);
  }

  /// Program side: makes the outputs set so far the controller's turn data: one broadcast per turn, a block
  /// to each SBA that has outputs, in SBA order. No outputs at all: the controller's turns pass.
  turn_data_status publish_outputs() noexcept {
    segment blocks[32];
    std::size_t count = 0;
    for (std::uint8_t sba = 0; sba <= max_sba; ++sba) {
      if (output_length_[sba] == 0) continue;
      blocks[count++] = segment{true, sba, byte_view(outputs_[sba], output_length_[sba])};
    }
    return this->set_turn_data(span<const segment>(blocks, count));
  }

  /// Program side: takes every waiting delivery. A broadcast from SBA s is s's inputs: kept (its first
  /// InputCapacity bytes; a longer one is counted in `input_overflows`) and `input_updates(s)` counts it.
  /// `visit(delivery_result, byte_view data)` sees every delivery, inputs included. Returns how many were
  /// taken.
  template <class Visit>
  std::size_t collect(Visit&& visit) noexcept {
    std::size_t taken = 0;
    for (;;) {
      std::uint8_t data[255];
      const delivery_result r = this->read(byte_buffer(data, sizeof data));
      if (!r) break;
      ++taken;
      if (r.kind == delivery_kind::broadcast) {
        const std::size_t kept = r.length < InputCapacity ? r.length : InputCapacity;
        if (kept != r.length) ++input_overflows_;
        for (std::size_t i = 0; i < kept; ++i) inputs_[r.sender][i] = data[i];
        input_length_[r.sender] = static_cast<std::uint8_t>(kept);
        ++input_updates_[r.sender];
      }
      visit(r, byte_view(data, r.length));
    }
    return taken;
  }
  /// Program side: `collect` without a visitor.
  std::size_t collect() noexcept {
    return collect([](const delivery_result&, byte_view) {});
  }

  /// Program side: the latest inputs collected from SBA `sba` (empty if none yet or out of range).
  [[nodiscard]] byte_view inputs(std::uint8_t sba) const noexcept {
    if (sba > max_sba) return {};
    return byte_view(inputs_[sba], input_length_[sba]);
  }
  /// Program side: how many times inputs from `sba` were collected (wraps at 2^32).
  [[nodiscard]] std::uint32_t input_updates(std::uint8_t sba) const noexcept {
    return sba > max_sba ? 0 : input_updates_[sba];
  }
  /// Program side: inputs longer than InputCapacity (kept cut to it).
  [[nodiscard]] std::uint32_t input_overflows() const noexcept { return input_overflows_; }

 private:
  std::uint8_t outputs_[32][OutputCapacity] = {};
  std::uint8_t output_length_[32] = {};
  std::uint8_t inputs_[32][InputCapacity] = {};
  std::uint8_t input_length_[32] = {};
  std::uint32_t input_updates_[32] = {};
  std::uint32_t input_overflows_ = 0;
};

}  // namespace trionet::genius

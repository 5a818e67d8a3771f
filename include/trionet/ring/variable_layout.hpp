// The layout of a direct variable transfer's fields (docs/protocol.md 1.3), as a policy type.
//
// The VR number travels as two 7-bit groups and the Q32.32 value as ten. The default sends each field's least
// significant group first and computes the CRC over the bytes as sent; real hardware may differ, so each
// field's group order, and which byte order the CRC covers, are parameters:
//
//   vr, least significant first     V0 = vr bits 6..0     V1 = vr bits 13..7
//   vr, most significant first      V0 = vr bits 13..7    V1 = vr bits 6..0
//   value, least significant first  X0 = bits 6..0 ... X8 = bits 62..56, X9 = bit 63 (bits 6..1 zero)
//   value, most significant first   X0 = bit 63 (bits 6..1 zero), X1 = bits 62..56 ... X9 = bits 6..0
//   CRC as sent                     over V0 V1 X0..X9 in the order they travel
//   CRC least significant first     over the same 12 groups in the default order (each field's least
//                                   significant group first), whatever order they travel in
//
// `variable_layout<>` is a static policy (the encoders, the decoder and the nodes take it as a template
// parameter; the default compiles to exactly the code of a fixed layout); `variable_layout_parameters` holds
// the same choices as values, for a profile read at run time. Stateless; safe from an ISR.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace trionet::ring {

/// The order of a field's 7-bit groups on the wire.
enum class group_order : std::uint8_t {
  least_significant_first = 0,  ///< the default (docs/protocol.md 1.3)
  most_significant_first = 1,   ///< the most significant group first
};

/// The order's name, the enumerator's spelling.
constexpr const char* to_string(group_order order) noexcept {
  switch (order) {
    case group_order::least_significant_first:
      return "least_significant_first";
    case group_order::most_significant_first:
      return "most_significant_first";
  }
  return "unknown";
}

/// Which order of the 12 field bytes the CRC covers.
enum class crc_input : std::uint8_t {
  as_sent = 0,                  ///< V0 V1 X0..X9 as they travel (the default)
  least_significant_first = 1,  ///< the groups in the default order, whatever order they travel in
};

/// The input's name, the enumerator's spelling.
constexpr const char* to_string(crc_input input) noexcept {
  switch (input) {
    case crc_input::as_sent:
      return "as_sent";
    case crc_input::least_significant_first:
      return "least_significant_first";
  }
  return "unknown";
}

/// The layout choices as values (a profile read at run time). Defaults: docs/protocol.md 1.3.
struct variable_layout_parameters {
  group_order vr = group_order::least_significant_first;     ///< order of the VR number's groups (V0 V1)
  group_order value = group_order::least_significant_first;  ///< order of the value's groups (X0..X9)
  crc_input crc = crc_input::as_sent;                        ///< which order of the field bytes the CRC covers

  /// Equal when every choice is.
  friend constexpr bool operator==(const variable_layout_parameters& a,
                                   const variable_layout_parameters& b) noexcept {
    return a.vr == b.vr && a.value == b.value && a.crc == b.crc;
  }
  /// Not equal when any choice differs.
  friend constexpr bool operator!=(const variable_layout_parameters& a,
                                   const variable_layout_parameters& b) noexcept {
    return !(a == b);
  }
};

/// The 12 field bytes of a frame laid out with `vr` and `value` orders, put in the default order (or back:
/// the map swaps the groups of each field whose order is not the default, so it is its own inverse).
constexpr void reorder_variable_fields(const std::uint8_t* in, std::uint8_t* out, group_order vr,
                                       group_order value) noexcept {
  const bool swap_vr = vr == group_order::most_significant_first;
  const bool swap_value = value == group_order::most_significant_first;
  out[0] = in[swap_vr ? 1 : 0];
  out[1] = in[swap_vr ? 0 : 1];
  for (std::size_t k = 0; k < 10; ++k) out[2 + k] = in[2 + (swap_value ? 9 - k : k)];
}

/// Reads the vr and Q32.32 value of the field bytes in the default layout (no checks).
inline void read_variable_data(const std::uint8_t* data, std::uint16_t& vr, std::int64_t& value) noexcept {
  vr = static_cast<std::uint16_t>(data[0] | (data[1] << 7));
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ && UINTPTR_MAX > 0xFFFFFFFFu
  // On 64-bit cores: X0..X7 as one little-endian word, their 7-bit groups squeezed together in three steps.
  std::uint64_t w = 0;
  std::memcpy(&w, data + 2, sizeof w);
  w = (w & 0x007F007F007F007Full) | ((w & 0x7F007F007F007F00ull) >> 1);
  w = (w & 0x00003FFF00003FFFull) | ((w & 0x3FFF00003FFF0000ull) >> 2);
  w = (w & 0x000000000FFFFFFFull) | ((w & 0x0FFFFFFF00000000ull) >> 4);
  value = static_cast<std::int64_t>(w | static_cast<std::uint64_t>(data[10]) << 56 |
                                    static_cast<std::uint64_t>(data[11]) << 63);
#else
  std::uint64_t bits = 0;  // a loop: the smallest code on a 32-bit core
  for (std::size_t k = 10; k-- > 0;) bits = (bits << 7) | data[2 + k];
  value = static_cast<std::int64_t>(bits);
#endif
}

}  // namespace trionet::ring

namespace trionet::detail {
// The 12 field bytes in the default layout.
constexpr void write_default_fields(std::uint8_t* out, std::uint16_t vr, std::int64_t value) noexcept {
  out[0] = static_cast<std::uint8_t>(vr & 0x7F);
  out[1] = static_cast<std::uint8_t>((vr >> 7) & 0x7F);
  std::uint64_t bits = static_cast<std::uint64_t>(value);
  for (std::size_t k = 0; k < 10; ++k) {
    out[2 + k] = static_cast<std::uint8_t>(bits & 0x7F);
    bits >>= 7;
  }
}
}  // namespace trionet::detail

namespace trionet::ring {

/// The 12 field bytes V0 V1 X0..X9 of `vr` (0..16383) and the Q32.32 `value`, in the given layout.
constexpr void write_variable_fields(std::uint8_t* out, std::uint16_t vr, std::int64_t value,
                                     group_order vr_order, group_order value_order) noexcept {
  std::uint8_t fields[12] = {};
  detail::write_default_fields(fields, vr, value);
  reorder_variable_fields(fields, out, vr_order, value_order);
}

/// Reads the vr and value of 12 field bytes in the given layout (no checks).
constexpr void read_variable_fields(const std::uint8_t* data, std::uint16_t& vr, std::int64_t& value,
                                    group_order vr_order, group_order value_order) noexcept {
  std::uint8_t fields[12] = {};
  reorder_variable_fields(data, fields, vr_order, value_order);
  vr = static_cast<std::uint16_t>(fields[0] | (fields[1] << 7));
  std::uint64_t bits = 0;
  for (std::size_t k = 10; k-- > 0;) bits = (bits << 7) | fields[2 + k];
  value = static_cast<std::int64_t>(bits);
}

/// The index (among the 12 field bytes) of the value group that carries bit 63: its bits 6..1 must be 0.
constexpr std::size_t top_value_group(group_order value_order) noexcept {
  return value_order == group_order::least_significant_first ? 11 : 2;
}

/// The layout as a static policy: `VrOrder` and `ValueOrder` for the fields, `CrcInput` for the CRC.
template <group_order VrOrder = group_order::least_significant_first,
          group_order ValueOrder = group_order::least_significant_first,
          crc_input CrcInput = crc_input::as_sent>
struct variable_layout {
  /// The same choices as values.
  static constexpr variable_layout_parameters parameters{VrOrder, ValueOrder, CrcInput};
  /// True when both fields travel in the default order (no groups to swap).
  static constexpr bool default_order =
      VrOrder == group_order::least_significant_first && ValueOrder == group_order::least_significant_first;
  /// Index of the group whose bits 6..1 must be zero (X9 by default).
  static constexpr std::size_t top_group = top_value_group(ValueOrder);

  /// The 12 field bytes V0 V1 X0..X9 of `vr` (0..16383) and `value`.
  static constexpr void write(std::uint8_t* out, std::uint16_t vr, std::int64_t value) noexcept {
    if constexpr (default_order) {
      detail::write_default_fields(out, vr, value);
    } else {
      write_variable_fields(out, vr, value, VrOrder, ValueOrder);
    }
  }
  /// The vr and value of 12 field bytes (no checks).
  static void read(const std::uint8_t* data, std::uint16_t& vr, std::int64_t& value) noexcept {
    if constexpr (default_order) {
      read_variable_data(data, vr, value);
    } else {
      read_variable_fields(data, vr, value, VrOrder, ValueOrder);
    }
  }
  /// The 12 bytes the CRC covers: `data` itself, or `scratch` filled with them.
  static constexpr const std::uint8_t* crc_bytes(const std::uint8_t* data, std::uint8_t* scratch) noexcept {
    if constexpr (CrcInput == crc_input::as_sent || default_order) {
      (void)scratch;
      return data;
    } else {
      reorder_variable_fields(data, scratch, VrOrder, ValueOrder);
      return scratch;
    }
  }
};

/// The default layout (docs/protocol.md 1.3): least significant group first, the CRC over the bytes as sent.
using default_variable_layout = variable_layout<>;

/// Calls `f` with the static policy `variable_layout<...>{}` that `p` describes (for host tools that read a
/// layout at run time and run templated code with it). Returns what `f` returns.
template <class F>
constexpr decltype(auto) with_variable_layout(const variable_layout_parameters& p, F&& f) {
  constexpr group_order l = group_order::least_significant_first;
  constexpr group_order m = group_order::most_significant_first;
  constexpr crc_input s = crc_input::as_sent;
  constexpr crc_input d = crc_input::least_significant_first;
  const bool vr_msf = p.vr == m;
  const bool value_msf = p.value == m;
  if (p.crc == d) {
    if (vr_msf && value_msf) return f(variable_layout<m, m, d>{});
    if (vr_msf) return f(variable_layout<m, l, d>{});
    if (value_msf) return f(variable_layout<l, m, d>{});
    return f(variable_layout<l, l, d>{});
  }
  if (vr_msf && value_msf) return f(variable_layout<m, m, s>{});
  if (vr_msf) return f(variable_layout<m, l, s>{});
  if (value_msf) return f(variable_layout<l, m, s>{});
  return f(variable_layout<l, l, s>{});
}

}  // namespace trionet::ring

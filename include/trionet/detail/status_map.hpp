// One status enum onto another where the second lists outcomes of the first (a CAN send's status takes the
// VR encoder's and the port's failures, a CAN receive's status the decoder's and the VR store's): the second
// enum repeats a run of the first's enumerators in the same order, each name ending with the first's name
// (`busy` -> `port_busy`), so the conversion is an offset. The names are compared at compile time through
// each enum's `to_string`, so an enumerator added to one enum and not the other fails the build instead of
// mapping to the wrong outcome.
#pragma once

#include "trionet/detail/attributes.hpp"

namespace trionet::detail {

/// True when `name` ends with `tail`.
constexpr bool ends_with(const char* name, const char* tail) noexcept {
  const char* n = name;
  while (*n != '\0') ++n;
  const char* t = tail;
  while (*t != '\0') ++t;
  while (t != tail) {
    if (n == name || *--n != *--t) return false;
  }
  return true;
}

/// True when each of the enumerators `First` .. `Last` of one status enum has its outcome, under its name, at
/// the same place in another enum from `To` on.
template <auto First, auto Last, auto To>
constexpr bool names_agree() noexcept {
  using from_type = decltype(First);
  using to_type = decltype(To);
  for (int v = static_cast<int>(First); v <= static_cast<int>(Last); ++v) {
    if (!ends_with(to_string(static_cast<to_type>(v - static_cast<int>(First) + static_cast<int>(To))),
                   to_string(static_cast<from_type>(v)))) {
      return false;
    }
  }
  return true;
}

/// The enumerators `First` .. `Last` of one status enum, and where their outcomes start in another (`To`).
template <auto First, auto Last, auto To>
struct status_map {
  using from_type = decltype(First);
  using to_type = decltype(To);
  static_assert(static_cast<int>(First) <= static_cast<int>(Last), "an empty run of enumerators");
  static_assert(names_agree<First, Last, To>(), "the enumerators of the two status enums do not line up by name");

  /// The outcome in `to_type` of `from`, one of `First` .. `Last`.
  static constexpr to_type of(from_type from) noexcept {
    TRIONET_ASSERT(static_cast<int>(from) >= static_cast<int>(First) &&
                   static_cast<int>(from) <= static_cast<int>(Last));
    return static_cast<to_type>(static_cast<int>(from) - static_cast<int>(First) + static_cast<int>(To));
  }
};

}  // namespace trionet::detail

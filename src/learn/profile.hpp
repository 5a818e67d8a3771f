// A profile: every configurable wire parameter of a network in one JSON file (docs/profile.md), read with
// strict validation, written back, and turned into a C++ header of constexpr policies for a firmware build.
// The default profile is the protocol reference's decisions (docs/protocol.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "learn/json.hpp"
#include "trionet/can/vr_codec.hpp"
#include "trionet/genius/crc6.hpp"
#include "trionet/genius/transmission.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/keypad_codes.hpp"
#include "trionet/ring/keypad_display.hpp"
#include "trionet/ring/variable_layout.hpp"

namespace trionet::learn {

/// The key OFF character of a keypad in keypad mode 127 (docs/protocol.md 1.7).
enum class key_off_rule : std::uint8_t {
  plus_64,  ///< key ON + 64 where that stays below 128, else the same (the default)
  same,     ///< the key ON character
};

constexpr const char* to_string(key_off_rule rule) noexcept {
  switch (rule) {
    case key_off_rule::plus_64:
      return "plus_64";
    case key_off_rule::same:
      return "same";
  }
  return "unknown";
}

/// The library's function for a rule (for `ring::keypad_config::key_off_code`).
constexpr std::uint8_t (*key_off_function(key_off_rule rule) noexcept)(std::uint8_t) noexcept {
  return rule == key_off_rule::same ? ring::same_key_off_code : ring::default_key_off_code;
}

/// Limits of the ring's character capacities (the decoder's and the receive buffer's).
constexpr std::size_t min_characters = 1;
constexpr std::size_t max_characters_limit = 65534;

struct ring_profile {
  ring::crc16_parameters crc{};               ///< docs/protocol.md 1.3: CRC-16/CCITT-FALSE
  ring::variable_layout_parameters layout{};  ///< least significant group first, CRC over the bytes as sent
  std::size_t max_characters = 256;           ///< longest character transfer accepted (1.4)
  std::size_t receive_buffer = 256;           ///< an MC's receive buffer in characters (1.6)
};

/// The profile's name of each key (`keypad.codes.<name>`), in the order of `ring::key`.
inline constexpr const char* keypad_key_names[ring::key_count] = {
    "0", "1",  "2",    "3",     "4",   "5",  "6",     "7",     "8",
    "9", "up", "down", "clear", "yes", "no", "point", "start", "stop"};

struct keypad_profile {
  ring::keypad_codes codes = ring::default_keypad_codes;  ///< 1.8
  ring::defkey_table defkey = ring::default_defkey;       ///< 1.6 / 1.8
  key_off_rule key_off = key_off_rule::plus_64;           ///< 1.7
  ring::display_model display{};                          ///< 1.9
};

struct can_profile {
  std::uint8_t node_count = 5;                               ///< 2..11 (2.1)
  can::byte_order byte_order = can::byte_order::big_endian;  ///< of the numbers in a message (2.2)
};

struct genius_profile {
  genius::crc6_parameters crc{};     ///< 3.2: CRC-6/G-704
  genius::control_layout control{};  ///< 3.2: the control characters' bit layout
};

struct profile {
  std::string name;  ///< free text, for people
  ring_profile ring;
  keypad_profile keypad;
  can_profile can;
  genius_profile genius;
};

[[nodiscard]] bool operator==(const profile& a, const profile& b) noexcept;
inline bool operator!=(const profile& a, const profile& b) noexcept {
  return !(a == b);
}

/// The schema version this library reads and writes ("trionet_profile": 1).
constexpr int profile_version = 1;

enum class profile_status : std::uint8_t {
  ok,
  not_json,             ///< the text is not JSON: `json` says why
  unsupported_version,  ///< "trionet_profile" is not 1
  missing_key,          ///< "trionet_profile" is missing
  unknown_key,          ///< a key the schema does not have
  wrong_type,           ///< e.g. a string where a boolean belongs
  out_of_range,         ///< a number or name outside what the key allows
  duplicate_code,  ///< two keypad keys send one raw character, or two Genius control characters share a tag
};

constexpr const char* to_string(profile_status status) noexcept {
  switch (status) {
    case profile_status::ok:
      return "ok";
    case profile_status::not_json:
      return "not_json";
    case profile_status::unsupported_version:
      return "unsupported_version";
    case profile_status::missing_key:
      return "missing_key";
    case profile_status::unknown_key:
      return "unknown_key";
    case profile_status::wrong_type:
      return "wrong_type";
    case profile_status::out_of_range:
      return "out_of_range";
    case profile_status::duplicate_code:
      return "duplicate_code";
  }
  return "unknown";
}

struct [[nodiscard]] profile_result {
  profile_status status = profile_status::ok;
  profile value;                       ///< the profile (status ok)
  std::string key;                     ///< the offending key, as a path: "ring.crc.polynomial"
  std::string message;                 ///< what was expected
  json_status json = json_status::ok;  ///< for not_json
  std::size_t line = 0;                ///< where (1-based; 0 if not known)
  std::size_t column = 0;
  explicit operator bool() const noexcept { return status == profile_status::ok; }
};

/// Reads a profile. Keys left out keep their default; anything else wrong is an error naming the key.
[[nodiscard]] profile_result read_profile(std::string_view json);

/// The profile as JSON, every key written, in the schema's order; read_profile gives it back.
[[nodiscard]] std::string write_profile(const profile& p);

enum class header_status : std::uint8_t {
  ok,
  bad_namespace,  ///< not a C++ namespace name (identifiers joined by "::")
};

constexpr const char* to_string(header_status status) noexcept {
  switch (status) {
    case header_status::ok:
      return "ok";
    case header_status::bad_namespace:
      return "bad_namespace";
  }
  return "unknown";
}

struct [[nodiscard]] header_result {
  header_status status = header_status::ok;
  std::string text;
  std::string reason;  ///< bad_namespace: why the name cannot be the header's namespace ("'int' is a C++ keyword")
  explicit operator bool() const noexcept { return status == header_status::ok; }
};

/// A C++17 header with the profile as constexpr policies and constants in `namespace_name`, for a firmware
/// build (docs/profile.md shows one). It includes only trionet headers. `bad_namespace` (with its reason) for a
/// name that is not identifiers joined by ::, has a C++ keyword as one of them, or is or names trionet.
[[nodiscard]] header_result profile_header(const profile& p,
                                           std::string_view namespace_name = "trionet_profile");

}  // namespace trionet::learn

// Membrane keypad keys, the raw characters they send and the DEFKEY table (docs/protocol.md 1.8).
//
//   key        raw (GET#4)   DEFKEY (GET#3)
//   0..9       '0'..'9'      0..9
//   up / +     'U'           10
//   down / -   'D'           11
//   CLR        'C'           12
//   Y / enter  'Y'           13
//   N          'N'           14
//   .          '.'           15
//   start      'S'           20
//   stop       'T'           21
//
// Both tables are constexpr data (flash on a microcontroller); nodes hold a pointer to the one they use.
#pragma once

#include <cstddef>
#include <cstdint>

namespace trionet::ring {

/// The 18 keys of the membrane keypad.
enum class key : std::uint8_t {
  digit_0,  ///< 0
  digit_1,  ///< 1
  digit_2,  ///< 2
  digit_3,  ///< 3
  digit_4,  ///< 4
  digit_5,  ///< 5
  digit_6,  ///< 6
  digit_7,  ///< 7
  digit_8,  ///< 8
  digit_9,  ///< 9
  up,       ///< up / +
  down,     ///< down / -
  clear,    ///< CLR
  yes,      ///< Y / enter
  no,       ///< N
  point,    ///< decimal point
  start,    ///< start
  stop,     ///< stop
};
constexpr std::size_t key_count = 18;  ///< the number of keys

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(key value) noexcept {
  switch (value) {
    case key::digit_0:
      return "digit_0";
    case key::digit_1:
      return "digit_1";
    case key::digit_2:
      return "digit_2";
    case key::digit_3:
      return "digit_3";
    case key::digit_4:
      return "digit_4";
    case key::digit_5:
      return "digit_5";
    case key::digit_6:
      return "digit_6";
    case key::digit_7:
      return "digit_7";
    case key::digit_8:
      return "digit_8";
    case key::digit_9:
      return "digit_9";
    case key::up:
      return "up";
    case key::down:
      return "down";
    case key::clear:
      return "clear";
    case key::yes:
      return "yes";
    case key::no:
      return "no";
    case key::point:
      return "point";
    case key::start:
      return "start";
    case key::stop:
      return "stop";
  }
  return "unknown";
}

/// The key a name means, in the key script's words (docs/basic.md): "0".."9", "up" or "+", "down" or "-",
/// "clr", "y" or "enter", "n", ".", "start", "stop", in any case. False for any other name.
constexpr bool key_named(const char* name, std::size_t length, key& out) noexcept {
  struct named {
    const char* name;
    key value;
  };
  constexpr named names[] = {{"0", key::digit_0},  {"1", key::digit_1},  {"2", key::digit_2},     {"3", key::digit_3},
                             {"4", key::digit_4},  {"5", key::digit_5},  {"6", key::digit_6},     {"7", key::digit_7},
                             {"8", key::digit_8},  {"9", key::digit_9},  {"up", key::up},         {"+", key::up},
                             {"down", key::down},  {"-", key::down},     {"clr", key::clear},     {"y", key::yes},
                             {"enter", key::yes},  {"n", key::no},       {".", key::point},       {"start", key::start},
                             {"stop", key::stop}};
  for (const named& candidate : names) {
    std::size_t i = 0;
    for (; i < length && candidate.name[i] != '\0'; ++i) {
      const char c = name[i] >= 'A' && name[i] <= 'Z' ? static_cast<char>(name[i] - 'A' + 'a') : name[i];
      if (c != candidate.name[i]) break;
    }
    if (i == length && candidate.name[i] == '\0') {
      out = candidate.value;
      return true;
    }
  }
  return false;
}

/// The key for a digit 0..9 (taken modulo 10).
constexpr key digit_key(unsigned digit) noexcept {
  return static_cast<key>(digit % 10);
}

/// The raw character each key sends (key ON), indexed by `key`.
struct keypad_codes {
  std::uint8_t raw[key_count];  ///< by key, in the order of `key`
  /// The raw character of key `k`.
  constexpr std::uint8_t operator[](key k) const noexcept { return raw[static_cast<std::size_t>(k)]; }
};

/// The characters the manual's keypad sends (the table at the top of this file).
inline constexpr keypad_codes default_keypad_codes = {
    {'0', '1', '2', '3', '4', '5', '6', '7', '8', '9', 'U', 'D', 'C', 'Y', 'N', '.', 'S', 'T'}};

/// The values the manual's programs expect from GET#3, indexed by `key`.
inline constexpr std::uint8_t defkey_values[key_count] = {0, 1,  2,  3,  4,  5,  6,  7,  8,
                                                          9, 10, 11, 12, 13, 14, 15, 20, 21};

/// DEFKEY: GET#3 translates each received character (0..127) through this table.
struct defkey_table {
  std::uint8_t value[128];  ///< by received character
  /// What GET#3 returns for the received character `c` (bit 7 ignored).
  constexpr std::uint8_t operator[](std::uint8_t c) const noexcept { return value[c & 0x7F]; }
};

/// The identity, except that the default keypad's raw characters map to the manual's key values.
constexpr defkey_table make_default_defkey(const keypad_codes& codes = default_keypad_codes) noexcept {
  defkey_table table{};
  for (unsigned c = 0; c < 128; ++c) table.value[c] = static_cast<std::uint8_t>(c);
  for (std::size_t k = 0; k < key_count; ++k) table.value[codes.raw[k] & 0x7F] = defkey_values[k];
  return table;
}

/// The DEFKEY table of the default keypad.
inline constexpr defkey_table default_defkey = make_default_defkey();

/// The key OFF character for a key ON character (docs/protocol.md 1.7, the default): on + 64 where that stays
/// below 128, else the same character.
constexpr std::uint8_t default_key_off_code(std::uint8_t on) noexcept {
  return on + 64 < 128 ? static_cast<std::uint8_t>(on + 64) : on;
}

/// Another key OFF rule (a profile's choice): the key OFF character is the key ON character.
constexpr std::uint8_t same_key_off_code(std::uint8_t on) noexcept {
  return on;
}

}  // namespace trionet::ring

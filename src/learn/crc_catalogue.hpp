// The CRC RevEng catalogue's 6-bit and 16-bit CRCs (crc_catalogue.txt, built in), and a reader for its line
// format:
//
//   width=16 poly=0x1021 init=0xffff refin=false refout=false xorout=0x0000 check=0x29b1
//   name="CRC-16/IBM-3740"
//
// poly, init and xorout in non-reflected notation; check = the CRC of the ASCII bytes "123456789". Other
// fields of the catalogue (residue, alias) are accepted and ignored.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace trionet::learn {

struct catalogue_entry {
  std::string name;
  unsigned width = 0;  ///< 1..16
  std::uint16_t polynomial = 0;
  std::uint16_t initial = 0;
  bool reflect_in = false;
  bool reflect_out = false;
  std::uint16_t xor_out = 0;
  std::uint16_t check = 0;
};

enum class catalogue_status : std::uint8_t {
  ok,
  bad_field,      ///< a word that is not key=value, an unknown key, or a malformed value
  missing_field,  ///< width, poly, init, refin, refout, xorout, check or name is missing
  out_of_range,   ///< width not 1..16, or a value wider than the width
};

constexpr const char* to_string(catalogue_status status) noexcept {
  switch (status) {
    case catalogue_status::ok:
      return "ok";
    case catalogue_status::bad_field:
      return "bad_field";
    case catalogue_status::missing_field:
      return "missing_field";
    case catalogue_status::out_of_range:
      return "out_of_range";
  }
  return "unknown";
}

struct [[nodiscard]] catalogue_result {
  catalogue_status status = catalogue_status::ok;
  std::vector<catalogue_entry> entries;
  std::size_t line = 0;  ///< 1-based line of the first error
  std::string detail;    ///< the offending word or field
  explicit operator bool() const noexcept { return status == catalogue_status::ok; }
};

/// Reads catalogue lines; blank lines and lines starting with '#' are skipped. Stops at the first error.
[[nodiscard]] catalogue_result parse_crc_catalogue(std::string_view text);

/// The built-in catalogue: the CRC RevEng catalogue's 6-bit and 16-bit entries.
[[nodiscard]] const std::vector<catalogue_entry>& crc_catalogue();

}  // namespace trionet::learn

// The reference CRC: Boost.CRC's crc_optimal with the parameters of CRC-16/CCITT-FALSE (poly 0x1021, init
// 0xFFFF, no final xor, not reflected). Boost's headers are included as system headers (see CMakeLists.txt)
// so that trionet's strict warnings apply to trionet's code only.
#pragma once

#include <boost/crc.hpp>
#include <cstddef>
#include <cstdint>

namespace trionet::bench {

using boost_crc16_ccitt_false_type = boost::crc_optimal<16, 0x1021, 0xFFFF, 0, false, false>;

inline std::uint16_t boost_crc16_ccitt_false(const std::uint8_t* data, std::size_t size) noexcept {
  boost_crc16_ccitt_false_type crc;
  crc.process_bytes(data, size);
  return crc.checksum();
}

}  // namespace trionet::bench

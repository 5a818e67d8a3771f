// Record layouts of trionet captures (see trionet/host/capture.hpp).
#include "trionet/host/capture.hpp"

namespace trionet::host {
namespace {

constexpr std::uint8_t canfd_fdf = 0x04;               // flags: a CAN FD frame (CANFD_FDF)
constexpr std::uint8_t canxl_xlf = 0x80;               // flags: a CAN XL frame (CANXL_XLF)
constexpr std::size_t canfd_record_length = 72;        // struct canfd_frame

}  // namespace

std::vector<std::uint16_t> genius_record_words(byte_view record) {
  std::vector<std::uint16_t> words;
  words.reserve(record.size() / genius_record_bytes_per_character);
  for (std::size_t i = 0; i + 1 < record.size(); i += genius_record_bytes_per_character) {
    words.push_back(static_cast<std::uint16_t>(record[i] << 8 | record[i + 1]));
  }
  return words;
}

std::array<std::uint8_t, socketcan_record_length> socketcan_record(const can::frame& frame) {
  std::array<std::uint8_t, socketcan_record_length> out{};
  for (std::size_t i = 0; i < 4; ++i) out[i] = static_cast<std::uint8_t>(frame.id >> (24 - 8 * i));
  const std::uint8_t length = frame.remote() ? (frame.dlc > 8 ? std::uint8_t{8} : frame.dlc)
                                             : frame.data_length();
  out[4] = length;
  out[6] = frame.dlc > 8 && length == 8 ? frame.dlc : std::uint8_t{0};  // len8_dlc
  for (std::size_t i = 0; i < frame.data_length(); ++i) out[8 + i] = frame.data[i];
  return out;
}

socketcan_record_result read_socketcan_record(byte_view record) {
  socketcan_record_result result;
  if (record.size() < 8) {
    result.status = socketcan_record_status::too_short;
    return result;
  }
  const std::uint32_t id = std::uint32_t{record[0]} << 24 | std::uint32_t{record[1]} << 16 |
                           std::uint32_t{record[2]} << 8 | record[3];
  const std::uint8_t length = record[4];
  const std::uint8_t flags = record[5];
  if ((flags & (canfd_fdf | canxl_xlf)) != 0 || record.size() == canfd_record_length) {
    result.status = socketcan_record_status::not_classic;
  } else if ((id & can_error_flag) != 0) {
    result.status = socketcan_record_status::error_frame;
  } else if (length > 8) {
    result.status = socketcan_record_status::bad_length;
  } else if ((id & can::frame::extended_flag) == 0 && (id & ~(can::frame::remote_flag | 0x7FFu)) != 0) {
    result.status = socketcan_record_status::bad_identifier;
  }
  if (result.status != socketcan_record_status::ok) return result;
  can::frame& frame = result.frame;
  frame.id = id & (can::frame::extended_flag | can::frame::remote_flag | can::frame::extended_mask);
  frame.dlc = length == 8 && record[6] > 8 && record[6] <= 15 ? record[6] : length;
  if (!frame.remote()) {
    if (record.size() < 8u + length) {
      result.status = socketcan_record_status::too_short;
      return result;
    }
    for (std::size_t i = 0; i < length; ++i) frame.data[i] = record[8 + i];
  }
  return result;
}

std::vector<std::uint8_t> socketcan_record_of(const candump_record& record) {
  std::vector<std::uint8_t> out;
  const auto header = [&](std::uint32_t id, std::size_t size) {
    out.assign(size, 0);
    for (std::size_t i = 0; i < 4; ++i) out[i] = static_cast<std::uint8_t>(id >> (24 - 8 * i));
  };
  switch (record.type) {
    case candump_frame_type::classic: {
      if (!record.classic_frame()) return out;  // a standard identifier above 7FF: no SocketCAN frame
      const auto classic = socketcan_record(record.frame);
      out.assign(classic.begin(), classic.end());
      return out;
    }
    case candump_frame_type::error:
      header(record.can_id, 16);
      out[4] = 8;  // CAN_ERR_DLC
      for (std::size_t i = 0; i < 8; ++i) out[8 + i] = record.frame.data[i];
      return out;
    case candump_frame_type::fd:
      header(record.can_id, 72);
      out[4] = static_cast<std::uint8_t>(record.length);
      out[5] = static_cast<std::uint8_t>(canfd_fdf | (record.flags & 0x03U));  // BRS, ESI
      for (std::size_t i = 0; i < record.data.size() && i < 64; ++i) out[8 + i] = record.data[i];
      return out;
    case candump_frame_type::xl:
      return out;
  }
  return out;
}

}  // namespace trionet::host

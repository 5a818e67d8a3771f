// candump text: see can_candump.hpp.
#include "trionet/host/candump.hpp"

#include <cstdio>

namespace trionet::host {
namespace {

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_blank(text.back())) text.remove_suffix(1);
  return text;
}

// "(seconds.micros)": 1..20 digits, '.', 1..6 digits (scaled to microseconds).
bool parse_timestamp(std::string_view text, candump_record& out) {
  if (text.size() < 4 || text.front() != '(' || text.back() != ')') return false;
  text = text.substr(1, text.size() - 2);
  const std::size_t dot = text.find('.');
  if (dot == std::string_view::npos || dot == 0 || dot > 19) return false;
  const std::string_view whole = text.substr(0, dot);
  const std::string_view fraction = text.substr(dot + 1);
  if (fraction.empty() || fraction.size() > 6) return false;
  std::uint64_t seconds = 0;
  for (char c : whole) {
    if (c < '0' || c > '9') return false;
    seconds = seconds * 10U + static_cast<std::uint64_t>(c - '0');
  }
  std::uint32_t micros = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    std::uint32_t digit = 0;
    if (i < fraction.size()) {
      const char c = fraction[i];
      if (c < '0' || c > '9') return false;
      digit = static_cast<std::uint32_t>(c - '0');
    }
    micros = micros * 10U + digit;
  }
  out.has_timestamp = true;
  out.seconds = seconds;
  out.microseconds = micros;
  return true;
}

candump_status parse_frame(std::string_view text, can::frame& out) {
  const std::size_t hash = text.find('#');
  if (hash == std::string_view::npos) {
    for (char c : text) {
      if (hex_value(c) < 0) return candump_status::identifier;
    }
    return candump_status::separator;
  }
  const std::string_view id_text = text.substr(0, hash);
  if (id_text.size() != 3 && id_text.size() != 8) return candump_status::identifier;
  std::uint32_t id = 0;
  for (char c : id_text) {
    const int v = hex_value(c);
    if (v < 0) return candump_status::identifier;
    id = id << 4U | static_cast<std::uint32_t>(v);
  }
  const bool extended = id_text.size() == 8;
  if (extended ? id > can::frame::extended_mask : id > can::frame::standard_mask) {
    return candump_status::identifier;
  }
  out.id = extended ? (id | can::frame::extended_flag) : id;
  std::string_view data = text.substr(hash + 1);
  if (!data.empty() && data.front() == '#') return candump_status::separator;  // CAN FD
  if (!data.empty() && (data.front() == 'R' || data.front() == 'r')) {
    out.id |= can::frame::remote_flag;
    out.dlc = 0;
    if (data.size() == 1) return candump_status::ok;
    if (data.size() == 2 && data[1] >= '0' && data[1] <= '8') {
      out.dlc = static_cast<std::uint8_t>(data[1] - '0');
      return candump_status::ok;
    }
    return candump_status::data;
  }
  std::uint8_t count = 0;
  while (!data.empty()) {
    if (data.front() == '.' && count > 0 && data.size() > 1) data.remove_prefix(1);
    if (data.size() < 2 || count == 8) return candump_status::data;
    const int high = hex_value(data[0]);
    const int low = hex_value(data[1]);
    if (high < 0 || low < 0) return candump_status::data;
    out.data[count++] = static_cast<std::uint8_t>(high << 4 | low);
    data.remove_prefix(2);
  }
  out.dlc = count;
  return candump_status::ok;
}

}  // namespace

candump_result parse_candump_line(std::string_view line) {
  candump_result result;
  std::string_view text = trim(line);
  if (text.empty()) {
    result.status = candump_status::empty;
    return result;
  }
  if (text.front() == '(') {
    const std::size_t close = text.find(')');
    if (close == std::string_view::npos || !parse_timestamp(text.substr(0, close + 1), result.record)) {
      result.status = candump_status::timestamp;
      return result;
    }
    text = text.substr(close + 1);
    if (text.empty() || !is_blank(text.front())) {
      result.status = candump_status::interface_name;
      return result;
    }
    text = trim(text);
    std::size_t end = 0;
    while (end < text.size() && !is_blank(text[end])) ++end;
    if (end == 0 || end == text.size()) {
      result.status = candump_status::interface_name;
      return result;
    }
    result.record.interface_name = std::string(text.substr(0, end));
    text = trim(text.substr(end));
  }
  std::size_t end = 0;
  while (end < text.size() && !is_blank(text[end])) ++end;
  // The log form may end with a direction flag, R (received) or T (sent): `candump -L -x`, asc2log.
  const std::string_view rest = trim(text.substr(end));
  if (result.record.has_timestamp && (rest == "R" || rest == "T")) {
    result.status = parse_frame(text.substr(0, end), result.record.frame);
    return result;
  }
  if (end != text.size()) {
    result.status = candump_status::trailing;
    const candump_status frame_error = parse_frame(text.substr(0, end), result.record.frame);
    if (frame_error != candump_status::ok) result.status = frame_error;
    return result;
  }
  result.status = parse_frame(text, result.record.frame);
  return result;
}

std::string format_candump_frame(const can::frame& frame) {
  char text[40];
  int length = frame.extended() ? std::snprintf(text, sizeof text, "%08X#", frame.identifier())
                                : std::snprintf(text, sizeof text, "%03X#", frame.identifier());
  std::string out(text, static_cast<std::size_t>(length));
  if (frame.remote()) {
    out += 'R';
    if (frame.dlc != 0) out += static_cast<char>('0' + (frame.dlc > 8 ? 8 : frame.dlc));
    return out;
  }
  static constexpr char digits[] = "0123456789ABCDEF";
  for (std::uint8_t i = 0; i < frame.data_length(); ++i) {
    out += digits[frame.data[i] >> 4U];
    out += digits[frame.data[i] & 0x0FU];
  }
  return out;
}

std::string format_candump_line(const candump_record& record) {
  if (!record.has_timestamp) return format_candump_frame(record.frame);
  char stamp[48];
  const int length =
      std::snprintf(stamp, sizeof stamp, "(%010llu.%06u) ", static_cast<unsigned long long>(record.seconds),
                    record.microseconds % 1000000U);
  std::string out(stamp, static_cast<std::size_t>(length));
  out += record.interface_name.empty() ? std::string("can0") : record.interface_name;
  out += ' ';
  out += format_candump_frame(record.frame);
  return out;
}

const char* to_string(candump_status status) {
  switch (status) {
    case candump_status::ok:
      return "ok";
    case candump_status::empty:
      return "empty";
    case candump_status::timestamp:
      return "timestamp";
    case candump_status::interface_name:
      return "interface_name";
    case candump_status::identifier:
      return "identifier";
    case candump_status::separator:
      return "separator";
    case candump_status::data:
      return "data";
    case candump_status::trailing:
      return "trailing";
  }
  return "unknown";
}

}  // namespace trionet::host

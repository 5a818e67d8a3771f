// candump text: see trionet/host/candump.hpp.
#include "trionet/host/candump.hpp"

#include <cstdio>

#include "trionet/host/text.hpp"

namespace trionet::host {
namespace {

constexpr std::uint32_t remote_flag = can::frame::remote_flag;
constexpr std::uint32_t extended_flag = can::frame::extended_flag;
constexpr std::uint8_t canxl_xlf = 0x80;  // the CAN XL flag can-utils forces into an XL frame's flags

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_blank(text.back())) text.remove_suffix(1);
  return text;
}

// Words of a line, left to right; `rest` is what follows the last word taken.
class words {
 public:
  explicit words(std::string_view text) : text_(text) {}
  std::string_view next() {
    std::size_t i = 0;
    while (i < text_.size() && is_blank(text_[i])) ++i;
    std::size_t end = i;
    while (end < text_.size() && !is_blank(text_[end])) ++end;
    const std::string_view word = text_.substr(i, end - i);
    text_.remove_prefix(end);
    return word;
  }
  std::string_view rest() const { return trim(text_); }

 private:
  std::string_view text_;
};

bool all_digits(std::string_view text) {
  for (char c : text) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

// "SECONDS.FRACTION" (candump -t a, -t d, -t z, the log form) or "YYYY-MM-DD HH:MM:SS.FRACTION" (-t A).
bool parse_timestamp(std::string_view text, candump_record& out) {
  const std::size_t dot = text.rfind('.');
  if (dot == std::string_view::npos) return false;
  const std::string_view whole = text.substr(0, dot);
  const std::string_view fraction = text.substr(dot + 1);
  if (fraction.empty() || fraction.size() > 9 || !all_digits(fraction)) return false;
  if (whole.size() == 19 && whole[4] == '-' && whole[7] == '-' && whole[10] == ' ' && whole[13] == ':' &&
      whole[16] == ':') {
    for (std::size_t i : {0U, 1U, 2U, 3U, 5U, 6U, 8U, 9U, 11U, 12U, 14U, 15U, 17U, 18U}) {
      if (whole[i] < '0' || whole[i] > '9') return false;
    }
    out.timestamp.assign(text.data(), text.size());
    out.fraction_digits = static_cast<std::uint8_t>(fraction.size());
    return true;  // a local date and time: kept as text
  }
  if (whole.empty() || whole.size() > 20 || !all_digits(whole)) return false;
  std::uint64_t seconds = 0;
  for (char c : whole) {
    const auto digit = static_cast<std::uint64_t>(c - '0');
    if (seconds > (UINT64_MAX - digit) / 10U) return false;
    seconds = seconds * 10U + digit;
  }
  std::uint32_t nanoseconds = 0;
  for (std::size_t i = 0; i < 9; ++i) {
    nanoseconds = nanoseconds * 10U + (i < fraction.size() ? static_cast<std::uint32_t>(fraction[i] - '0') : 0U);
  }
  // The time as 64-bit nanoseconds (captures, the live tools' events): at most 18446744073.709551615 s.
  constexpr std::uint64_t billion = 1000000000U;
  if (seconds > UINT64_MAX / billion || seconds * billion > UINT64_MAX - nanoseconds) return false;
  out.timestamp.assign(text.data(), text.size());
  out.has_timestamp = true;
  out.seconds = seconds;
  out.nanoseconds = nanoseconds;
  out.fraction_digits = static_cast<std::uint8_t>(fraction.size());
  return true;
}

void clear_frame(candump_record& out) {
  out.type = candump_frame_type::classic;
  out.can_id = 0;
  out.length = 0;
  out.len8_dlc = 0;
  out.flags = 0;
  out.sdt = 0;
  out.af = 0;
  out.frame = can::frame{};
  out.data.clear();
}

// The frame view of the fields parse_candump_frame filled in.
void fill_frame(candump_record& out) {
  can::frame& f = out.frame;
  if (out.type == candump_frame_type::error) {
    f.id = out.can_id & can::frame::extended_mask;
  } else if (out.type == candump_frame_type::classic) {
    f.id = out.can_id & (extended_flag | remote_flag | ((out.can_id & extended_flag) != 0 ? can::frame::extended_mask
                                                                                          : 0xFFFFFU));
  } else {
    f.id = out.can_id;
  }
  const std::uint16_t length = out.length > 8 ? std::uint16_t{8} : out.length;
  f.dlc = out.len8_dlc != 0 ? out.len8_dlc : static_cast<std::uint8_t>(length);
}

// One "[N]", "{N}", "[NN]" or "[NNNN]" of the screen form: sets type, length and len8_dlc.
bool parse_screen_length(std::string_view word, candump_record& out) {
  if (word.size() < 3) return false;
  const std::string_view digits = word.substr(1, word.size() - 2);
  if (word.front() == '{' && word.back() == '}') {  // candump -8: the raw DLC of a classic frame
    const int dlc = digits.size() == 1 ? hex_digit(digits[0]) : -1;
    if (dlc < 0) return false;
    out.length = static_cast<std::uint16_t>(dlc > 8 ? 8 : dlc);
    out.len8_dlc = static_cast<std::uint8_t>(dlc > 8 ? dlc : 0);
    return true;
  }
  if (word.front() != '[' || word.back() != ']' || !all_digits(digits)) return false;
  unsigned value = 0;
  for (char c : digits) value = value * 10U + static_cast<unsigned>(c - '0');
  if (digits.size() == 1 && value <= 8) {
    out.length = static_cast<std::uint16_t>(value);
  } else if (digits.size() == 2 && value <= 64) {
    out.type = candump_frame_type::fd;
    out.length = static_cast<std::uint16_t>(value);
  } else if (digits.size() == 4 && value <= 2048) {
    out.type = candump_frame_type::xl;
    out.length = static_cast<std::uint16_t>(value);
  } else {
    return false;
  }
  return true;
}

// One data byte of the screen form: two hex digits, or eight binary digits (candump -b).
bool parse_screen_byte(std::string_view word, std::uint8_t& out) {
  if (word.size() == 2 && hex_digit(word[0]) >= 0 && hex_digit(word[1]) >= 0) {
    out = static_cast<std::uint8_t>(hex_digit(word[0]) << 4 | hex_digit(word[1]));
    return true;
  }
  if (word.size() != 8) return false;
  unsigned value = 0;
  for (char c : word) {
    if (c != '0' && c != '1') return false;
    value = value << 1U | static_cast<unsigned>(c - '0');
  }
  out = static_cast<std::uint8_t>(value);
  return true;
}

// "(VV|FF:SS:AAAAAAAA)": the CAN XL header of the screen form.
bool parse_screen_xl_header(std::string_view word, candump_record& out) {
  if (word.size() != 19 || word.front() != '(' || word.back() != ')' || word[3] != '|' || word[6] != ':' ||
      word[9] != ':') {
    return false;
  }
  std::uint32_t vcid = 0;
  std::uint32_t flags = 0;
  std::uint32_t sdt = 0;
  std::uint32_t af = 0;
  if (!parse_hex_number(word.substr(1, 2), 2, vcid) || !parse_hex_number(word.substr(4, 2), 2, flags) ||
      !parse_hex_number(word.substr(7, 2), 2, sdt) || !parse_hex_number(word.substr(10, 8), 8, af)) {
    return false;
  }
  out.can_id = vcid << 16U | (out.can_id & 0x7FFU);
  out.flags = static_cast<std::uint8_t>(flags);
  out.sdt = static_cast<std::uint8_t>(sdt);
  out.af = af;
  return true;
}

// The screen form after the interface name: [RX|TX F F] ID LENGTH [XL header] DATA... | remote request,
// then nothing, ERRORFRAME, "..." (a long CAN XL frame) or the ASCII column.
candump_status parse_screen(words& w, std::string_view first, candump_record& out) {
  out.form = candump_form::screen;
  std::string_view word = first;
  if (word == "RX" || word == "TX") {  // candump -x: direction and two flag columns
    out.direction = word[0] == 'R' ? 'R' : 'T';
    const std::string_view brs = w.next();
    const std::string_view esi = w.next();
    if (brs.size() != 1 || esi.size() != 1) return candump_status::identifier;
    out.flags = static_cast<std::uint8_t>((brs == "B" ? 1U : 0U) | (esi == "E" ? 2U : 0U));
    word = w.next();
  }
  std::uint32_t id = 0;
  if ((word.size() != 3 && word.size() != 8) || !parse_hex_number(word, 8, id)) return candump_status::identifier;
  out.can_id = id;
  if (word.size() == 8) {
    if ((id & can_error_flag) != 0) {
      out.type = candump_frame_type::error;
    } else {
      out.can_id |= extended_flag;
    }
  }
  const candump_frame_type id_type = out.type;
  if (!parse_screen_length(w.next(), out)) return candump_status::length;
  if (out.type != candump_frame_type::xl && out.type != candump_frame_type::fd) out.flags = 0;
  if (id_type == candump_frame_type::error) {
    if (out.type == candump_frame_type::xl) return candump_status::length;
    out.type = candump_frame_type::error;  // "20000080  [00]  ...  ERRORFRAME": CAN FD length, error flag
  }
  if (out.type == candump_frame_type::xl) {
    if (word.size() != 3) return candump_status::identifier;
    if (!parse_screen_xl_header(w.next(), out)) return candump_status::xl_header;
  }
  const std::size_t shown = out.length > 64 ? 64 : out.length;
  std::string_view rest = w.rest();
  if (out.type == candump_frame_type::classic && rest.substr(0, 6) == "remote") {
    words request(rest);
    if (request.next() != "remote" || request.next() != "request" || !request.rest().empty()) {
      return candump_status::trailing;
    }
    out.can_id |= remote_flag;
    fill_frame(out);
    return candump_status::ok;
  }
  for (std::size_t i = 0; i < shown; ++i) {
    std::uint8_t byte = 0;
    if (!parse_screen_byte(w.next(), byte)) return candump_status::data;
    if (i < 8) out.frame.data[i] = byte;
    out.data.push_back(byte);
  }
  if (out.length > shown && w.next() != "...") return candump_status::data;
  rest = w.rest();
  fill_frame(out);
  if (rest.empty()) return candump_status::ok;
  if (out.type == candump_frame_type::error && rest == "ERRORFRAME") return candump_status::ok;
  if (out.length <= 8 && rest.size() >= 2 && ((rest.front() == '\'' && rest.back() == '\'') ||
                                              (rest.front() == '`' && rest.back() == '`'))) {
    return candump_status::ok;  // candump -a: the data as ASCII
  }
  return candump_status::trailing;
}

}  // namespace

candump_status parse_candump_frame(std::string_view text, candump_record& out) {
  // The grammar of can-utils' parse_canframe (lib.c), read character by character; a position past the
  // end reads as the string's terminating NUL.
  // A NUL inside the word is a character like any other that is not the grammar's (can-utils' C strings
  // would end there, and read the frame before it).
  const std::string_view cs = text;
  const auto at = [&cs](std::size_t i) { return i < cs.size() ? cs[i] : '\0'; };
  const auto nibble = [](char c) { return hex_digit(c) < 0 ? 16U : static_cast<unsigned>(hex_digit(c)); };
  clear_frame(out);
  if (cs.size() < 4) return candump_status::identifier;
  std::size_t digits = 0;
  if (at(3) == '#') {
    digits = 3;
  } else if (at(5) == '#') {
    digits = 5;
  } else if (at(8) == '#') {
    digits = 8;
  } else {
    return candump_status::identifier;
  }
  std::uint32_t id = 0;
  if (!parse_hex_number(cs.substr(0, digits), 8, id)) return candump_status::identifier;
  if (digits == 3) {
    out.can_id = id;
  } else if (digits == 5) {  // CAN XL: two digits of VCID, then the priority (11 bits kept)
    out.can_id = (id << 4U & 0xFF0000U) | (id & 0x7FFU);
  } else {
    out.can_id = (id & can_error_flag) != 0 ? id : id | extended_flag;
  }
  std::size_t idx = digits + 1;
  // Five digits are a CAN XL frame's VCID and priority: its header must follow (no remote or CAN FD form).
  if (digits == 5 && (at(idx) == 'R' || at(idx) == 'r' || at(idx) == '#')) return candump_status::identifier;
  if (digits == 5 && (at(idx + 2) != ':' || at(idx + 5) != ':' || at(idx + 14) != '#')) {
    return candump_status::xl_header;
  }

  if (at(idx) == 'R' || at(idx) == 'r') {  // remote frame: R, an optional length, an optional _D
    out.can_id |= remote_flag;
    ++idx;
    if (at(idx) != '\0') {
      const unsigned length = nibble(at(idx++));
      if (length > 8) return candump_status::trailing;  // LEN is 0..8: what follows R is not one
      out.length = static_cast<std::uint16_t>(length);
      if (length == 8 && at(idx) == '_') {
        const unsigned dlc = nibble(at(++idx));
        if (dlc > 8 && dlc <= 15) out.len8_dlc = static_cast<std::uint8_t>(dlc);
        ++idx;
      }
    }
    // can-utils stops reading here and ignores the rest of the word; a frame with more after it is refused.
    if (idx < cs.size()) return candump_status::trailing;
    if ((out.can_id & can_error_flag) != 0 && digits == 8) out.type = candump_frame_type::error;
    fill_frame(out);
    return candump_status::ok;
  }

  std::size_t max_length = 8;
  if (at(idx) == '#') {  // CAN FD: ## and one flags digit
    const unsigned flags = nibble(at(idx + 1));
    if (flags > 15) return candump_status::fd_flags;
    out.type = candump_frame_type::fd;
    out.flags = static_cast<std::uint8_t>(flags);
    max_length = 64;
    idx += 2;
  } else if (at(idx + 14) == '#') {  // CAN XL: FF:SS:AAAAAAAA#
    if (at(idx + 2) != ':' || at(idx + 5) != ':') return candump_status::xl_header;
    std::uint32_t flags = 0;
    std::uint32_t sdt = 0;
    std::uint32_t af = 0;
    if (!parse_hex_number(cs.substr(idx, 2), 2, flags) || !parse_hex_number(cs.substr(idx + 3, 2), 2, sdt) ||
        !parse_hex_number(cs.substr(idx + 6, 8), 8, af)) {
      return candump_status::xl_header;
    }
    out.type = candump_frame_type::xl;
    out.flags = static_cast<std::uint8_t>(flags | canxl_xlf);
    out.sdt = static_cast<std::uint8_t>(sdt);
    out.af = af;
    max_length = 2048;
    idx += 15;
  }

  std::size_t length = 0;
  for (; length < max_length; ++length) {
    if (at(idx) == '.') ++idx;  // one optional separator before each byte
    if (idx >= cs.size()) break;
    const unsigned high = nibble(at(idx++));
    if (high > 15) return candump_status::data;
    const unsigned low = nibble(at(idx++));
    if (low > 15) return candump_status::data;
    const auto byte = static_cast<std::uint8_t>(high << 4U | low);
    if (length < 8) out.frame.data[length] = byte;
    out.data.push_back(byte);
  }
  out.length = static_cast<std::uint16_t>(length);
  if (max_length == 8 && length == 8 && at(idx) == '_') {
    const unsigned dlc = nibble(at(++idx));
    if (dlc > 8 && dlc <= 15) out.len8_dlc = static_cast<std::uint8_t>(dlc);
    ++idx;
  }
  // More data than the frame holds (028#0100000000020D7A0102), or anything else after it: can-utils reads
  // the frame and ignores the rest of the word; here that is a wrong line, not a plausible frame.
  if (idx < cs.size()) return candump_status::trailing;
  // The error flag makes an error frame of a classic or CAN FD frame (`20000080##0`): can-utils prints both
  // as ERRORFRAME.
  if (out.type != candump_frame_type::xl && (out.can_id & can_error_flag) != 0 && digits == 8) {
    out.type = candump_frame_type::error;
  }
  fill_frame(out);
  return candump_status::ok;
}

candump_status parse_candump_line(std::string_view line, candump_record& out) {
  out.form = candump_form::compact;
  out.timestamp.clear();
  out.has_timestamp = false;
  out.seconds = 0;
  out.nanoseconds = 0;
  out.fraction_digits = 0;
  out.interface_name.clear();
  out.direction = 0;
  clear_frame(out);
  if (line.size() > candump_max_line_length) return candump_status::too_long;
  std::string_view text = trim(line);
  if (text.empty()) return candump_status::empty;

  bool stamped = false;
  if (text.front() == '(') {
    const std::size_t close = text.find(')');
    if (close == std::string_view::npos || !parse_timestamp(text.substr(1, close - 1), out)) {
      return candump_status::timestamp;
    }
    stamped = true;
    // can-utils reads a log line with sscanf("(%llu.%llu) %s %s"): the blank after ')' may be absent.
    text = text.substr(close + 1);
    if (trim(text).empty()) return candump_status::interface_name;
  }
  words w(text);
  const std::string_view first = w.next();
  if (!stamped && first.find('#') != std::string_view::npos) {
    const candump_status status = parse_candump_frame(first, out);
    if (status != candump_status::ok) return status;
    return w.rest().empty() ? candump_status::ok : candump_status::trailing;
  }
  if (first.empty()) return candump_status::interface_name;
  out.interface_name.assign(first.data(), first.size());
  const std::string_view second = w.next();
  if (second.empty()) return candump_status::interface_name;
  if (second.find('#') == std::string_view::npos) return parse_screen(w, second, out);

  out.form = stamped ? candump_form::log : candump_form::compact;
  if (!stamped) return candump_status::timestamp;  // "IFACE FRAME" is the log form without its timestamp
  const candump_status status = parse_candump_frame(second, out);
  if (status != candump_status::ok) return status;
  const std::string_view direction = w.next();
  if (direction.empty()) return candump_status::ok;
  if ((direction != "R" && direction != "T") || !w.rest().empty()) return candump_status::trailing;
  out.direction = direction[0];
  return candump_status::ok;
}

candump_result parse_candump_line(std::string_view line) {
  candump_result result;
  result.status = parse_candump_line(line, result.record);
  return result;
}

std::string format_candump_frame(const can::frame& frame) {
  static constexpr char digits[] = "0123456789ABCDEF";
  char text[48];
  int length = frame.extended() ? std::snprintf(text, sizeof text, "%08X#", frame.identifier())
                                : std::snprintf(text, sizeof text, "%03X#", frame.identifier());
  std::string out(text, static_cast<std::size_t>(length));
  const bool raw_dlc = frame.dlc > 8 && frame.dlc <= 15;
  if (frame.remote()) {
    out += 'R';
    if (frame.dlc != 0) out += raw_dlc ? '8' : digits[frame.dlc];
  } else {
    for (std::uint8_t i = 0; i < frame.data_length(); ++i) {
      out += digits[frame.data[i] >> 4U];
      out += digits[frame.data[i] & 0x0FU];
    }
  }
  if (raw_dlc) {
    out += '_';
    out += digits[frame.dlc];
  }
  return out;
}

std::string format_candump_line(const candump_record& record) {
  if (!record.has_timestamp) return format_candump_frame(record.frame);
  char stamp[48];
  const int length = record.fraction_digits == 9
                         ? std::snprintf(stamp, sizeof stamp, "(%010llu.%09u) ",
                                         static_cast<unsigned long long>(record.seconds),
                                         record.nanoseconds % 1000000000U)
                         : std::snprintf(stamp, sizeof stamp, "(%010llu.%06u) ",
                                         static_cast<unsigned long long>(record.seconds),
                                         record.nanoseconds % 1000000000U / 1000U);
  std::string out(stamp, static_cast<std::size_t>(length));
  out += record.interface_name.empty() ? std::string("can0") : record.interface_name;
  out += ' ';
  out += format_candump_frame(record.frame);
  if (record.direction == 'R' || record.direction == 'T') {
    out += ' ';
    out += record.direction;
  }
  return out;
}

}  // namespace trionet::host

#include "learn/ring_capture.hpp"

#include <algorithm>
#include <charconv>
#include <cstdlib>

#include "trionet/ring/bytes.hpp"
#include "trionet/ring/encode.hpp"
#include "trionet/q32.hpp"

namespace trionet::learn {

frame_extraction variable_transfers(byte_view stream) {
  frame_extraction out;
  const std::size_t n = stream.size();
  std::size_t i = 0;
  while (i < n) {
    const std::uint8_t header = stream[i];
    const std::uint8_t hops = ring::hops_of(header);
    bool whole = ring::classify(header) == ring::byte_class::header && ring::type_of(header) == 2 &&
                 hops != 0 && n - i >= 16 && stream[i + 15] == ring::make_end_of_message(hops);
    for (std::size_t k = 1; whole && k < 15; ++k) whole = ring::is_data(stream[i + k]);
    if (!whole) {
      ++out.skipped_bytes;
      ++i;
      continue;
    }
    variable_frame frame{};
    std::copy(stream.begin() + i + 1, stream.begin() + i + 15, frame.begin());
    out.frames.push_back(frame);
    i += 16;
  }
  return out;
}

namespace {

bool blank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

}  // namespace

sent_list_result parse_sent_list(std::string_view text) {
  sent_list_result result;
  std::size_t line_number = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string line(text.substr(0, end));
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    ++line_number;
    const std::size_t comment = line.find('#');
    if (comment != std::string::npos) line.resize(comment);
    std::size_t at = 0;
    const auto skip_blanks = [&] {
      while (at < line.size() && blank(line[at])) ++at;
    };
    const auto word = [&] {
      skip_blanks();
      const std::size_t start = at;
      while (at < line.size() && !blank(line[at])) ++at;
      return line.substr(start, at - start);
    };
    const std::string vr_text = word();
    if (vr_text.empty()) continue;
    const std::string value_text = word();
    skip_blanks();
    const auto fail = [&](sent_list_status status) {
      result.status = status;
      result.line = line_number;
      result.sent.clear();
      return result;
    };
    if (value_text.empty() || at != line.size()) return fail(sent_list_status::syntax);
    unsigned long vr = 0;
    const auto parsed_vr = std::from_chars(vr_text.data(), vr_text.data() + vr_text.size(), vr, 10);
    if (parsed_vr.ptr != vr_text.data() + vr_text.size() || vr_text[0] == '-' || vr_text[0] == '+')
      return fail(sent_list_status::syntax);
    if (parsed_vr.ec == std::errc::result_out_of_range || vr > ring::max_vr)
      return fail(sent_list_status::vr_out_of_range);
    if (parsed_vr.ec != std::errc()) return fail(sent_list_status::syntax);
    // A real number as the CLI's --value takes it: strtod over the whole word, finite.
    char* parsed_end = nullptr;
    const double value = std::strtod(value_text.c_str(), &parsed_end);
    if (parsed_end != value_text.c_str() + value_text.size() ||
        value_text.find_first_of("xXnN") != std::string::npos)
      return fail(sent_list_status::syntax);
    const trionet::q32_result q = trionet::q32_from_double(value);
    if (!q) return fail(sent_list_status::value_out_of_range);
    result.sent.push_back(sent_variable{static_cast<std::uint16_t>(vr), q.raw});
  }
  return result;
}

std::vector<variable_frame> encode_capture(const std::vector<sent_variable>& sent,
                                           const ring::crc16_parameters& crc,
                                           const ring::variable_layout_parameters& layout) {
  const ring::crc16_runtime runtime(crc);
  std::vector<variable_frame> frames;
  frames.reserve(sent.size());
  ring::with_variable_layout(layout, [&](auto policy) {
    using layout_policy = decltype(policy);
    for (const sent_variable& s : sent) {
      std::uint8_t bytes[ring::framing_length + ring::variable_data_length];
      const ring::encode_result encoded =
          ring::encode_variable<ring::crc16_runtime, layout_policy>(bytes, 1, s.vr, s.value, runtime);
      variable_frame frame{};
      if (encoded) std::copy(bytes + 1, bytes + 15, frame.begin());
      frames.push_back(frame);
    }
  });
  return frames;
}

}  // namespace trionet::learn

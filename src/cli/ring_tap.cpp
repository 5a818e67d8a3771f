// One direction of a ring link as this host sees it: see ring_live.hpp.
#include "ring_live.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/node.hpp"

namespace trionet::cli {

ring_tap::ring_tap(live::capture_file* capture, const std::string& link_name) : capture_(capture) {
  if (capture_ != nullptr) interface_ = capture_->add(link_name, host::capture_network::ring);
}

void ring_tap::push(byte_view bytes, std::uint64_t time_ns, const sink& out) {
  for (std::uint8_t byte : bytes) push(byte, time_ns, out);
}

void ring_tap::push(std::uint8_t byte, std::uint64_t time_ns, const sink& out) {
  ++bytes_;
  if (capture_ != nullptr) {
    records_.push(byte, time_ns, [&](byte_view record, std::uint64_t t) { capture_->write(interface_, t, record); });
  }
  const std::uint8_t before = open_hops_;  // the message an error is about (0: none was open)
  if (!ring::is_data(byte)) open_hops_ = ring::type_of(byte) != 0 ? ring::hops_of(byte) : 0;  // a header opens
  const ring::decode_result r = decoder_.push(byte);
  if (r.status == ring::decode_status::incomplete) return;
  last_hops_ = r.status == ring::decode_status::frame_error ? before : r.msg.hops;
  report(r, time_ns, out);
}

void ring_tap::idle(std::uint64_t time_ns, const sink& out) {
  if (capture_ != nullptr) {
    records_.flush([&](byte_view record, std::uint64_t t) { capture_->write(interface_, t, record); });
  }
  if (!decoder_.open()) return;
  last_hops_ = open_hops_;
  const ring::decode_result r = decoder_.line_idle();
  open_hops_ = 0;
  if (r.status != ring::decode_status::incomplete) report(r, time_ns, out);
}

void ring_tap::report(const ring::decode_result& r, std::uint64_t time_ns, const sink& out) {
  switch (r.status) {
    case ring::decode_status::ok:
      ++messages_;
      ++by_type_[static_cast<std::size_t>(r.msg.type) < 5 ? static_cast<std::size_t>(r.msg.type) : 0];
      break;
    case ring::decode_status::crc_error:
      ++crc_errors_;
      break;
    case ring::decode_status::no_room:
      ++no_room_;
      break;
    case ring::decode_status::frame_error:
    case ring::decode_status::incomplete:
      ++frame_errors_[ring::to_string(r.error)];
      break;
  }
  out(r, time_ns);
}

void ring_tap::add_counters(event& e, const std::string& prefix) const {
  std::uint64_t frame_errors = 0;
  for (const auto& entry : frame_errors_) frame_errors += entry.second;
  e.number(prefix + "bytes", bytes_);
  e.number(prefix + "messages", messages_);
  e.number(prefix + "char", by_type_[static_cast<int>(ring::message_type::character)]);
  e.number(prefix + "var", by_type_[static_cast<int>(ring::message_type::variable)]);
  e.number(prefix + "offset",
           by_type_[static_cast<int>(ring::message_type::keypad_offset)]);
  e.number(prefix + "mode", by_type_[static_cast<int>(ring::message_type::keypad_mode)]);
  e.number(prefix + "crc_errors", crc_errors_);
  e.number(prefix + "frame_errors", frame_errors);
  for (const auto& entry : frame_errors_) {
    e.number(prefix + entry.first, entry.second);
  }
}

void ring_tap::counters(std::string& out, std::uint64_t time_ns) const {
  event e(out, "counters");
  e.time(time_ns);
  add_counters(e, "");
  std::uint64_t frame_errors = 0;
  for (const auto& entry : frame_errors_) frame_errors += entry.second;
  const auto bit = [](bool raised, ring::netstat_bit b) { return raised ? static_cast<unsigned>(b) : 0U; };
  e.number("netstat", bit(crc_errors_ != 0, ring::netstat_rx_crc_error) |
                          bit(frame_errors != 0, ring::netstat_rx_frame_error));
}

}  // namespace trionet::cli

// Writes the test captures for the Wireshark dissectors, each with the library's own view of every record:
//
//   ring.pcapng      three links of a ring: every message type, every frame error reason, a CRC error
//   example2.pcapng  the manual's example 2 on the simulated ring, one interface per link (125 kbit/s)
//   can.pcapng       two CAN buses: VR frames of a 5-node exchange between several pairs, and non-VR frames
//   genius.pcapng    a Genius line: broadcast, directed, blocks, CRC errors, framing errors, stray characters
//   random.pcapng    a ring link, a Genius line (its name not UTF-8) and a CAN bus carrying random messages with
//                    random faults
//
// and NAME.jsonl beside each: one JSON object per record, in file order, read back from the capture with
// pcapng_reader and printed by the record view (trionet/host/capture_view.hpp); can_3_nodes.jsonl is the view
// of can.pcapng for an exchange of 3 nodes. scripts/wireshark-compare
// runs tshark with the Lua dissectors on the capture and checks that it shows exactly these fields.
//
//   trionet_wireshark_captures OUTPUT_DIRECTORY   (created if missing)
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "embedded_files.hpp"
#include "ring_network.hpp"
#include "trionet/can.hpp"
#include "trionet/genius.hpp"
#include "trionet/host/capture.hpp"
#include "trionet/host/capture_view.hpp"
#include "trionet/host/pcapng.hpp"
#include "trionet/ring.hpp"

namespace {

using namespace trionet;
using namespace trionet::host;
using bytes = std::vector<std::uint8_t>;

constexpr std::uint64_t ring_byte_ns = 80000;        // 10 bits at 125 kbit/s
constexpr std::uint64_t genius_character_ns = 71615;  // 11 bits at 153.6 kbaud, rounded down
constexpr std::uint64_t epoch = 1700000000ull * 1000000000ull;

[[noreturn]] void die(const std::string& what) {
  std::fprintf(stderr, "trionet_wireshark_captures: %s\n", what.c_str());
  std::exit(1);
}

void check(pcapng_write_status status) {
  if (status != pcapng_write_status::ok) die(std::string("write failed: ") + to_string(status));
}

// Reads `capture` back and writes the record view of each record as a line of `jsonl`; returns the count.
std::size_t write_view(const std::string& capture, const std::string& jsonl, const capture_view_options& options = {}) {
  std::ifstream in(capture, std::ios::binary);
  std::ofstream out(jsonl);
  pcapng_reader reader(in);
  std::size_t records = 0;
  for (;;) {
    const pcapng_read_result r = reader.next();
    if (r.status == pcapng_read_status::end_of_file) break;
    if (!r) die(capture + ": " + to_string(r.status));
    out << fields_json(record_fields(reader, r.record, options)) << '\n';
    ++records;
  }
  if (!out) die("cannot write " + jsonl);
  return records;
}

// ---------------------------------------------------------------------------------------------------------
// ring

// One link: bytes with their byte-times, cut into records (and at an idle line, as 1.10 says a receiver does)
// by the host library's recorder, the one the tool's `ring simulate --pcap` uses.
class ring_link {
 public:
  ring_link(pcapng_writer& writer, const std::string& name)
      : recorder_(writer, add(writer, name), 1e9 * 10 / ring_byte_ns, 10, epoch) {}

  void send(const bytes& b) {
    for (std::uint8_t byte : b) byte_at(now_++, byte);
  }
  void idle(std::uint64_t byte_times) {
    now_ += byte_times;
    flush();
  }
  void byte_at(std::uint64_t time, std::uint8_t byte) { recorder_.byte_at(time, byte); }
  void flush() {
    recorder_.flush();
    check(recorder_.status());
  }

 private:
  static std::uint32_t add(pcapng_writer& writer, const std::string& name) {
    const pcapng_interface_result added = writer.add_interface(name, capture_network::ring);
    if (!added) die("add_interface");
    return added.id;
  }

  ring_link_recorder recorder_;
  std::uint64_t now_ = 0;
};

bytes encoded(const ring::message& m) {
  std::uint8_t buffer[300];
  const ring::encode_result r = ring::encode(byte_buffer(buffer, sizeof buffer), m);
  if (!r) die("ring encode");
  return bytes(buffer, buffer + r.length);
}
bytes text_message(std::uint8_t hops, const std::string& text) {
  return encoded(ring::message::characters(
      hops, byte_view(reinterpret_cast<const std::uint8_t*>(text.data()), text.size())));
}
bytes variable(std::uint8_t hops, std::uint16_t vr, double value) {
  return encoded(ring::message::variable(hops, vr, trionet::q32_from_double(value).raw));
}

void write_ring(const std::string& dir) {
  std::ofstream file(dir + "/ring.pcapng", std::ios::binary);
  pcapng_writer writer(file);
  ring_link link0(writer, "link 0: MC1 -> MC2");
  ring_link link1(writer, "link 1: MC2 -> keypad");
  ring_link link2(writer, "link 2: keypad -> MC1");

  // Every message type, well formed.
  link0.send(text_message(2, "SPEED:"));
  link0.send(variable(1, 200, 99));  // the golden frame
  link0.send(variable(3, 16383, -2.5));
  link0.send(encoded(ring::message::variable(1, 0, INT64_MAX)));  // the largest and smallest Q32.32 values
  link0.send(encoded(ring::message::variable(1, 1, INT64_MIN)));
  link0.send(variable(1, 7, 0.1));
  link0.send(encoded(ring::message::keypad_offset(2, 5)));
  link0.send(encoded(ring::message::keypad_mode(2, 127)));
  link0.send(encoded(ring::message::keypad_mode(2, 0)));
  std::string controls = "\x0c\x0e" "FEED \\ LENGTH:\r\n\x1b" "H ";
  controls.push_back('\0');
  controls += "\x7f\t\"quoted\"";
  link0.send(text_message(15, controls));  // every kind of escape in the text field
  link0.send(text_message(1, std::string(256, 'A')));  // the longest by default
  // A CRC error: C1 of the golden frame changed.
  bytes crc = variable(1, 200, 99);
  crc[14] ^= 0x01;
  link0.send(crc);
  link0.idle(10);

  // Every frame error reason.
  link1.send({0x41, 0x42, 0x43});                    // stray data
  link1.send({0x88});                                // stray end of message
  link1.send({0x91, 'H', 'E'});                      // interrupted by the next header
  link1.send({0x89, 0x41, 0x90});                    // end of message hops 2, header hops 1
  link1.send({0x89, 0x88});                          // character transfer without characters
  link1.send(bytes{0x8a, 1, 2, 3, 4, 5, 6, 7, 0x88});  // variable transfer of 7 bytes
  link1.send({0x8b, 0x00, 0x88});                    // keypad offset 0
  link1.send({0x8c, 0x05, 0x88});                    // keypad mode 5
  link1.send({0x8d, 0x41, 0x88});                    // type 5
  link1.send({0x8f, 0x41, 0x42, 0x88});              // type 7
  link1.send({0x81, 0x41, 0x42, 0x80});              // header with A = 0
  bytes x9 = variable(1, 200, 99);  // X9 (frame byte 12) with bits 6..1 set, and the CRC of what is sent
  x9[12] = 0x02;
  const std::uint16_t x9_crc = ring::crc_of<ring::crc16_ccitt_false, ring::variable_crc_length>(x9.data() + 1);
  x9[13] = static_cast<std::uint8_t>(x9_crc & 0x7F);
  x9[14] = static_cast<std::uint8_t>((x9_crc >> 8) & 0x7F);
  link1.send(x9);
  bytes long_text = text_message(1, std::string(256, 'C'));
  long_text.insert(long_text.end() - 1, 'D');  // 257 characters: one too many
  link1.send(long_text);
  link1.send({0x41, 0x88, 0x42});  // stray data, stray end of message, stray data
  link1.send({0x89, 0x41});       // cut short by the idle line
  link1.idle(5);
  link1.send({0x42});
  link1.send({0x89, 0x43});  // cut short by the end of the capture

  // Keypad traffic and a text on the third link.
  link2.send(text_message(14, "5"));
  link2.send(text_message(14, "U"));
  link2.send(text_message(1, "X"));

  link0.flush();
  link1.flush();
  link2.flush();
  if (!file) die("cannot write ring.pcapng");
}

void write_example2(const std::string& dir) {
  std::ofstream file(dir + "/example2.pcapng", std::ios::binary);
  pcapng_writer writer(file);
  // The manual's Example 2 as `trionet ring simulate example2` runs it: its two programs and a keypad.
  std::vector<trionet::host::node_spec> nodes(3);
  const char* const programs[] = {"examples/manual/example2_three_axis.bas", "examples/manual/example2_two_axis.bas"};
  for (std::size_t i = 0; i < 2; ++i) {
    const trionet::host::embedded_file* program = trionet::host::find_embedded_file(programs[i]);
    if (program == nullptr) die("example 2's programs are not built in");
    nodes[i].what = trionet::host::node_spec::kind::mc;
    nodes[i].program_name = programs[i];
    nodes[i].program_text = std::string(program->text());
  }
  nodes[2].what = trionet::host::node_spec::kind::keypad;
  std::string error;
  auto net = trionet::host::ring_network::build(nodes, trionet::host::network_config{}, error);
  if (!net || !net->set_keys("wait=1000 1:up 1:up 1:up 1:y 1:up 1:up 1:y 1:start", error)) die(error.c_str());
  const char* const names[] = {"MC 3-axis", "MC 2-axis", "keypad"};
  std::vector<ring_link> links;
  links.reserve(3);
  for (std::size_t i = 0; i < 3; ++i) {
    links.emplace_back(writer, "link " + std::to_string(i) + ": " + names[i] + " -> " + names[(i + 1) % 3]);
  }
  net->on_link_byte([&](std::uint64_t time, std::size_t link, std::uint8_t byte) { links[link].byte_at(time, byte); });
  if (net->run(2000000) != trionet::host::run_end::settled) die("example 2 did not settle");
  if (net->report(2).vrs.empty()) die("example 2 did not complete its handshake");
  for (ring_link& link : links) link.flush();
  if (!file) die("cannot write example2.pcapng");
}

// ---------------------------------------------------------------------------------------------------------
// CAN

can::frame frame_of(std::uint32_t id, std::uint8_t dlc, const bytes& data) {
  can::frame f;
  f.id = id;
  f.dlc = dlc;
  for (std::size_t i = 0; i < data.size() && i < 8; ++i) f.data[i] = data[i];
  return f;
}

can::frame vr_frame(std::uint8_t sender, std::uint8_t receiver, std::uint8_t vr, double value) {
  const can::identifier_result id = can::exchange_identifier(5, sender, receiver);
  if (!id) die("exchange identifier");
  std::uint8_t data[can::vr_message_size];
  if (can::encode_vr(vr, value, data) != can::encode_status::ok) die("encode_vr");
  return frame_of(id.identifier, 8, bytes(data, data + 8));
}

void write_can(const std::string& dir) {
  std::ofstream file(dir + "/can.pcapng", std::ios::binary);
  pcapng_writer writer(file);
  const std::uint32_t can0 = writer.add_interface("can0", capture_network::can).id;
  const std::uint32_t can1 = writer.add_interface("can1", capture_network::can).id;
  const std::vector<can::frame> frames = {
      vr_frame(1, 4, 1, 2.345),  // the note's example: 028#0100000000020D7A
      vr_frame(2, 1, 7, -1.5),
      vr_frame(5, 3, 255, 4294967295.9999),
      vr_frame(3, 5, 0, 0.0),
      vr_frame(4, 2, 100, 2.34565),
      vr_frame(1, 2, 10, -0.0001),
      vr_frame(2, 3, 11, 123456.789),
      vr_frame(3, 4, 12, 1.0),
      vr_frame(4, 5, 13, -7.25),
      vr_frame(5, 1, 14, 99),
      frame_of(40, 8, {1, 1, 0, 0, 0, 0, 0, 0}),                    // sign 1, magnitude 0: -0
      frame_of(40, 8, {1, 2, 0, 0, 0, 2, 0, 0}),                    // bad sign
      frame_of(21, 8, {1, 0, 0, 0, 0, 2, 0x27, 0x10}),              // fraction 10000
      frame_of(0x123, 8, {1, 2, 3, 4, 5, 6, 7, 8}),                 // foreign identifier
      frame_of(0x7FF, 0, {}),                                       // foreign, no data
      frame_of(can::frame::extended_flag | 40, 8, bytes(8, 0)),     // extended identifier 40
      frame_of(can::frame::remote_flag | 40, 8, {}),                // remote frame on 40
      frame_of(40, 3, {1, 0, 0}),                                   // DLC 3
      frame_of(40, 12, {1, 0, 0, 0, 0, 2, 0x0d, 0x7a}),             // DLC 12 (8 bytes on the wire)
      frame_of(60, 8, bytes(8, 0)),                                 // node 6 of 5
      frame_of(14, 8, bytes(8, 0)),                                 // receive channel 5 of 5 nodes
  };
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto record = socketcan_record(frames[i]);
    check(writer.write(i % 3 == 2 ? can1 : can0, epoch + i * 1000000u + 123,
                       byte_view(record.data(), record.size())));
  }
  if (!file) die("cannot write can.pcapng");
}

// ---------------------------------------------------------------------------------------------------------
// Genius

std::vector<std::uint16_t> words_of(const genius::transmission& t) {
  std::uint16_t out[600];
  const genius::encode_result r = genius::encode_transmission(span<std::uint16_t>(out, 600), t);
  if (!r) die("genius encode");
  return std::vector<std::uint16_t>(out, out + r.length);
}
std::uint16_t word(genius::character c) {
  return genius::encode_character(c);
}

void write_genius(const std::string& dir) {
  std::ofstream file(dir + "/genius.pcapng", std::ios::binary);
  pcapng_writer writer(file);
  const std::uint32_t line = writer.add_interface("genius 153.6 kbaud", capture_network::genius).id;
  genius_record_splitter splitter;
  std::uint64_t now = 0;
  const auto sink = [&](byte_view record, std::uint64_t time_ns) { check(writer.write(line, time_ns, record)); };
  const auto send = [&](const std::vector<std::uint16_t>& words) {
    for (std::uint16_t w : words) splitter.push(w, epoch + (now++) * genius_character_ns, sink);
    now += 20;  // the skip time and turn of the next device, roughly
  };

  const std::uint8_t a[] = {0x11, 0x22, 0x33};
  const std::uint8_t b[] = {0xA5};
  const std::uint8_t c[] = {0x00, 0xFF, 0x40};
  const genius::segment plain[] = {{false, 0, byte_view(a, 3)}};
  const genius::segment with_blocks[] = {
      {false, 0, byte_view(b, 1)}, {true, 7, byte_view(a, 3)}, {false, 0, byte_view(c, 3)}, {true, 31, byte_view(b, 1)}};
  const genius::segment only_block[] = {{true, 0, byte_view(c, 3)}};
  std::vector<std::uint8_t> many(300, 0x5A);
  const genius::segment big[] = {{false, 0, byte_view(many.data(), many.size())}};

  send(words_of({4, true, 0, span<const genius::segment>(plain, 1)}));         // broadcast
  send(words_of({5, false, 9, span<const genius::segment>(plain, 1)}));        // directed
  send(words_of({6, false, 0, {}}));                                           // directed, destination only
  send(words_of({7, true, 0, span<const genius::segment>(with_blocks, 4)}));   // blocks
  send(words_of({8, false, 30, span<const genius::segment>(only_block, 1)}));  // directed, one block
  std::vector<std::uint16_t> stop_error = words_of({9, true, 0, span<const genius::segment>(plain, 1)});
  stop_error.back() ^= 0x04;  // Stop CRC bit 0
  send(stop_error);
  std::vector<std::uint16_t> block_error = words_of({10, true, 0, span<const genius::segment>(with_blocks, 4)});
  block_error[6] ^= 0x08;  // the first End of block's CRC bit 1
  send(block_error);
  send({0x0695});  // start bit 1
  send({0x0294});  // stop bit 0
  send({0x1694});  // bits above bit 10
  std::vector<std::uint16_t> framed_out = words_of({11, true, 0, span<const genius::segment>(plain, 1)});
  framed_out[2] |= 0x0001;  // a framing error inside a transmission cuts it short
  send(framed_out);
  send({word(genius::data_character(0x44)), word(genius::data_character(0x45)), word(genius::stop_character(0))});
  send({word(genius::start_character(12, true)), word(genius::data_character(1))});  // cut short by a Start
  send({word(genius::start_character(13, true)), word(genius::control_character(0xA0)),
        word(genius::stop_character(0))});  // unknown control character
  send({word(genius::start_character(14, true)), word(genius::start_of_block_character(1)),
        word(genius::end_of_block_character(0)), word(genius::stop_character(0))});  // empty block
  send({word(genius::start_character(15, false)), word(genius::data_character(40)),
        word(genius::stop_character(0))});  // destination out of range
  send({word(genius::start_character(16, false)), word(genius::start_of_block_character(2))});  // no destination
  send({word(genius::start_character(17, true)), word(genius::stop_character(0))});  // empty transmission
  send({word(genius::start_character(18, true)), word(genius::end_of_block_character(0))});
  send({word(genius::start_character(19, true)), word(genius::start_of_block_character(3)),
        word(genius::data_character(1)), word(genius::stop_character(0))});  // block not closed
  std::vector<std::uint16_t> overflow = words_of({20, true, 0, span<const genius::segment>(big, 1)});
  send(overflow);
  send({word(genius::start_character(21, true)), word(genius::data_character(1))});  // open at the end
  splitter.flush(sink);
  if (!file) die("cannot write genius.pcapng");
}

// ---------------------------------------------------------------------------------------------------------
// random: well-formed traffic with random faults, on all three networks, from a fixed seed

class random_source {  // xorshift64: the same capture on every machine
 public:
  explicit random_source(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    state_ ^= state_ << 13;
    state_ ^= state_ >> 7;
    state_ ^= state_ << 17;
    return state_;
  }
  std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(next() % n); }
  std::uint8_t byte() { return static_cast<std::uint8_t>(next()); }

 private:
  std::uint64_t state_;
};

// A valid frame of a random message, or random bytes; then, one time in three, a random fault.
bytes random_ring_bytes(random_source& r) {
  bytes out;
  const std::uint8_t hops = static_cast<std::uint8_t>(1 + r.below(15));
  switch (r.below(6)) {
    case 0: {
      std::string text(1 + r.below(r.below(8) == 0 ? 300 : 12), ' ');
      for (char& c : text) c = static_cast<char>(r.below(128));
      out = text_message(hops, text);
      break;
    }
    case 1:
      out = encoded(ring::message::variable(hops, static_cast<std::uint16_t>(r.below(16384)),
                                            static_cast<std::int64_t>(r.next())));
      break;
    case 2:
      out = encoded(ring::message::keypad_offset(hops, static_cast<std::uint8_t>(1 + r.below(15))));
      break;
    case 3:
      out = encoded(ring::message::keypad_mode(hops, r.below(2) == 0 ? 0 : 127));
      break;
    default:
      out.resize(r.below(20));
      for (std::uint8_t& b : out) b = r.byte();
      break;
  }
  if (r.below(3) == 0 && !out.empty()) {
    const std::size_t at = r.below(static_cast<std::uint32_t>(out.size()));
    switch (r.below(3)) {
      case 0:
        out[at] ^= static_cast<std::uint8_t>(1u << r.below(8));
        break;
      case 1:
        out.erase(out.begin() + static_cast<std::ptrdiff_t>(at));
        break;
      default:
        out.insert(out.begin() + static_cast<std::ptrdiff_t>(at), r.byte());
        break;
    }
  }
  return out;
}

std::vector<std::uint16_t> random_genius_words(random_source& r) {
  std::vector<std::uint8_t> data(r.below(r.below(10) == 0 ? 300 : 8));
  for (std::uint8_t& b : data) b = r.byte();
  std::vector<genius::segment> segments;
  std::size_t at = 0;
  while (at < data.size()) {
    const std::size_t n = 1 + r.below(static_cast<std::uint32_t>(data.size() - at));
    segments.push_back({r.below(2) == 0, static_cast<std::uint8_t>(r.below(32)), byte_view(data.data() + at, n)});
    at += n;
  }
  const bool broadcast = !data.empty() && r.below(2) == 0;  // a directed one may carry its destination alone
  std::vector<std::uint16_t> out(data.size() + 2 * segments.size() + 3);
  const genius::encode_result result = genius::encode_transmission(
      span<std::uint16_t>(out.data(), out.size()),
      genius::transmission{static_cast<std::uint8_t>(r.below(32)), broadcast, static_cast<std::uint8_t>(r.below(32)),
                           span<const genius::segment>(segments.data(), segments.size())});
  if (!result) die("genius encode");
  out.resize(result.length);
  if (r.below(3) == 0) {
    const std::size_t where = r.below(static_cast<std::uint32_t>(out.size()));
    switch (r.below(3)) {
      case 0:
        out[where] = static_cast<std::uint16_t>(out[where] ^ (1u << r.below(11)));  // any bit: framing errors too
        break;
      case 1:
        out.erase(out.begin() + static_cast<std::ptrdiff_t>(where));
        break;
      default:
        out.insert(out.begin() + static_cast<std::ptrdiff_t>(where), static_cast<std::uint16_t>(r.below(0x800)));
        break;
    }
  }
  return out;
}

can::frame random_can_frame(random_source& r) {
  can::frame f;
  const std::uint8_t sender = static_cast<std::uint8_t>(1 + r.below(5));
  const std::uint8_t receiver = static_cast<std::uint8_t>(1 + (sender + r.below(4)) % 5);
  const can::identifier_result id = can::exchange_identifier(5, sender, receiver);
  f.id = r.below(4) != 0 && id ? id.identifier : r.below(0x800);
  if (r.below(10) == 0) f.id |= can::frame::remote_flag;
  if (r.below(10) == 0) f.id = can::frame::extended_flag | static_cast<std::uint32_t>(r.next() & 0x1FFFFFFF);
  f.dlc = static_cast<std::uint8_t>(r.below(5) != 0 ? 8 : r.below(16));
  for (std::uint8_t& d : f.data) d = r.byte();
  f.data[1] = static_cast<std::uint8_t>(r.below(8) != 0 ? r.below(2) : r.byte());
  if (r.below(4) != 0) f.data[6] = static_cast<std::uint8_t>(f.data[6] % 0x28);  // mostly fractions <= 10239
  return f;
}

void write_random(const std::string& dir) {
  std::ofstream file(dir + "/random.pcapng", std::ios::binary);
  pcapng_writer writer(file);
  random_source r(0x7452494F4E4554ull);
  ring_link link(writer, "link 0: random");
  // A name in Latin-1, not UTF-8 (a capture written elsewhere): tshark prints its bytes, the view escapes the
  // byte that is not UTF-8, and scripts/wireshark-compare reads both as the same name.
  const std::uint32_t line = writer.add_interface("genius random, Stra\xdf" "e 3", capture_network::genius).id;
  const std::uint32_t bus = writer.add_interface("can random", capture_network::can).id;
  genius_record_splitter splitter;
  std::uint64_t now = 0;
  const auto sink = [&](byte_view record, std::uint64_t time_ns) { check(writer.write(line, time_ns, record)); };
  for (int i = 0; i < 400; ++i) {
    link.send(random_ring_bytes(r));
    if (r.below(8) == 0) link.idle(3);
    for (std::uint16_t w : random_genius_words(r)) splitter.push(w, epoch + (now++) * genius_character_ns, sink);
    const auto record = socketcan_record(random_can_frame(r));
    check(writer.write(bus, epoch + static_cast<std::uint64_t>(i) * 1000000u, byte_view(record.data(), record.size())));
  }
  // CAN FD frames (standard and extended, flags BRS and ESI) and error frames: the view gives the fields
  // Wireshark's SocketCAN dissector shows for them.
  for (int i = 0; i < 40; ++i) {
    const bool error_frame = r.below(4) == 0;
    const bool fd = !error_frame;
    std::vector<std::uint8_t> record(fd ? 72 : 16, 0);
    const bool extended = r.below(2) == 0;
    const std::uint32_t id = error_frame ? 0x20000000U | static_cast<std::uint32_t>(r.below(0x200))
                             : extended  ? 0x80000000U | static_cast<std::uint32_t>(r.below(0x20000000))
                                         : static_cast<std::uint32_t>(r.below(0x800));
    for (int b = 0; b < 4; ++b) record[static_cast<std::size_t>(b)] = static_cast<std::uint8_t>(id >> (24 - 8 * b));
    record[4] = static_cast<std::uint8_t>(fd ? r.below(65) : 8);
    if (fd) record[5] = static_cast<std::uint8_t>(0x04U | r.below(4));  // CANFD_FDF, BRS and ESI at random
    for (std::size_t k = 8; k < record.size(); ++k) record[k] = static_cast<std::uint8_t>(r.below(256));
    check(writer.write(bus, epoch + static_cast<std::uint64_t>(400 + i) * 1000000u, byte_view(record.data(), record.size())));
  }
  link.flush();
  splitter.flush(sink);
  if (!file) die("cannot write random.pcapng");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIRECTORY\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) die("cannot create " + dir + ": " + error.message());
  write_ring(dir);
  write_example2(dir);
  write_can(dir);
  write_genius(dir);
  write_random(dir);
  for (const char* name : {"ring", "example2", "can", "genius", "random"}) {
    const std::size_t records = write_view(dir + "/" + name + ".pcapng", dir + "/" + name + ".jsonl");
    std::printf("%s.pcapng: %zu records\n", name, records);
  }
  capture_view_options three_nodes;  // the same CAN capture seen as a 3-node exchange (a preference in Lua)
  three_nodes.can_node_count = 3;
  write_view(dir + "/can.pcapng", dir + "/can_3_nodes.jsonl", three_nodes);
  return 0;
}

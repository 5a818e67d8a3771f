// The instruction counter's driver: runs one fixed workload `repeats` times, for callgrind (not a benchmark).
//
//   trionet_instructions <workload> <repeats>     prints "<units> <unit name>" fed through the code measured
//   trionet_instructions --list                   prints the workload names
//
// The code measured for each workload is one `trionet_measured_*` function, never inlined, so that
//   valgrind --tool=callgrind --collect-atstart=no --toggle-collect='trionet_measured_*' ...
// counts exactly the instructions executed inside it (the library's code inlined there, its callees, and the
// loop that feeds it bytes) and nothing of start-up, workload generation or checking. scripts/bench runs two
// repeat counts and divides the difference of the two totals by the difference of the units fed, so that any
// cost paid once per run cancels too. What is outside the measured functions (e.g. GET# reading a delivered
// message) is not counted.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "boost_crc.hpp"
#include "genius_layout.hpp"
#include "simulated_ring.hpp"
#include "trionet/can/frame.hpp"
#include "trionet/can/node.hpp"
#include "trionet/can/vr_codec.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/motion_coordinator.hpp"
#include "trionet/vr.hpp"
#include "workloads.hpp"

namespace tb = trionet::bench;
namespace ring = trionet::ring;
namespace can = trionet::can;
using trionet::byte_view;

namespace {

struct tally {
  std::uint64_t messages = 0;
  std::uint64_t characters = 0;
  std::uint64_t fields = 0;
  std::uint64_t other = 0;

  void operator()(const ring::decode_result& r) noexcept {
    if (r.status == ring::decode_status::ok) {
      ++messages;
      characters += r.msg.text.size();
      fields += r.msg.vr ^ static_cast<std::uint64_t>(r.msg.value);
    } else {
      ++other;
    }
  }
};

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "trionet_instructions: %s\n", what);
  std::exit(1);
}

}  // namespace

// ---- the measured functions (C linkage: plain names for callgrind's --toggle-collect) ----

// An empty asm statement that may touch any memory: no instructions, but the compiler can no longer treat a
// measured function as pure and drop or merge repeated calls with the same arguments.
#define TRIONET_OPAQUE() asm volatile("" ::: "memory")

extern "C" {

[[gnu::noinline]] void trionet_measured_decoder_bytewise(ring::decoder<>& d, const std::uint8_t* p,
                                                         std::size_t n, tally& t) noexcept {
  TRIONET_OPAQUE();
  for (const std::uint8_t* const end = p + n; p != end; ++p) {
    const ring::decode_result r = d.push(*p);
    if (r.status != ring::decode_status::incomplete) t(r);
  }
}

[[gnu::noinline]] void trionet_measured_decoder_bulk(ring::decoder<>& d, const std::uint8_t* p, std::size_t n,
                                                     tally& t) noexcept {
  TRIONET_OPAQUE();
  d.push(byte_view(p, n), t);
}

[[gnu::noinline]] void trionet_measured_mc_forward(ring::motion_coordinator<>& mc, const std::uint8_t* p,
                                                   std::size_t n, std::uint64_t& sent) noexcept {
  TRIONET_OPAQUE();
  for (const std::uint8_t* const end = p + n; p != end; ++p) {
    mc.receive(*p);
    std::uint8_t out = 0;
    if (mc.transmit(out)) sent += out;
  }
}

[[gnu::noinline]] void trionet_measured_mc_forward_bulk(ring::motion_coordinator<>& mc, const std::uint8_t* p,
                                                        std::size_t n, std::uint8_t* out,
                                                        std::size_t& sent) noexcept {
  TRIONET_OPAQUE();
  for (std::size_t i = 0; i < n; i += tb::dma_chunk) {
    mc.receive(byte_view(p + i, n - i < tb::dma_chunk ? n - i : tb::dma_chunk));
    sent += mc.transmit(trionet::byte_buffer(out, tb::dma_chunk * 2));
  }
}

// What a host's POSIX link (src/host/posix_link.cpp) does with one read() and one write() of up to 256 bytes:
// before, a byte at a time through the node's byte port (virtual calls); now, the node's bulk calls.
[[gnu::noinline]] void trionet_measured_host_link_bytewise(trionet::byte_port& port, const std::uint8_t* p,
                                                           std::size_t n, std::uint8_t* out,
                                                           std::size_t& sent) noexcept {
  TRIONET_OPAQUE();
  for (std::size_t i = 0; i < n; i += tb::host_chunk) {
    const std::size_t k = n - i < tb::host_chunk ? n - i : tb::host_chunk;
    for (std::size_t j = 0; j < k; ++j) port.receive(p[i + j]);
    std::size_t m = 0;
    while (m < tb::host_chunk && port.transmit(out[m])) ++m;
    sent += m;
  }
}

[[gnu::noinline]] void trionet_measured_host_link_bulk(tb::host_mc& mc, const std::uint8_t* p, std::size_t n,
                                                       std::uint8_t* out, std::size_t& sent) noexcept {
  TRIONET_OPAQUE();
  for (std::size_t i = 0; i < n; i += tb::host_chunk) {
    mc.receive(byte_view(p + i, n - i < tb::host_chunk ? n - i : tb::host_chunk));
    sent += mc.transmit(trionet::byte_buffer(out, tb::host_chunk));
  }
}

[[gnu::noinline]] void trionet_measured_mc_receive(ring::motion_coordinator<>& mc, const std::uint8_t* p,
                                                   std::size_t n) noexcept {
  TRIONET_OPAQUE();
  for (const std::uint8_t* const end = p + n; p != end; ++p) mc.receive(*p);
}

[[gnu::noinline]] std::uint16_t trionet_measured_crc_table(const std::uint8_t* p, std::size_t length,
                                                           std::size_t count) noexcept {
  TRIONET_OPAQUE();
  std::uint16_t sum = 0;
  for (std::size_t m = 0; m < count; ++m)
    sum ^= ring::crc16_ccitt_false_table::compute(p + m * length, length);
  return sum;
}

[[gnu::noinline]] std::uint16_t trionet_measured_crc_sliced(const std::uint8_t* p, std::size_t length,
                                                            std::size_t count) noexcept {
  TRIONET_OPAQUE();
  std::uint16_t sum = 0;
  for (std::size_t m = 0; m < count; ++m)
    sum ^= ring::crc16_ccitt_false_sliced::compute(p + m * length, length);
  return sum;
}

[[gnu::noinline]] std::uint16_t trionet_measured_crc_bitwise(const std::uint8_t* p, std::size_t length,
                                                             std::size_t count) noexcept {
  TRIONET_OPAQUE();
  std::uint16_t sum = 0;
  for (std::size_t m = 0; m < count; ++m)
    sum ^= ring::crc16_ccitt_false_bitwise::compute(p + m * length, length);
  return sum;
}

[[gnu::noinline]] std::uint16_t trionet_measured_crc_boost(const std::uint8_t* p, std::size_t length,
                                                           std::size_t count) noexcept {
  TRIONET_OPAQUE();
  std::uint16_t sum = 0;
  for (std::size_t m = 0; m < count; ++m) sum ^= tb::boost_crc16_ccitt_false(p + m * length, length);
  return sum;
}

[[gnu::noinline]] void trionet_measured_can_encode_parts(const can::vr_message* messages, std::size_t n,
                                                         can::frame& out) noexcept {
  TRIONET_OPAQUE();
  for (std::size_t i = 0; i < n; ++i) (void)can::encode_vr_message(messages[i], out.data);
}

[[gnu::noinline]] void trionet_measured_can_encode_double(const double* values, std::size_t n,
                                                          can::frame& out) noexcept {
  TRIONET_OPAQUE();
  for (std::size_t i = 0; i < n; ++i)
    (void)can::encode_vr(static_cast<std::uint16_t>(i & 0xFF), values[i], out.data);
}

[[gnu::noinline]] std::uint32_t trionet_measured_can_decode(const can::frame* frames,
                                                            std::size_t n) noexcept {
  TRIONET_OPAQUE();
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const can::decode_result r = can::decode_vr_frame(frames[i]);
    sum += r.message.value.integer_part + static_cast<std::uint32_t>(r.status);
  }
  return sum;
}

[[gnu::noinline]] void trionet_measured_can_node_receive(can::vr_exchange_node& node,
                                                         const can::frame* frames, std::size_t n) noexcept {
  TRIONET_OPAQUE();
  for (std::size_t i = 0; i < n; ++i) (void)node.receive(frames[i]);
}

[[gnu::noinline]] void trionet_measured_simulator(tb::simulated_ring& r, std::uint64_t byte_times) noexcept {
  TRIONET_OPAQUE();
  r.run(byte_times);
}

[[gnu::noinline]] void trionet_measured_genius_bus(trionet::host::genius_bus& bus,
                                                  trionet::host::genius_bus_result& result) {
  TRIONET_OPAQUE();
  result = bus.run();
}

}  // extern "C"

namespace {

// Keeps a result alive without a benchmark library: a volatile store.
volatile std::uint64_t sink;

struct workload {
  const char* name;
  const char* unit;
  std::uint64_t (*run)(std::size_t repeats);
};

// Every message decoded, none in error, and every character delivered (a character stream's messages carry
// characters_per_message each; a variable stream's none).
void check(const tally& t, const std::vector<std::uint8_t>& stream, std::size_t repeats) {
  const std::uint64_t messages = repeats * tb::messages_per_stream;
  const bool characters =
      ring::type_of(stream[0]) == static_cast<std::uint8_t>(ring::message_type::character);
  if (t.other != 0 || t.messages != messages ||
      t.characters != (characters ? messages * tb::characters_per_message : 0)) {
    fail("decoder results are wrong");
  }
}

std::uint64_t decoder_bytewise(const std::vector<std::uint8_t>& stream, std::size_t repeats) {
  ring::decoder<> d;
  tally t;
  for (std::size_t r = 0; r < repeats; ++r)
    trionet_measured_decoder_bytewise(d, stream.data(), stream.size(), t);
  check(t, stream, repeats);
  sink = t.characters + t.fields;
  return repeats * stream.size();
}

std::uint64_t decoder_bulk(const std::vector<std::uint8_t>& stream, std::size_t repeats) {
  ring::decoder<> d;
  tally t;
  for (std::size_t r = 0; r < repeats; ++r) trionet_measured_decoder_bulk(d, stream.data(), stream.size(), t);
  check(t, stream, repeats);
  sink = t.characters + t.fields;
  return repeats * stream.size();
}

std::uint64_t mc_forward(const std::vector<std::uint8_t>& stream, std::size_t repeats) {
  trionet::vr_table<256> vr;
  ring::motion_coordinator<> mc(vr);
  std::uint64_t sent = 0;
  for (std::size_t r = 0; r < repeats; ++r)
    trionet_measured_mc_forward(mc, stream.data(), stream.size(), sent);
  if (mc.netstat() != 0 || mc.forward_backlog() != 0 ||
      mc.forwarding_counters().messages_forwarded != repeats * tb::messages_per_stream) {
    fail("forwarding went wrong");
  }
  sink = sent;
  return repeats * stream.size();
}

// A DMA-fed node, through `measured`: the bulk receive + transmit.
using dma_measured = void (*)(ring::motion_coordinator<>&, const std::uint8_t*, std::size_t, std::uint8_t*,
                              std::size_t&) noexcept;
std::uint64_t mc_forward_dma(const std::vector<std::uint8_t>& stream, std::size_t repeats,
                             dma_measured measured) {
  trionet::vr_table<256> vr;
  ring::motion_coordinator<> mc(vr);
  std::uint8_t out[tb::dma_chunk * 2];
  std::size_t sent = 0;
  for (std::size_t r = 0; r < repeats; ++r) measured(mc, stream.data(), stream.size(), out, sent);
  if (mc.netstat() != 0 || mc.forward_backlog() != 0 || sent != repeats * stream.size() ||
      mc.forwarding_counters().messages_forwarded != repeats * tb::messages_per_stream) {
    fail("DMA-fed forwarding went wrong");
  }
  sink = out[0];
  return repeats * stream.size();
}

// A host's POSIX link on a node with a host's forward buffer: each read() of up to 256 bytes goes in, then
// what one write() of 256 bytes takes comes out.
std::uint64_t host_link(const std::vector<std::uint8_t>& stream, std::size_t repeats, bool bulk) {
  trionet::vr_table<256> vr;
  tb::host_mc mc(vr);
  std::uint8_t out[tb::host_chunk];
  std::size_t sent = 0;
  for (std::size_t r = 0; r < repeats; ++r) {
    if (bulk) {
      trionet_measured_host_link_bulk(mc, stream.data(), stream.size(), out, sent);
    } else {
      trionet_measured_host_link_bytewise(mc, stream.data(), stream.size(), out, sent);
    }
  }
  if (mc.netstat() != 0 || mc.forward_backlog() != 0 || sent != repeats * stream.size() ||
      mc.forwarding_counters().messages_forwarded != repeats * tb::messages_per_stream) {
    fail("the host link's forwarding went wrong");
  }
  sink = out[0];
  return repeats * stream.size();
}

// Character transfers to the node, one message per call; the program's GET#4 reading between messages is not
// measured.
std::uint64_t mc_deliver_characters(std::size_t repeats) {
  const std::vector<std::uint8_t> stream = tb::character_stream(1);
  const std::size_t frame = tb::characters_per_message + ring::framing_length;
  trionet::vr_table<256> vr;
  ring::motion_coordinator<> mc(vr);
  std::uint64_t read = 0;
  for (std::size_t r = 0; r < repeats; ++r) {
    for (std::size_t start = 0; start < stream.size(); start += frame) {
      trionet_measured_mc_receive(mc, &stream[start], frame);
      while (const ring::get_result g = mc.get(4)) read += g.value;
    }
  }
  if (mc.netstat() != 0 || mc.counters().character_messages != repeats * tb::messages_per_stream) {
    fail("delivery went wrong");
  }
  sink = read;
  return repeats * stream.size();
}

std::uint64_t mc_deliver_variables(std::size_t repeats) {
  const std::vector<std::uint8_t> stream = tb::variable_stream(1);
  trionet::vr_table<256> vr;
  ring::motion_coordinator<> mc(vr);
  for (std::size_t r = 0; r < repeats; ++r) trionet_measured_mc_receive(mc, stream.data(), stream.size());
  if (mc.netstat() != 0 || mc.counters().variables_written != repeats * tb::messages_per_stream) {
    fail("delivery went wrong");
  }
  return repeats * stream.size();
}

template <std::uint16_t (*Measured)(const std::uint8_t*, std::size_t, std::size_t)>
std::uint64_t crc(std::size_t length, std::size_t count, std::size_t repeats) {
  const std::vector<std::uint8_t> bytes = tb::random_bytes(length * count);
  std::uint16_t sum = 0;
  for (std::size_t r = 0; r < repeats; ++r)
    sum = static_cast<std::uint16_t>(sum ^ Measured(bytes.data(), length, count));
  sink = sum;
  return repeats * bytes.size();
}

constexpr std::size_t frames_per_repeat = 256;

std::uint64_t can_encode_parts(std::size_t repeats) {
  const std::vector<can::frame> frames = tb::vr_frames(frames_per_repeat);
  std::vector<can::vr_message> messages;
  for (const can::frame& f : frames) messages.push_back(can::decode_vr_frame(f).message);
  can::frame out;
  for (std::size_t r = 0; r < repeats; ++r)
    trionet_measured_can_encode_parts(messages.data(), messages.size(), out);
  sink = out.data[7];
  return repeats * frames.size();
}

std::uint64_t can_encode_double(std::size_t repeats) {
  const std::vector<can::frame> frames = tb::vr_frames(frames_per_repeat);
  std::vector<double> values;
  for (const can::frame& f : frames)
    values.push_back(trionet::to_double(can::decode_vr_frame(f).message.value));
  can::frame out;
  for (std::size_t r = 0; r < repeats; ++r)
    trionet_measured_can_encode_double(values.data(), values.size(), out);
  sink = out.data[7];
  return repeats * frames.size();
}

std::uint64_t can_decode(std::size_t repeats) {
  const std::vector<can::frame> frames = tb::vr_frames(frames_per_repeat);
  std::uint32_t sum = 0;
  for (std::size_t r = 0; r < repeats; ++r) sum += trionet_measured_can_decode(frames.data(), frames.size());
  sink = sum;
  return repeats * frames.size();
}

std::uint64_t can_node_receive(std::size_t repeats) {
  struct null_port final : can::port {
    can::transmit_status send(const can::frame&) noexcept override { return can::transmit_status::ok; }
  } bus;
  trionet::vr_table<256> vr;
  can::vr_exchange_node node(can::make_node_address(5, 1).address, bus, vr);
  const std::vector<can::frame> frames = tb::vr_frames(frames_per_repeat);
  for (std::size_t r = 0; r < repeats; ++r)
    trionet_measured_can_node_receive(node, frames.data(), frames.size());
  if (node.counters().written != repeats * frames.size()) fail("the CAN node did not write every frame");
  return repeats * frames.size();
}

std::uint64_t simulator(std::size_t repeats) {
  constexpr std::uint64_t byte_times = 1024;
  static tb::simulated_ring r;  // static: four nodes with their VR tables are too big for some stacks
  for (std::size_t k = 0; k < repeats; ++k) trionet_measured_simulator(r, byte_times);
  if (!r.healthy()) fail("the simulated ring went wrong");
  return repeats * byte_times * tb::simulated_ring::nodes;
}

// The Genius bus simulator (genius_layout.hpp, 30 devices and the controller) for 10 scans per repeat: per
// simulated bit time.
std::uint64_t genius_bus_30_devices(std::size_t repeats) {
  const auto stations = tb::genius_layout(30);
  trionet::host::genius_bus bus(stations, tb::genius_config(static_cast<std::uint32_t>(10 * repeats)));
  trionet::host::genius_bus_result result;
  trionet_measured_genius_bus(bus, result);
  if (!result.complete || result.collisions != 0 || result.wrong_deliveries != 0)
    fail("the simulated Genius bus did not complete its scans cleanly");
  return static_cast<std::uint64_t>(result.end_us * 1e6 / static_cast<double>(bus.bit_ps()));
}

constexpr std::size_t crc_short = 12;
constexpr std::size_t crc_short_count = 256;
constexpr std::size_t crc_long = 4096;

const workload workloads[] = {
    {"decoder_characters_bytewise", "byte",
     [](std::size_t n) { return decoder_bytewise(tb::character_stream(1), n); }},
    {"decoder_characters_bulk", "byte",
     [](std::size_t n) { return decoder_bulk(tb::character_stream(1), n); }},
    {"decoder_variables_bytewise", "byte",
     [](std::size_t n) { return decoder_bytewise(tb::variable_stream(1), n); }},
    {"decoder_variables_bulk", "byte", [](std::size_t n) { return decoder_bulk(tb::variable_stream(1), n); }},
    {"mc_forward_characters", "byte", [](std::size_t n) { return mc_forward(tb::character_stream(2), n); }},
    {"mc_forward_variables", "byte", [](std::size_t n) { return mc_forward(tb::variable_stream(2), n); }},
    {"mc_forward_characters_bulk", "byte",
     [](std::size_t n) {
       return mc_forward_dma(tb::character_stream(2), n, trionet_measured_mc_forward_bulk);
     }},
    {"mc_forward_variables_bulk", "byte",
     [](std::size_t n) {
       return mc_forward_dma(tb::variable_stream(2), n, trionet_measured_mc_forward_bulk);
     }},
    {"host_link_characters_bytewise", "byte",
     [](std::size_t n) { return host_link(tb::character_stream(2), n, false); }},
    {"host_link_characters_bulk", "byte", [](std::size_t n) { return host_link(tb::character_stream(2), n, true); }},
    {"mc_deliver_characters", "byte", mc_deliver_characters},
    {"mc_deliver_variables", "byte", mc_deliver_variables},
    {"crc_12_bytes_trionet_table", "byte",
     [](std::size_t n) { return crc<trionet_measured_crc_table>(crc_short, crc_short_count, n); }},
    {"crc_12_bytes_trionet_sliced", "byte",
     [](std::size_t n) { return crc<trionet_measured_crc_sliced>(crc_short, crc_short_count, n); }},
    {"crc_12_bytes_trionet_bitwise", "byte",
     [](std::size_t n) { return crc<trionet_measured_crc_bitwise>(crc_short, crc_short_count, n); }},
    {"crc_12_bytes_boost", "byte",
     [](std::size_t n) { return crc<trionet_measured_crc_boost>(crc_short, crc_short_count, n); }},
    {"crc_4096_bytes_trionet_table", "byte",
     [](std::size_t n) { return crc<trionet_measured_crc_table>(crc_long, 1, n); }},
    {"crc_4096_bytes_trionet_sliced", "byte",
     [](std::size_t n) { return crc<trionet_measured_crc_sliced>(crc_long, 1, n); }},
    {"crc_4096_bytes_trionet_bitwise", "byte",
     [](std::size_t n) { return crc<trionet_measured_crc_bitwise>(crc_long, 1, n); }},
    {"crc_4096_bytes_boost", "byte",
     [](std::size_t n) { return crc<trionet_measured_crc_boost>(crc_long, 1, n); }},
    {"can_encode_parts", "frame", can_encode_parts},
    {"can_encode_double", "frame", can_encode_double},
    {"can_decode", "frame", can_decode},
    {"can_node_receive", "frame", can_node_receive},
    {"simulator_4_nodes", "node-byte step", simulator},
    {"genius_bus_30_devices", "bit time", genius_bus_30_devices},
};

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--list") == 0) {
    for (const workload& w : workloads) std::printf("%s %s\n", w.name, w.unit);
    return 0;
  }
  if (argc != 3) fail("usage: trionet_instructions <workload> <repeats> | --list");
  const long repeats = std::strtol(argv[2], nullptr, 10);
  if (repeats < 1) fail("repeats must be at least 1");
  for (const workload& w : workloads) {
    if (std::strcmp(argv[1], w.name) == 0) {
      const std::uint64_t units = w.run(static_cast<std::size_t>(repeats));
      std::printf("%llu %s\n", static_cast<unsigned long long>(units), w.unit);
      return 0;
    }
  }
  fail("no such workload (see --list)");
}

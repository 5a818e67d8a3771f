// Fuzz harness: the pcapng reader and writer (src/host/trionet/host/pcapng.hpp).
//
// Input: read whole as a pcapng file; also taken as a script for the writer (first byte: 1..4 interfaces,
// each with a network byte and a name; then records: interface byte, 8 time bytes, a length byte and the
// bytes), whose file is read back, and read again with one byte (position and value from the input) changed.
// Invariants:
//   - no crash, no undefined behaviour, no unbounded memory, whatever the file (ASan/UBSan in scripts/fuzz);
//   - every call consumes at least one whole block or ends reading: the number of calls is bounded by the
//     input size; a status that ends reading repeats on every later call;
//   - a record names an interface of its section, its bytes fit in the file, its network matches its
//     interface's link type (and for link type 252 the dissector its tags name);
//   - write -> read gives back every interface name and every record (interface, time, bytes, network).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_check.hpp"
#include "trionet/host/pcapng.hpp"

// The host library is compiled into the tool, not into the header library: compile it here.
#include "../src/host/pcapng.cpp"

namespace {

using namespace trionet::host;
using trionet_fuzz::input_reader;

void check_file(const std::string& file) {
  std::istringstream in(file);
  pcapng_reader::limits limits;
  limits.max_block_length = 1u << 16;
  limits.max_interfaces = 64;
  pcapng_reader reader(in, limits);
  const std::size_t max_calls = file.size() / 12 + 2;  // a block is at least 12 bytes
  for (std::size_t call = 0;; ++call) {
    FUZZ_CHECK(call <= max_calls);
    const pcapng_read_result r = reader.next();
    FUZZ_CHECK(r.status <= pcapng_read_status::bad_exported_pdu);
    if (r) {
      FUZZ_CHECK(r.record.interface < reader.interfaces().size());
      FUZZ_CHECK(r.record.bytes.size() <= file.size());
      const std::uint16_t link_type = reader.interfaces()[r.record.interface].link_type;
      if (link_type == linktype_can_socketcan) {
        FUZZ_CHECK(r.record.network == capture_network::can);
      } else if (link_type == linktype_wireshark_upper_pdu && r.record.dissector == "trionet_ring") {
        FUZZ_CHECK(r.record.network == capture_network::ring);
      } else if (link_type == linktype_wireshark_upper_pdu && r.record.dissector == "trionet_genius") {
        FUZZ_CHECK(r.record.network == capture_network::genius);
      } else {
        FUZZ_CHECK(r.record.network == capture_network::other);
      }
      if (link_type != linktype_wireshark_upper_pdu) FUZZ_CHECK(r.record.dissector.empty());
    }
    if (ends_reading(r.status) || r.status == pcapng_read_status::end_of_file) {
      FUZZ_CHECK(reader.next().status == r.status);
      FUZZ_CHECK(reader.next().status == r.status);
      return;
    }
  }
}

struct written {
  std::uint32_t interface;
  std::uint64_t time_ns;
  std::vector<std::uint8_t> bytes;
};

void check_round_trip(input_reader& script) {
  std::ostringstream out;
  pcapng_writer writer(out);
  const std::size_t interfaces = 1u + script.byte() % 4u;
  std::vector<std::string> names;
  std::vector<capture_network> networks;
  for (std::size_t i = 0; i < interfaces; ++i) {
    const auto network = static_cast<capture_network>(script.byte() % 3u);
    std::string name(script.byte() % 24u, '\0');
    for (char& c : name) c = static_cast<char>('a' + script.byte() % 26u);
    const pcapng_interface_result added = writer.add_interface(name, network);
    FUZZ_CHECK(added && added.id == i);
    names.push_back(name);
    networks.push_back(network);
  }
  std::vector<written> records;
  while (!script.done() && records.size() < 64) {
    written record;
    record.interface = static_cast<std::uint32_t>(script.byte() % interfaces);
    record.time_ns = std::uint64_t{script.u32()} << 32 | script.u32();
    record.bytes.resize(script.byte());
    for (std::uint8_t& b : record.bytes) b = script.byte();
    FUZZ_CHECK(writer.write(record.interface, record.time_ns,
                            trionet::byte_view(record.bytes.data(), record.bytes.size())) ==
               pcapng_write_status::ok);
    records.push_back(record);
  }
  FUZZ_CHECK(writer.write(static_cast<std::uint32_t>(interfaces), 0, {}) == pcapng_write_status::bad_interface);
  const std::string file = out.str();

  std::istringstream in(file);
  pcapng_reader reader(in);
  for (const written& record : records) {
    const pcapng_read_result r = reader.next();
    FUZZ_CHECK(r.status == pcapng_read_status::ok);
    FUZZ_CHECK(r.record.interface == record.interface);
    FUZZ_CHECK(r.record.time_ns == record.time_ns);
    FUZZ_CHECK(std::vector<std::uint8_t>(r.record.bytes.begin(), r.record.bytes.end()) == record.bytes);
    FUZZ_CHECK(r.record.network == networks[record.interface]);
  }
  FUZZ_CHECK(reader.next().status == pcapng_read_status::end_of_file);
  FUZZ_CHECK(reader.interfaces().size() == interfaces);
  for (std::size_t i = 0; i < interfaces; ++i) FUZZ_CHECK(reader.interfaces()[i].name == names[i]);

  // One byte changed: whatever it hits, the reader stays within its invariants.
  if (!file.empty()) {
    std::string changed = file;
    const std::uint32_t position = script.u32();
    changed[position % changed.size()] = static_cast<char>(script.byte() ^ 0x5A);
    check_file(changed);
    check_file(changed.substr(0, position % changed.size()));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file(reinterpret_cast<const char*>(data), data == nullptr ? 0 : size);
  check_file(file);
  input_reader script(data, data == nullptr ? 0 : size);
  check_round_trip(script);
  return 0;
}

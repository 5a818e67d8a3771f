// Captures in the tool: `<part> decode --pcap FILE` reads a pcapng capture record by record (docs/cli.md).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "cli.hpp"
#include "trionet/host/pcapng.hpp"

namespace trionet::cli {

/// Where a record came from: its number in the file (1-based, as Wireshark counts frames), its interface
/// and its time.
struct capture_position {
  std::uint64_t record = 0;
  std::uint32_t interface = 0;
  std::string_view interface_name;
  std::uint64_t time_ns = 0;
};

/// Adds "record", "interface_id", "interface" (when the capture names it) and "time" to an event.
void add_position(event& e, const capture_position& where);

/// Reads the capture at `path`. With `fields`, every record is printed as one JSON object of the fields
/// Wireshark's dissectors show (host::record_fields), whatever its network; else `decode` is called for each
/// record of `network` and appends its events, and a record of another network is one `other_network`
/// event. A record the reader rejects is a `capture_error` event and reading goes on; a file that cannot be
/// read on ends with a `capture_error` event. Returns the exit status: 1 if the file cannot be opened, is not
/// pcapng or cannot be read, or standard output fails; else 0.
/// A decoder that prints text instead of JSON events passes `note`: it is called, in place of the
/// `capture_error` and `other_network` events, with the record's number, the reader's reason (`error` true) or
/// the other network's name (`error` false), and the output to append to.
using capture_note = std::function<void(std::uint64_t record, std::string_view what, bool error, std::string& out)>;
int read_capture(const std::string& path, host::capture_network network, bool fields, std::uint8_t can_node_count,
                 const std::function<void(const host::pcapng_record&, const capture_position&, std::string&)>& decode,
                 const capture_note& note = nullptr);

}  // namespace trionet::cli

// The library's own view of a capture record: the decoders' results as named fields, with the names and
// meanings of the Wireshark dissectors in wireshark/ (trionet_ring.*, trionet_can.*, trionet_genius.*), so
// that `tshark -T json` output and the tool's JSON can be compared field for field (docs/wireshark.md).
//
// Each record is decoded on its own, by a fresh decoder with the default configuration (ring: 256
// characters, CRC-16/CCITT-FALSE; Genius: 256 data bytes, 16 segments, CRC-6/G-704; CAN: the node count
// given), as a dissector sees it. A record that holds several messages (transmissions) is cut the way
// capture.hpp cuts a link, and each part is decoded in turn. Host code (std::string, std::vector).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "trionet/host/pcapng.hpp"
#include "trionet/host/text.hpp"
#include "trionet/span.hpp"

namespace trionet::host {

/// One named value. `text` holds text fields and byte strings ("48:01:00"); a field of type `marker`
/// carries no value (Wireshark's expert items, e.g. "trionet_ring.expert.crc_error").
struct capture_field {
  enum class type : std::uint8_t { unsigned_integer, signed_integer, boolean, real, text, marker };
  std::string name;
  type kind = type::marker;
  std::uint64_t unsigned_value = 0;
  std::int64_t signed_value = 0;
  bool boolean = false;
  double real = 0;
  std::string text;
};

using capture_fields = std::vector<capture_field>;

struct capture_view_options {
  std::uint8_t can_node_count = 5;  ///< TN20-17 controllers on the bus (2..11)
};

/// The fields of a ring record: header (hops, type), data, end of message, the type's fields, the CRC of a
/// direct variable transfer, the decoder's status and frame error.
capture_fields ring_record_fields(byte_view record);

/// The fields of a Genius record: every character (word, control bit, byte, kind and the kind's fields),
/// the parser's status per character and for the transmission, the CRCs it checked.
capture_fields genius_record_fields(byte_view record);

/// The fields of a SocketCAN record: Wireshark's own can.id, can.len and flags, and for a TN20-17 VR frame
/// (a standard data frame of DLC 8 whose identifier routes for `node_count` nodes) the route and the value.
capture_fields can_record_fields(byte_view record, std::uint8_t node_count);

/// All fields of a record from `reader`: frame.interface_id, frame.interface_name, frame.time_epoch, the
/// exported-PDU dissector name if any, then the network's fields.
capture_fields record_fields(const pcapng_reader& reader, const pcapng_record& record,
                             const capture_view_options& options = {});

/// The fields as one JSON object on one line: each name once, in order of first appearance; a value, or an
/// array of values when the name occurs more than once; a marker is "".
std::string fields_json(const capture_fields& fields);


}  // namespace trionet::host

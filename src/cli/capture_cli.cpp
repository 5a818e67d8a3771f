// `--pcap FILE` for the decoders: see capture_cli.hpp.
#include "capture_cli.hpp"

#include <fstream>

#include "trionet/host/capture_view.hpp"
#include "trionet/host/files.hpp"

namespace trionet::cli {

void add_position(event& e, const capture_position& where) {
  e.number("record", where.record).number("interface_id", where.interface);
  if (!where.interface_name.empty()) e.text("interface", where.interface_name);
  e.time(where.time_ns);
}

int read_capture(const std::string& path, host::capture_network network, bool fields, std::uint8_t can_node_count,
                 const std::function<void(const host::pcapng_record&, const capture_position&, std::string&)>& decode,
                 const capture_note& note) {
  std::ifstream file;
  const host::file_result usable = host::open_input_stream(path, file);
  if (!usable) return fail_io(usable.message(path, "capture"));
  host::pcapng_reader reader(file);
  host::capture_view_options options;
  options.can_node_count = can_node_count;
  output out;
  std::uint64_t number = 0;
  while (true) {
    const host::pcapng_read_result r = reader.next();
    if (r.status == host::pcapng_read_status::end_of_file) break;
    ++number;
    if (r.status == host::pcapng_read_status::not_pcapng || r.status == host::pcapng_read_status::read_failed) {
      out.flush();
      return fail_io(host::printable(path) + (r.status == host::pcapng_read_status::not_pcapng
                                                  ? ": not a pcapng capture (it does not start with a section header "
                                                    "block; a libpcap .pcap file converts with editcap -F pcapng)"
                                                  : ": reading the capture failed"));
    }
    if (!r) {
      if (note) {
        note(number, host::to_string(r.status), true, out.text());
      } else {
        event(out.text(), "capture_error").number("record", number).text("reason", host::to_string(r.status));
      }
      if (host::ends_reading(r.status)) break;
      continue;
    }
    capture_position where;
    where.record = number;
    where.interface = r.record.interface;
    where.interface_name = reader.interfaces()[r.record.interface].name;
    where.time_ns = r.record.time_ns;
    if (fields) {
      out.text() += host::fields_json(host::record_fields(reader, r.record, options));
      out.text() += '\n';
    } else if (r.record.network == network) {
      decode(r.record, where, out.text());
    } else if (note) {
      note(number, host::to_string(r.record.network), false, out.text());
    } else {
      event e(out.text(), "other_network");
      add_position(e, where);
      e.text("network", host::to_string(r.record.network));
    }
    if (!out.maybe_flush()) return fail_output();
  }
  if (!out.flush()) return fail_output();
  return exit_ok;
}

}  // namespace trionet::cli

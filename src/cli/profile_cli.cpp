// `--profile FILE` for every command, and `trionet profile show|header` (docs/profile.md).
#include "profile_cli.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "trionet/host/files.hpp"

namespace trionet::cli {
namespace {

learn::profile& profile_in_effect() {
  static learn::profile p;
  return p;
}

bool& profile_named() {
  static bool named = false;
  return named;
}

std::string& profile_path() {
  static std::string path;
  return path;
}

constexpr const char* show_usage =
    "usage: trionet profile show [FILE]\n"
    "Prints a profile as JSON with every key: FILE's (checked strictly), else the one --profile names, else "
    "the\n"
    "default (docs/protocol.md's decisions), a start for writing one. Exit status 0, 1 when FILE cannot be\n"
    "read, 2 when it is not a valid profile (the message names the key, its line and column).\n";

constexpr const char* header_usage =
    "usage: trionet profile header [FILE] [--namespace NS] [-o OUT]\n"
    "Writes a C++17 header with the profile's constexpr policies (ring_crc, ring_layout, ring_decoder,\n"
    "motion_coordinator<>, keypad<>, keypad_codes, defkey, can_node_count, genius_crc) in namespace NS\n"
    "(default trionet_profile) for a firmware build: FILE's profile, else the one --profile names, else the\n"
    "default. To standard output, or to OUT. NS is identifiers joined by ::, none a C++ keyword or trionet\n"
    "(the library's namespace). Exit status 0, 1 when reading or writing failed, 2 for bad arguments or a\n"
    "profile that is not valid.\n";

const option_list show_options = {
    {"FILE", nullptr, "@file", "the profile to print (else the one --profile names, else the default)"}};

const option_list header_options = {
    {"FILE", nullptr, "@file", "the profile (else the one --profile names, else the default)"},
    {"--namespace", "NS", "", "the C++ namespace of the policies (default trionet_profile)"},
    {"-o", "OUT", "@file", "write the header to OUT (else to standard output)"},
};

// Writes `text` to the file `path`: the exit status, 1 with the cause when it cannot be written.
int write_text_file(const std::string& path, const std::string& text, const char* what) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  const auto failed = [&] {
    return fail_io(std::string("cannot write ") + what + " " + host::printable(path) + ": " + std::strerror(errno));
  };
  if (file == nullptr) return failed();
  const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  if (std::fclose(file) != 0 || !written) return failed();
  return exit_ok;
}

// The profile a `profile` command works on: FILE if given, else the one in effect.
int profile_argument(const arguments& args, learn::profile& out) {
  if (args.positionals.size() > 1)
    return fail("unexpected argument '" + host::printable(args.positionals[1]) + "'");
  if (args.positionals.empty()) {
    out = active_profile();
    return exit_ok;
  }
  const std::string& file = args.positionals[0];
  // An unknown option, as for every other command: a file whose name starts with '-' is given as ./NAME.
  if (file.size() > 1 && file[0] == '-') {
    return fail("unexpected argument '" + host::printable(file) + "' (not an option here; a file named so is ./" +
                host::printable(file) + ")");
  }
  std::string error;
  bool io = false;
  if (!read_profile_file(file, out, error, io)) return io ? fail_io(error) : fail(error);
  return exit_ok;
}

int show_main(const words& all) {
  arguments args;
  std::string error;
  if (!parse_arguments(all, show_options, args, error)) return fail(error);
  learn::profile p;
  const int status = profile_argument(args, p);
  if (status != exit_ok) return status;
  return write_profile_file(p, "-");
}

int header_main(const words& all) {
  arguments args;
  std::string error;
  if (!parse_arguments(all, header_options, args, error)) return fail(error);
  learn::profile p;
  const int status = profile_argument(args, p);
  if (status != exit_ok) return status;
  const std::string name = args.has("--namespace") ? args.options.at("--namespace") : "trionet_profile";
  const learn::header_result header = learn::profile_header(p, name);
  if (!header) return fail("--namespace '" + host::printable(name) + "' cannot be used: " + header.reason);
  if (!args.has("-o")) {
    return write_stdout(header.text) ? exit_ok : fail_output();
  }
  return write_text_file(args.options.at("-o"), header.text, "header");
}

const command profile_commands[] = {
    {"show", "print a profile (a file's, the one --profile names, or the default) with every key", show_usage,
     show_main, show_options},
    {"header", "write a C++ header of constexpr policies for a firmware build", header_usage, header_main,
     header_options},
};

}  // namespace

const learn::profile& active_profile() {
  return profile_in_effect();
}

bool profile_given() {
  return profile_named();
}

bool read_profile_file(const std::string& path, learn::profile& out, std::string& error, bool& io) {
  std::string text;
  const host::file_result read = host::read_bounded_file(path, learn::max_json_bytes, text);
  if (!read) {
    io = true;
    error = read.message(path, "profile");
    return false;
  }
  io = false;
  const learn::profile_result r = learn::read_profile(text);
  if (!r) {
    error = "profile " + host::printable(path) + ": " + learn::to_string(r.status);
    if (r.status == learn::profile_status::not_json)
      error += std::string(" (") + learn::to_string(r.json) + ")";
    if (!r.key.empty()) error += " at " + r.key;
    if (r.line != 0)
      error += " (line " + std::to_string(r.line) + ", column " + std::to_string(r.column) + ")";
    if (!r.message.empty()) error += ": " + r.message;
    return false;
  }
  out = r.value;
  return true;
}

int write_profile_file(const learn::profile& p, const std::string& path) {
  const std::string text = learn::write_profile(p);
  if (path == "-") {
    return write_stdout(text) ? exit_ok : fail_output();
  }
  return write_text_file(path, text, "profile");
}

int take_profile_option(words& args) {
  std::string path;
  bool found = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--") break;
    const bool joined = args[i].compare(0, 10, "--profile=") == 0;  // --profile=FILE
    if (args[i] != "--profile" && !joined) continue;
    if (found) return fail("option --profile given twice");
    if (!joined && i + 1 >= args.size()) return fail("option --profile needs a value");
    path = joined ? args[i].substr(10) : args[i + 1];
    found = true;
    const std::size_t taken = joined ? 1 : 2;
    args.erase(args.begin() + static_cast<std::ptrdiff_t>(i),
               args.begin() + static_cast<std::ptrdiff_t>(i + taken));
    --i;
  }
  if (!found) return exit_ok;
  std::string error;
  bool io = false;
  if (!read_profile_file(path, profile_in_effect(), error, io)) return io ? fail_io(error) : fail(error);
  profile_named() = true;
  profile_path() = path;
  return exit_ok;
}

int check_ring_capacities(const std::string& command, ring_capacity_use use) {
  const learn::ring_profile& p = active_profile().ring;
  const auto refuse = [&](const char* key, std::size_t value) {
    return fail("profile " + host::printable(profile_path()) + ": ring." + key + " is " + std::to_string(value) + ": `trionet " +
                command + "` supports " + (use == ring_capacity_use::text_limit && key[0] == 'm' ? "at most " : "only ") +
                std::to_string(ring::default_max_characters) +
                " (a compile-time capacity; build a firmware with this profile from `trionet profile header`)");
  };
  const bool fits = use == ring_capacity_use::text_limit ? p.max_characters <= ring::default_max_characters
                                                         : p.max_characters == ring::default_max_characters;
  if (!fits) return refuse("max_characters", p.max_characters);
  if (use == ring_capacity_use::receive_buffer && p.receive_buffer != ring::default_max_characters)
    return refuse("receive_buffer", p.receive_buffer);
  return exit_ok;
}

ring::encode_result encode_with_profile(byte_buffer out, const ring::message& m) {
  const learn::ring_profile& p = active_profile().ring;
  if (p.crc == ring::crc16_parameters{} && p.layout == ring::variable_layout_parameters{})
    return ring::encode(out, m);
  const ring::crc16_runtime crc(p.crc);
  return ring::with_variable_layout(p.layout, [&](auto layout) {
    return ring::encode<ring::crc16_runtime, decltype(layout)>(out, m, crc);
  });
}

const part profile_part = {"profile", "the wire parameters in one file: show one, write its C++ header",
                           profile_commands, sizeof profile_commands / sizeof profile_commands[0], ""};

}  // namespace trionet::cli

// The man pages and the bash completion, written from the command and option tables: see manual.hpp.
#include "manual.hpp"

#include <set>
#include <vector>

namespace trionet::cli {
namespace {

// ---------------------------------------------------------------------------------------------------------
// what the tables do not hold: exit status, files, examples

struct exit_status_entry {
  int status;
  const char* meaning;
};

constexpr exit_status_entry exit_statuses[] = {
    {exit_ok, "the work was done: the input was read (wire errors are events in the output, not failures)"},
    {exit_io, "reading or writing failed: a missing or unreadable file, port or program, a capture that is not "
              "pcapng, an output that cannot be written, a live link that was lost"},
    {exit_usage, "bad arguments: one line \"trionet: PROBLEM\" on standard error, nothing on standard output"},
    {exit_check, "a --check found a problem (genius timing --check), or a learn command found no single answer"},
    {exit_limit, "a limit cut the work short and --fail-on-limit was given (without it: 0, the limit said on "
                 "standard error)"},
};

// An example a page prints: a command and its whole output, checked against the tool by the test
// manual_examples (tests/cli).
struct example {
  const char* page;  // "ring": trionet-ring(1); "" for trionet(1)
  const char* text;  // what it shows
  const char* command;
  const char* output;
};

constexpr example examples[] = {
    {"", "The frame that sets VR(200) to 99 on the Motion Coordinator one hop along:",
     "trionet ring encode var --to 10 --vr 200 --value 99", "8a 48 01 00 00 00 00 30 0c 00 00 00 00 7f 3e 88\n"},
    {"", "The TN20-17 frame node 1 sends to node 2 to set VR(5) = 1.5, as candump text:",
     "trionet can encode --from 1 --to 2 --vr 5 --value 1.5", "014#0500000000011388\n"},
    {"ring", "Encode a direct variable transfer, then decode it again:",
     "trionet ring encode var --to 10 --vr 200 --value 99", "8a 48 01 00 00 00 00 30 0c 00 00 00 00 7f 3e 88\n"},
    {"ring", "", "trionet ring decode 8a 48 01 00 00 00 00 30 0c 00 00 00 00 7f 3e 88",
     "{\"event\":\"message\",\"line\":1,\"type\":\"var\",\"hops\":1,\"vr\":200,\"raw\":\"0x0000006300000000\","
     "\"value\":99}\n"},
    {"can", "The frame node 1 sends to node 2 to set VR(5) = 1.5, and what a decoder makes of it:",
     "trionet can encode --from 1 --to 2 --vr 5 --value 1.5", "014#0500000000011388\n"},
    {"can", "", "echo 014#0500000000011388 | trionet can decode",
     "{\"event\":\"vr\",\"line\":1,\"id\":20,\"from\":1,\"to\":2,\"vr\":5,\"negative\":false,\"int\":1,"
     "\"frac\":5000,\"value\":1.5}\n"},
    {"can", "The identifier tables of an exchange of three controllers:", "trionet can table --nodes 3",
     "Node Base address  Rx #1  Rx #2\n10                 10     11\n20                 20     21\n"
     "30                 30     31\n\nNode Base address  Tx #5  Tx #6\n10                 20     30\n"
     "20                 31     10\n30                 11     21\n"},
    {"genius", "A transmission from SBA 3 to SBA 5 carrying two bytes, as characters, and decoded again:",
     "trionet genius encode --from 3 --to 5 1122", "c:03 05 11 22 c:51\n"},
    {"genius", "", "trionet genius decode c:03 05 11 22 c:51",
     "transmission from SBA 3, directed to SBA 5 (line 1, character 1)\n  data 11 22\n"
     "1 transmission, 0 errors, 0 characters skipped\n"},
    {"genius", "The scan time of a bus of two devices with 16 bytes of inputs and outputs each:",
     "trionet genius scan-time --rate 153.6s --device 16,16",
     "rate 153.6s (153.6 kbaud standard): 0.943 ms per device + 0.0715 ms per byte of inputs and outputs (GE "
     "GFK-0825F)\n  device  io_bytes  scan_time_ms\n       1        16         2.087\n"
     "       2        16         2.087\n"
     "bus: 2 devices, 32 bytes: sum 4.174 ms, scan time 4.174 ms (above the minimum of 3 ms)\n"
     "computed character time (11 bits at 153600 bit/s): 0.071615 ms, not used above\n"},
    {"profile", "The default profile, a start for writing one:", "trionet profile show > my.json", ""},
    {"profile", "An encoding with a profile's parameters (here the default's, so the frame is the usual one):",
     "trionet ring encode var --to 10 --vr 200 --value 99 --profile my.json",
     "8a 48 01 00 00 00 00 30 0c 00 00 00 00 7f 3e 88\n"},
};

// ---------------------------------------------------------------------------------------------------------
// roff

// Text for roff: backslashes escaped, hyphens of options and names kept as the ASCII minus (\-), and a line
// never starting with a control character.
std::string roff(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '\\') {
      out += "\\e";
    } else if (c == '-') {
      out += "\\-";
    } else {
      out += c;
    }
  }
  if (!out.empty() && (out[0] == '.' || out[0] == '\'')) out.insert(0, "\\&");
  return out;
}

std::string upper(std::string text) {
  for (char& c : text) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  }
  return text;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t from = 0;
  while (from < text.size()) {
    std::size_t end = text.find('\n', from);
    if (end == std::string::npos) end = text.size();
    lines.push_back(text.substr(from, end - from));
    from = end + 1;
  }
  return lines;
}

std::size_t indent_of(const std::string& line) {
  const std::size_t at = line.find_first_not_of(' ');
  return at == std::string::npos ? line.size() : at;
}

std::string trimmed(const std::string& line) {
  const std::size_t first = line.find_first_not_of(' ');
  if (first == std::string::npos) return "";
  return line.substr(first, line.find_last_not_of(' ') - first + 1);
}

// Where a "TERM   description" line's description starts (two or more blanks after the term), or npos.
std::size_t description_column(const std::string& line) {
  const std::size_t gap = line.find("  ", indent_of(line));
  if (gap == std::string::npos) return std::string::npos;
  const std::size_t at = line.find_first_not_of(' ', gap);
  return at == std::string::npos ? std::string::npos : at;
}

// A command's help text as man(7) text: the synopsis lines of "usage:", then its paragraphs and lists. A
// block headed "...options:" is left out: the option table lists those options.
std::string help_as_roff(const std::string& usage) {
  const std::vector<std::string> lines = lines_of(usage);
  std::string out;
  std::size_t i = 0;
  // Synopsis: "usage: trionet ...", further "trionet ..." lines, and their notes (further right, or after a
  // wide gap on the same line).
  struct synopsis_line {
    std::string command;
    std::string note;
  };
  std::vector<synopsis_line> synopsis;
  if (i < lines.size() && lines[i].compare(0, 6, "usage:") == 0) {
    std::string first = trimmed(lines[i].substr(6));
    std::vector<std::string> candidates;
    if (!first.empty()) candidates.push_back(first);
    ++i;
    // A note is set off by three or more blanks and starts as words do; other runs of blanks align the
    // synopsis lines of a help text and are one blank here.
    const auto add = [&synopsis](const std::string& text) {
      synopsis_line s;
      for (std::size_t at = 0; at < text.size(); ++at) {
        if (text[at] != ' ') {
          s.command += text[at];
          continue;
        }
        const std::size_t next = text.find_first_not_of(' ', at);
        if (next == std::string::npos) break;
        if (next - at >= 3 && ((text[next] >= 'a' && text[next] <= 'z') || text[next] == '(')) {
          s.note = trimmed(text.substr(next));
          break;
        }
        s.command += ' ';
        at = next - 1;
      }
      synopsis.push_back(s);
    };
    if (!first.empty()) add(first);
    while (i < lines.size() && indent_of(lines[i]) > 0 && !trimmed(lines[i]).empty()) {
      const std::string text = trimmed(lines[i]);
      if (text.compare(0, 8, "trionet ") == 0) {
        add(text);
      } else if (!synopsis.empty()) {
        synopsis.back().note += (synopsis.back().note.empty() ? "" : " ") + text;
      }
      ++i;
    }
  }
  for (const synopsis_line& s : synopsis) {
    out += ".TP\n.B " + roff(s.command) + "\n" + (s.note.empty() ? "" : roff(s.note) + "\n");
  }
  // The rest: paragraphs (lines from the margin, and their indented continuation lines), lists of
  // "TERM  description" lines, and skipped option blocks.
  bool in_paragraph = false;
  bool in_list = false;
  std::size_t list_indent = 0;
  while (i < lines.size()) {
    const std::string& line = lines[i++];
    const std::string text = trimmed(line);
    if (text.empty()) {
      in_paragraph = in_list = false;
      continue;
    }
    const std::size_t indent = indent_of(line);
    if (indent == 0 && text.size() >= 8 && text.compare(text.size() - 8, 8, "options:") == 0) {
      while (i < lines.size() && indent_of(lines[i]) > 0) ++i;
      in_paragraph = in_list = false;
      continue;
    }
    if (indent == 0) {
      if (!in_paragraph || in_list) out += ".PP\n";
      out += roff(text) + "\n";
      in_paragraph = text.back() != ':';
      in_list = false;
      continue;
    }
    const std::size_t column = description_column(line);
    if (column != std::string::npos && (!in_list || indent <= list_indent)) {
      out += ".TP\n.B " + roff(trimmed(line.substr(0, column))) + "\n" + roff(line.substr(column)) + "\n";
      in_list = true;
      list_indent = indent;
      in_paragraph = false;
      continue;
    }
    // A continuation: of a list item's description, or of a paragraph.
    if (!in_list && !in_paragraph) out += ".PP\n";
    out += roff(text) + "\n";
    if (!in_list) in_paragraph = true;
  }
  return out;
}

std::string option_item(const option& o) {
  std::string tag;
  if (o.name[0] == '-') {
    tag = "\\fB" + roff(o.name) + "\\fR";
    if (o.value != nullptr) tag += " \\fI" + roff(o.value) + "\\fR";
  } else {
    tag = "\\fI" + roff(o.name) + "\\fR";
  }
  std::string text = roff(o.help);
  if (o.repeatable) text += " (may be given more than once)";
  return ".TP\n" + tag + "\n" + text + "\n";
}

std::string header(const std::string& name, const std::string& what) {
  return ".\\\" Written by `trionet --man " + name + "` from the tool's command and option tables.\n" + ".TH " +
         upper(name) + " 1 \"\" \"" + roff(version_line()) + "\" \"User Commands\"\n.SH NAME\n" + roff(name) +
         " \\- " + roff(what) + "\n";
}

std::string exit_status_section() {
  std::string out = ".SH EXIT STATUS\n";
  for (const exit_status_entry& e : exit_statuses) {
    out += ".TP\n.B " + std::to_string(e.status) + "\n" + roff(e.meaning) + "\n";
  }
  return out;
}

std::string examples_section(const std::string& page) {
  std::string out;
  for (const example& e : examples) {
    if (page != e.page) continue;
    if (out.empty()) out = ".SH EXAMPLES\n";
    if (e.text[0] != '\0') out += ".PP\n" + roff(e.text) + "\n";
    out += ".PP\n.RS 4\n.nf\n\\f(CW$ " + roff(e.command) + "\\fR\n";
    for (const std::string& line : lines_of(e.output)) out += (line.empty() ? std::string("\\&") : roff(line)) + "\n";
    out += ".fi\n.RE\n";
  }
  return out;
}

std::string common_options_section() {
  std::string out;
  for (const option& o : common_options()) out += option_item(o);
  return out;
}

std::string tool_page(const part_list& parts) {
  std::string out = header("trionet", "the Trio Motion Coordinator ring, TN20-17 CAN VR exchange and GE Genius bus "
                                      "from the shell");
  out += ".SH SYNOPSIS\n.B trionet\n.I part command\n.RI [ options ]\n.br\n.B trionet \\-\\-version\n";
  out += ".br\n.B trionet \\-\\-completion bash\n";
  out += ".SH DESCRIPTION\n.B trionet\nencodes, decodes, simulates and analyses the traffic of three industrial "
         "networks: the Trio Motion Coordinator fibre-optic ring, Trio's CAN VR exchange (TN20-17) and the GE "
         "Genius bus. Decoders read as the input arrives and print one JSON event per line; bad wire data is an "
         "event, never a failure. The parts, each with its own page:\n";
  for (std::size_t i = 0; i < parts.count; ++i) {
    const part& p = *parts.parts[i];
    out += ".TP\n.B " + roff(p.name) + "\n" + roff(p.summary) + "; see\n.BR trionet\\-" + roff(p.name) + " (1).\n";
  }
  out += ".PP\n"
         "\\fBtrionet\\fR \\fIpart\\fR \\fB\\-\\-help\\fR lists a part's commands, \\fBtrionet\\fR \\fIpart "
         "command\\fR \\fB\\-\\-help\\fR prints a command's help.\n";
  out += ".SH OPTIONS\nEvery command takes these (anywhere before \\fB\\-\\-\\fR):\n" + common_options_section();
  out += ".PP\nAlone:\n.TP\n.B \\-\\-version\nprint the version and exit.\n"
         ".TP\n\\fB\\-\\-completion\\fR \\fIbash\\fR\nprint the bash completion script (as installed in "
         "/usr/share/bash\\-completion/completions/trionet).\n"
         ".TP\n\\fB\\-\\-man\\fR [\\fIPAGE\\fR]\nprint the man page PAGE (without it: the names of the pages).\n";
  out += exit_status_section();
  out += ".SH FILES\n"
         ".TP\n.I FILE.json\na profile (\\fB\\-\\-profile\\fR): every configurable wire parameter of a network; "
         "see\n.BR trionet\\-profile (1).\n"
         ".TP\n.I /usr/share/bash\\-completion/completions/trionet\nthe bash completion (from the package "
         "\\fBtrionet\\fR).\n"
         ".TP\n.I /usr/lib/<triplet>/wireshark/plugins/trionet_*.lua\nthe Wireshark dissectors of the three "
         "networks (from the package \\fBtrionet\\-wireshark\\fR; \\fBtshark \\-G folders\\fR names the folder).\n"
         ".TP\n.I /usr/share/doc/libtrionet\\-dev/\nthe library's documentation: the protocol reference, the "
         "pages of each part, the profile.\n";
  out += examples_section("");
  out += ".SH SEE ALSO\n";
  for (std::size_t i = 0; i < parts.count; ++i) out += ".BR trionet\\-" + roff(parts.parts[i]->name) + " (1),\n";
  out += ".BR candump (1),\n.BR tshark (1)\n";
  return out;
}

std::string part_page(const part_list& parts, const part& p) {
  const std::string name = std::string("trionet-") + p.name;
  std::string out = header(name, p.summary);
  out += ".SH SYNOPSIS\n";
  for (std::size_t i = 0; i < p.count; ++i) {
    out += std::string(i == 0 ? "" : ".br\n") + ".B trionet " + roff(p.name) + " " + roff(p.commands[i].name) +
           "\n.RI [ options ]\n";
  }
  out += ".SH DESCRIPTION\nThe commands of the part \\fB" + roff(p.name) + "\\fR of\n.BR trionet (1):\n";
  for (std::size_t i = 0; i < p.count; ++i) {
    out += ".TP\n.B " + roff(p.commands[i].name) + "\n" + roff(p.commands[i].summary) + "\n";
  }
  for (const std::string& line : lines_of(p.notes)) out += ".PP\n" + roff(line) + "\n";
  out += ".SH COMMANDS\n";
  // Commands that share a help text share a section.
  std::set<std::size_t> done;
  for (std::size_t i = 0; i < p.count; ++i) {
    if (done.count(i) != 0) continue;
    std::vector<std::size_t> group;
    for (std::size_t j = i; j < p.count; ++j) {
      if (p.commands[j].usage == p.commands[i].usage) {
        group.push_back(j);
        done.insert(j);
      }
    }
    std::string title = std::string("trionet ") + p.name + " ";
    for (std::size_t k = 0; k < group.size(); ++k) {
      title += std::string(k == 0 ? "" : k + 1 == group.size() ? " and " : ", ") + p.commands[group[k]].name;
    }
    out += ".SS " + roff(title) + "\n" + help_as_roff(p.commands[i].usage);
    for (const std::size_t k : group) {
      const command& c = p.commands[k];
      out += ".PP\n" + std::string(group.size() == 1 ? "Options and operands:" : "Options and operands of \\fB" +
                                                                                     roff(c.name) + "\\fR:") +
             "\n";
      out += ".RS 4\n";
      for (const option& o : c.options) out += option_item(o);
      out += ".RE\n";
    }
  }
  out += ".SH OPTIONS\nEvery command also takes these (anywhere before \\fB\\-\\-\\fR):\n" + common_options_section();
  out += exit_status_section();
  out += ".PP\nEach command's section says which of them it uses.\n";
  out += ".SH FILES\n.TP\n.I FILE.json\na profile (\\fB\\-\\-profile\\fR): see\n.BR trionet\\-profile (1).\n"
         ".TP\n.I FILE.pcapng\na capture, written and read by the commands' \\fB\\-\\-pcap\\fR options; "
         "Wireshark shows it with the package \\fBtrionet\\-wireshark\\fR.\n";
  out += examples_section(p.name);
  out += ".SH SEE ALSO\n.BR trionet (1)";
  for (std::size_t i = 0; i < parts.count; ++i) {
    if (parts.parts[i] != &p) out += std::string(",\n.BR trionet\\-") + roff(parts.parts[i]->name) + " (1)";
  }
  out += "\n";
  return out;
}

// ---------------------------------------------------------------------------------------------------------
// bash

// Single-quoted for the shell.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

// The key script's words: "wait=", "KEYPAD:", and the keys (include/trionet/ring/keypad_codes.hpp).
constexpr const char* key_words = "0 1 2 3 4 5 6 7 8 9 . up down clr y n start stop";

constexpr const char* bash_functions = R"bash(
# The words of the line up to the cursor, split as the shell splits them (quotes and backslashes kept out),
# in _trionet_words; the last is the word being completed.
_trionet_split() {
  local line=${COMP_LINE:0:COMP_POINT} word="" quote="" c i n=0
  _trionet_words=()
  for ((i = 0; i < ${#line}; i++)); do
    c=${line:i:1}
    if [[ -n $quote ]]; then
      if [[ $c == "$quote" ]]; then quote=""; else word+=$c; fi
    elif [[ $c == [\"\'] ]]; then quote=$c
    elif [[ $c == \\ ]]; then ((i++)); word+=${line:i:1}
    elif [[ $c == [[:blank:]] ]]; then
      if ((n)); then _trionet_words+=("$word"); fi
      word=""; n=0; continue
    else word+=$c
    fi
    n=1
  done
  _trionet_words+=("$word")
}

# Adds to COMPREPLY what SPEC offers for the word CUR (see `option::completion` in the tool's source).
_trionet_offer() {
  local spec=$1 cur=$2 word prefix
  for word in $spec; do
    case $word in
      @file) COMPREPLY+=($(compgen -f -- "$cur")) ;;
      @port) COMPREPLY+=($(compgen -W "- $(compgen -G '/dev/tty[AU]*' | tr '\n' ' ')" -- "$cur") $(compgen -f -- "$cur")) ;;
      @interface) COMPREPLY+=($(compgen -W "- $(ls /sys/class/net 2>/dev/null | tr '\n' ' ')" -- "$cur")) ;;
      @keys)
        local last=${cur##*[[:blank:]]}
        prefix=${cur%"$last"}
        if [[ $last == [0-9]*:* ]]; then
          COMPREPLY+=($(compgen -P "$prefix${last%%:*}:" -W "@KEYS@" -- "${last#*:}"))
        else
          COMPREPLY+=($(compgen -P "$prefix" -W "wait= 1: 2: 3: 4:" -- "$last"))
        fi ;;
      *@file)
        prefix=${word%@file}
        if [[ $cur == "$prefix"* ]]; then COMPREPLY+=($(compgen -P "$prefix" -f -- "${cur#"$prefix"}"))
        else COMPREPLY+=($(compgen -W "$prefix" -- "$cur")); fi ;;
      *) COMPREPLY+=($(compgen -W "$word" -- "$cur")) ;;
    esac
  done
}

# What the option $1 of the command offers for its value ("-": a value, nothing to offer); empty for a flag.
_trionet_value() {
  local entry
  for entry in "${values[@]}"; do
    if [[ $entry == "$1 "* ]]; then
      printf '%s\n' "${entry#"$1 "}"
      return
    fi
  done
}

_trionet() {
  local IFS=$' \t\n' cur prev part command spec i operand=0 value="" options="" values="" operands=()
  COMPREPLY=()
  _trionet_split
  local count=${#_trionet_words[@]}
  cur=${_trionet_words[count - 1]}
  if ((count == 2)); then
    if [[ $cur == -* ]]; then COMPREPLY=($(compgen -W "--help --version --completion --man" -- "$cur"))
    else COMPREPLY=($(compgen -W "@PARTS@" -- "$cur")); fi
  elif ((count == 3)); then
    case ${_trionet_words[1]} in
@COMMANDS@    esac
  elif ((count > 3)); then
    case "${_trionet_words[1]} ${_trionet_words[2]}" in
@OPTIONS@    esac
    # --name=value
    if [[ $cur == --*=* ]]; then
      prev=${cur%%=*}; cur=${cur#*=}; value=1
    else
      prev=${_trionet_words[count - 2]}
    fi
    spec=$(_trionet_value "$prev")
    if [[ -n $value || ( -n $spec && $prev == -* ) ]]; then
      [[ -n $spec && $spec != - ]] && _trionet_offer "$spec" "$cur"
      [[ -n $value ]] && COMPREPLY=("${COMPREPLY[@]/#/$prev=}") && cur="$prev=$cur"
    elif [[ $cur == -* ]]; then
      COMPREPLY=($(compgen -W "$options" -- "$cur"))
    else
      # Which operand this is: the words after the command that are neither options nor their values.
      for ((i = 3; i < count - 1; i++)); do
        case ${_trionet_words[i]} in
          --) ;;
          --*=*) ;;
          -) ((operand++)) ;;
          -*) [[ -n $(_trionet_value "${_trionet_words[i]}") ]] && ((i++)) ;;
          *) ((operand++)) ;;
        esac
      done
      ((operand >= ${#operands[@]})) && operand=$((${#operands[@]} - 1))
      ((operand >= 0)) && _trionet_offer "${operands[operand]}" "$cur"
    fi
  fi
  # The shell replaces only the part of the word after its last word-break character (: and = by default).
  local broken=${cur%"${cur##*[${COMP_WORDBREAKS//[[:blank:]\"\'\\]/}]}"}
  if [[ -n $broken && ${#COMPREPLY[@]} -gt 0 ]]; then
    COMPREPLY=("${COMPREPLY[@]#"$broken"}")
  fi
  return 0
}
complete -o filenames -F _trionet trionet
)bash";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

}  // namespace

std::string manual_page_names(const part_list& parts) {
  std::string names = "trionet\n";
  for (std::size_t i = 0; i < parts.count; ++i) names += std::string("trionet-") + parts.parts[i]->name + "\n";
  return names;
}

bool manual_page(const part_list& parts, const std::string& name, std::string& page) {
  if (name == "trionet") {
    page = tool_page(parts);
    return true;
  }
  for (std::size_t i = 0; i < parts.count; ++i) {
    if (name == std::string("trionet-") + parts.parts[i]->name) {
      page = part_page(parts, *parts.parts[i]);
      return true;
    }
  }
  return false;
}

std::string bash_completion(const part_list& parts) {
  std::string names;
  std::string commands;
  std::string options;
  for (std::size_t i = 0; i < parts.count; ++i) {
    const part& p = *parts.parts[i];
    names += std::string(i == 0 ? "" : " ") + p.name;
    std::string command_names = "--help";
    for (std::size_t j = 0; j < p.count; ++j) {
      const command& c = p.commands[j];
      command_names += std::string(" ") + c.name;
      std::string option_names;
      std::string values;
      std::string operands;
      for (const option& o : joined(c.options, common_options())) {
        if (o.name[0] != '-') {
          operands += " " + quoted(o.completion);
          continue;
        }
        option_names += std::string(option_names.empty() ? "" : " ") + o.name;
        if (o.value != nullptr) {
          values += " " + quoted(std::string(o.name) + " " + (o.completion[0] == '\0' ? "-" : o.completion));
        }
      }
      options += std::string("      ") + quoted(std::string(p.name) + " " + c.name) + ")\n        options=" +
                 quoted(option_names) + "\n        values=(" + values + ")\n        operands=(" + operands +
                 ")\n        ;;\n";
    }
    commands += std::string("      ") + p.name + ") COMPREPLY=($(compgen -W " + quoted(command_names) +
                " -- \"$cur\")) ;;\n";
  }
  std::string script =
      "# bash completion for trionet(1): parts, commands, options and their values. Written by\n"
      "# `trionet --completion bash` from the tool's command and option tables; load it with\n"
      "#   source <(trionet --completion bash)\n"
      "# or install it as /usr/share/bash-completion/completions/trionet.\n";
  script += bash_functions;
  script = replaced(script, "@PARTS@", names);
  script = replaced(script, "@COMMANDS@", commands);
  script = replaced(script, "@OPTIONS@", options);
  script = replaced(script, "@KEYS@", key_words);
  return script;
}

}  // namespace trionet::cli

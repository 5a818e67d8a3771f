// The man pages and the bash completion (`trionet --man`, `trionet --completion bash`, as the build installs
// them) against the tool itself: every option of every command is in its help, its man page and its
// completion, and is one the command's parser takes; the pages render without warnings; the completion
// completes; the pages' examples print what the tool prints.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "support/run_cli.hpp"
#include "support/text_match.hpp"

namespace {

using trionet::test::find_all_patterns;
using trionet::test::find_pattern;
using trionet::test::replace_pattern;
using trionet::test::run_cli;

// Group 1 of every match of `pattern` in `text`.
std::vector<std::string> all_matches(const std::string& text, const std::string& pattern) {
  std::vector<std::string> found;
  for (const std::vector<std::string>& m : find_all_patterns(text, pattern)) found.push_back(m[1]);
  return found;
}

// The options a text names: "--name" words, and "-x" for a lowercase letter x.
std::set<std::string> options_named(const std::string& text) {
  const std::string option_word = R"((^|[\s\[(`|,])(--[a-z][a-z0-9-]*|-[a-z])(?![A-Za-z0-9_-]))";
  std::set<std::string> found;
  for (const std::vector<std::string>& m : find_all_patterns(text, option_word)) found.insert(m[2]);
  return found;
}

// The indented "  NAME  summary" lines under `heading` in a usage text.
std::vector<std::string> listed_under(const std::string& usage, const std::string& heading) {
  std::vector<std::string> names;
  std::size_t at = usage.find(heading + "\n");
  if (at == std::string::npos) return names;
  at += heading.size() + 1;
  const std::string entry = R"(^  (\S+)\s)";
  while (at < usage.size()) {
    const std::size_t end = usage.find('\n', at);
    const std::string line = usage.substr(at, end - at);
    const std::vector<std::string> m = find_pattern(line, entry);
    if (m.empty()) break;
    names.push_back(m[1]);
    at = end + 1;
  }
  return names;
}

// roff text as read: \- is -, \e is \, fonts and \& are dropped.
std::string unroff(std::string text) {
  text = replace_pattern(text, R"(\\f(\(..|[BIRP]))", "");
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\\' && i + 1 < text.size()) {
      const char next = text[i + 1];
      if (next == '-') out += '-';
      if (next == 'e') out += '\\';
      ++i;
      continue;
    }
    out += text[i];
  }
  return out;
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

struct tool_tables {
  // part -> its commands, from the help texts
  std::vector<std::pair<std::string, std::vector<std::string>>> parts;
};

tool_tables read_help() {
  tool_tables t;
  const auto top = run_cli("--help");
  for (const std::string& part : listed_under(top.out, "parts:")) {
    t.parts.push_back({part, listed_under(run_cli(part + " --help").out, "commands:")});
  }
  return t;
}

// The command's entry of the completion script: its option names, the ones that take a value, its operands.
struct completion_entry {
  std::set<std::string> options;
  std::set<std::string> value_options;
  std::vector<std::string> operands;
  bool found = false;
};

completion_entry completion_of(const std::string& script, const std::string& part, const std::string& command) {
  completion_entry e;
  const std::string key = "      '" + part + " " + command + "')\n";
  const std::size_t at = script.find(key);
  if (at == std::string::npos) return e;
  const std::size_t end = script.find(";;", at);
  const std::string body = script.substr(at + key.size(), end - at - key.size());
  std::vector<std::string> m = find_pattern(body, R"(options='([^']*)')");
  if (!m.empty()) {
    for (const std::string& word : lines_of(replace_pattern(m[1], " ", "\n")))
      e.options.insert(word);
  }
  m = find_pattern(body, R"(values=\(([^)]*)\))");
  if (!m.empty()) {
    for (const std::string& name : all_matches(m[1], R"('(\S+) )")) e.value_options.insert(name);
  }
  m = find_pattern(body, R"(operands=\(([^)]*)\))");
  if (!m.empty()) {
    e.operands = all_matches(m[1], R"('([^']*)')");
  }
  e.found = true;
  return e;
}

// The section of a part's man page that describes `command` (".SS trionet PART ..." naming it), and the options
// its option lists name (the .TP tags in bold).
struct man_section {
  std::string text;
  std::set<std::string> listed;
};

man_section man_section_of(const std::string& page, const std::string& part, const std::string& command) {
  man_section s;
  const std::vector<std::string> lines = lines_of(page);
  const std::string names_command = "(^| |, )" + command + "(,| |$)";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string title = unroff(lines[i]);
    if (title.rfind(".SS trionet " + part + " ", 0) != 0) continue;
    if (find_pattern(title.substr(13 + part.size()), names_command).empty()) continue;
    for (std::size_t j = i + 1; j < lines.size() && lines[j].rfind(".SS", 0) != 0 && lines[j].rfind(".SH", 0) != 0;
         ++j) {
      s.text += unroff(lines[j]) + "\n";
      if (lines[j - 1] == ".TP" && lines[j].rfind("\\fB\\-", 0) == 0) {
        const std::string tag = unroff(lines[j]);
        s.listed.insert(tag.substr(0, tag.find(' ')));
      }
    }
    break;
  }
  return s;
}

const std::set<std::string> common = {"--profile", "--fail-on-limit", "--help", "-h"};

std::set<std::string> without_common(std::set<std::string> options) {
  for (const std::string& c : common) options.erase(c);
  return options;
}

std::string joined(const std::set<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : " ") + n;
  return text;
}

TEST(Manual, EveryOptionOfEveryCommandIsInItsHelpManPageAndCompletion) {
  const tool_tables tables = read_help();
  ASSERT_GE(tables.parts.size(), 4u);
  const auto script = run_cli("--completion bash");
  ASSERT_EQ(script.exit_code, 0) << script.err;
  std::size_t commands = 0;
  std::size_t options = 0;
  for (const auto& [part, names] : tables.parts) {
    ASSERT_FALSE(names.empty()) << part;
    const auto page = run_cli("--man trionet-" + part);
    ASSERT_EQ(page.exit_code, 0) << page.err;
    // Commands that share a help text are one group: together they have the options the text names.
    std::map<std::string, std::vector<std::string>> groups;
    for (const std::string& command : names) {
      const auto help = run_cli(part + " " + command + " --help");
      ASSERT_EQ(help.exit_code, 0) << part << " " << command;
      groups[help.out].push_back(command);
    }
    for (const auto& [help, group] : groups) {
      // A help text that gives a command's arguments as "the arguments of `trionet PART COMMAND`" names its
      // options too.
      std::string named = help;
      for (const std::string& other : all_matches(help, "`trionet " + part + " ([a-z-]+)`"))
        named += run_cli(part + " " + other + " --help").out;
      const std::set<std::string> in_help = without_common(options_named(named));
      std::set<std::string> in_tables;
      for (const std::string& command : group) {
        ++commands;
        SCOPED_TRACE(part + " " + command);
        const completion_entry completion = completion_of(script.out, part, command);
        ASSERT_TRUE(completion.found);
        for (const char* c : {"--profile", "--help"}) EXPECT_EQ(completion.options.count(c), 1u) << c;
        const man_section section = man_section_of(page.out, part, command);
        ASSERT_FALSE(section.text.empty()) << "no section in trionet-" << part << "(1)";
        for (const std::string& o : without_common(completion.options)) {
          ++options;
          in_tables.insert(o);
          EXPECT_EQ(in_help.count(o), 1u) << o << " is not in the help text";
          EXPECT_EQ(section.listed.count(o), 1u) << o << " is not listed in the man page";
        }
      }
      for (const std::string& o : in_help) {
        EXPECT_EQ(in_tables.count(o), 1u) << o << " is in the help of " << part << " " << group.front()
                                          << " but no command of it takes it";
      }
      const man_section section = man_section_of(page.out, part, group.front());
      EXPECT_EQ(joined(section.listed), joined(in_tables)) << part << " " << group.front();
    }
  }
  EXPECT_GE(commands, 20u);
  EXPECT_GE(options, 80u);
}

// The tables are what the parsers read: each option the completion offers is taken by its command (whatever
// else the command then says), and an option it does not offer is refused.
TEST(Manual, EveryCompletedOptionIsTakenByItsCommand) {
  const tool_tables tables = read_help();
  const std::string script = run_cli("--completion bash").out;
  for (const auto& [part, names] : tables.parts) {
    for (const std::string& command : names) {
      SCOPED_TRACE(part + " " + command);
      const completion_entry completion = completion_of(script, part, command);
      ASSERT_TRUE(completion.found);
      // A command whose first operand is one of a few words (ring encode print|var|...) gets the first.
      std::string head = part + " " + command;
      if (!completion.operands.empty() && !completion.operands.front().empty() &&
          completion.operands.front().find('@') == std::string::npos) {
        head += " " + completion.operands.front().substr(0, completion.operands.front().find(' '));
      }
      const auto refused = run_cli(head + " --no-such-option");
      EXPECT_NE(refused.err.find("unknown option --no-such-option"), std::string::npos) << refused.err;
      for (const std::string& o : without_common(completion.options)) {
        const bool value = completion.value_options.count(o) != 0;
        const auto r = run_cli(head + " " + o + (value ? " /dev/null" : "") + " </dev/null");
        EXPECT_EQ(r.err.find("unknown option"), std::string::npos) << o << ": " << r.err;
      }
    }
  }
}

std::string complete(const std::string& line) {
  const std::string path = "/tmp/trionet-completion-" + std::to_string(::getpid());
  {
    std::ofstream script(path);
    script << trionet::test::run_cli("--completion bash").out
           << "COMP_LINE=\"$1\"; COMP_POINT=${#COMP_LINE}; read -ra COMP_WORDS <<< \"$1\"\n"
              "[[ $1 == *' ' ]] && COMP_WORDS+=('')\n"
              "COMP_CWORD=$((${#COMP_WORDS[@]} - 1)); _trionet; printf '%s\\n' \"${COMPREPLY[@]}\"\n";
  }
  std::string out;
  if (FILE* p = ::popen(("bash " + path + " '" + line + "'").c_str(), "r")) {
    char buffer[4096];
    std::size_t got = 0;
    while ((got = std::fread(buffer, 1, sizeof buffer, p)) > 0) out.append(buffer, got);
    ::pclose(p);
  }
  std::remove(path.c_str());
  return out;
}

TEST(Manual, CompletionCompletesPartsCommandsOptionsAndValues) {
  EXPECT_EQ(complete("trionet ri"), "ring\n");
  EXPECT_EQ(complete("trionet "), "ring\ncan\ngenius\nprofile\n");
  EXPECT_EQ(complete("trionet genius sc"), "scan-time\n");
  EXPECT_EQ(complete("trionet ring decode --p"), "--pcap\n--profile\n");
  EXPECT_EQ(complete("trionet ring encode "), "print\nvar\noffset\nmode\n");
  EXPECT_EQ(complete("trionet genius timing --rate "), "153.6s\n153.6e\n76.8\n38.4\n");
  EXPECT_EQ(complete("trionet genius scan-time --json --rate 7"), "76.8\n");
  EXPECT_EQ(complete("trionet ring join /dev/null --flow r"), "rtscts\n");
  EXPECT_EQ(complete("trionet ring send /dev/null --baud 9600 v"), "var\n");
  EXPECT_EQ(complete("trionet ring simulate ex"), "example1\nexample2\nexample3\nexample3-fixed\n");
  // The shell replaces what follows the ':' of a key word.
  EXPECT_EQ(complete("trionet ring simulate example2 --keys 1:st"), "start\nstop\n");
  EXPECT_NE(complete("trionet can monitor ").find("-\n"), std::string::npos);
  EXPECT_EQ(complete("trionet profile show /etc/host"), complete("trionet profile header /etc/host"));
  EXPECT_NE(complete("trionet profile show /etc/host").find("/etc/hostname\n"), std::string::npos);
}

// The roff of a page without warnings from man (groff -ww), at the width of a terminal.
TEST(Manual, PagesRenderWithoutWarnings) {
  if (std::system("command -v man >/dev/null 2>&1") != 0) GTEST_SKIP() << "man is not installed";
  for (const std::string& page : lines_of(run_cli("--man").out)) {
    SCOPED_TRACE(page);
    const std::string path = "/tmp/trionet-" + std::to_string(::getpid()) + "-" + page + ".1";
    {
      std::ofstream out(path);
      out << run_cli("--man " + page).out;
    }
    const std::string warnings_path = path + ".warnings";
    const int status = std::system(("LC_ALL=C.UTF-8 MANWIDTH=80 man --warnings -l " + path + " >/dev/null 2>" +
                                    warnings_path)
                                       .c_str());
    EXPECT_EQ(status, 0);
    EXPECT_EQ(trionet::test::slurp(warnings_path), "");
    const std::string text = trionet::test::slurp(path);
    for (const char* section : {".SH NAME", ".SH SYNOPSIS", ".SH DESCRIPTION", ".SH OPTIONS", ".SH EXIT STATUS",
                                ".SH FILES", ".SH EXAMPLES", ".SH SEE ALSO"}) {
      EXPECT_NE(text.find(std::string("\n") + section + "\n"), std::string::npos) << section;
    }
    std::remove(path.c_str());
    std::remove(warnings_path.c_str());
  }
  const auto none = run_cli("--man trionet-nothing");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("no man page 'trionet-nothing'"), std::string::npos);
}

// docs/cli.md's exit statuses are the man page's.
TEST(Manual, ExitStatusesAreTheOnesDocsCliMdLists) {
  const std::string page = trionet::test::slurp(std::string(TRIONET_SOURCE_DIR) + "/docs/cli.md");
  const std::size_t at = page.find("- Exit status: ");
  ASSERT_NE(at, std::string::npos);
  std::set<std::string> documented;
  const std::string paragraph = page.substr(at, page.find("\n- ", at + 1) - at);
  for (const std::string& status : all_matches(paragraph, R"(\*\*(\d)\*\*)")) documented.insert(status);
  ASSERT_GE(documented.size(), 4u);
  for (const std::string& page_name : lines_of(run_cli("--man").out)) {
    const std::string man = run_cli("--man " + page_name).out;
    const std::size_t section = man.find(".SH EXIT STATUS\n");
    const std::string statuses = man.substr(section, man.find(".SH", section + 4) - section);
    std::set<std::string> listed;
    for (const std::string& status : all_matches(statuses, R"(\.TP\n\.B (\d+)\n)")) listed.insert(status);
    EXPECT_EQ(joined(listed), joined(documented)) << page_name;
  }
}

// Every example of every page, run in one shell per page (as a reader would type them, in a new directory
// with the tool on PATH), prints what the page prints.
TEST(Manual, ExamplesPrintWhatTheToolPrints) {
  const std::string tool = TRIONET_CLI_PATH;
  const std::string tool_dir = tool.substr(0, tool.rfind('/'));
  std::size_t examples = 0;
  for (const std::string& page_name : lines_of(run_cli("--man").out)) {
    const std::vector<std::string> lines = lines_of(run_cli("--man " + page_name).out);
    char directory[] = "/tmp/trionet-examples-XXXXXX";
    ASSERT_NE(::mkdtemp(directory), nullptr);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (lines[i].rfind("\\f(CW$ ", 0) != 0) continue;
      const std::string command = unroff(lines[i]).substr(2);
      std::string expected;
      for (std::size_t j = i + 1; j < lines.size() && lines[j] != ".fi"; ++j) expected += unroff(lines[j]) + "\n";
      SCOPED_TRACE(page_name + ": " + command);
      ++examples;
      const std::string script = std::string(directory) + "/.command";
      {
        std::ofstream out(script);
        out << "cd " << directory << " && PATH=" << tool_dir << ":$PATH && ln -sf " << tool << " " << directory
            << "/trionet && PATH=" << directory << ":$PATH\n"
            << command << "\n";
      }
      std::string out;
      int status = -1;
      if (FILE* p = ::popen(("bash " + script + " 2>&1 </dev/null").c_str(), "r")) {
        char buffer[4096];
        std::size_t got = 0;
        while ((got = std::fread(buffer, 1, sizeof buffer, p)) > 0) out.append(buffer, got);
        status = ::pclose(p);
      }
      EXPECT_EQ(status, 0);
      EXPECT_EQ(out, expected);
    }
    std::system((std::string("rm -rf ") + directory).c_str());
  }
  EXPECT_GE(examples, 10u);
}

}  // namespace

// docs/cli.md's exit-status table, read from the page and checked against the tool cell by cell: every
// command the tool has has a row, every cell with a number is brought about here (a case below) and gives
// that exit status, with exactly one "trionet: " message whenever it is not 0 or 3.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/live_process.hpp"
#include "support/run_cli.hpp"
#include "support/temp_files.hpp"

namespace {

using trionet::test::temp_file;
using trionet::test::temp_path;
using trionet::test::cli_result;
using trionet::test::pty_pair;
using trionet::test::run_cli;
using trionet::test::run_cli_redirected;
using trionet::test::tool_process;

// ---- the page ----

struct status_table {
  std::vector<std::string> columns;                              // after "command"
  std::map<std::string, std::map<std::string, std::string>> rows;  // command -> column -> cell
};

std::string trimmed(std::string text) {
  const std::size_t first = text.find_first_not_of(" `");
  const std::size_t last = text.find_last_not_of(" `");
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream row(line.substr(1));
  std::string cell;
  while (std::getline(row, cell, '|')) cells.push_back(trimmed(cell));
  if (!cells.empty() && cells.back().empty()) cells.pop_back();
  return cells;
}

// The table under docs/cli.md's "Exit status, command by command": its header row starts "| command |".
status_table read_table() {
  std::ifstream page(std::string(TRIONET_SOURCE_DIR) + "/docs/cli.md");
  status_table table;
  std::string line;
  bool in_table = false;
  while (std::getline(page, line)) {
    if (!in_table) {
      if (line.rfind("| command | success |", 0) != 0) continue;
      in_table = true;
      const std::vector<std::string> header = cells_of(line);
      table.columns.assign(header.begin() + 1, header.end());
      continue;
    }
    if (line.rfind("|---", 0) == 0) continue;
    if (line.empty() || line[0] != '|') break;
    const std::vector<std::string> cells = cells_of(line);
    EXPECT_EQ(cells.size(), table.columns.size() + 1) << line;
    for (std::size_t i = 1; i < cells.size() && i <= table.columns.size(); ++i) {
      table.rows[cells[0]][table.columns[i - 1]] = cells[i];
    }
  }
  return table;
}

// The tool's commands, "ring encode" ..., from its own help.
std::set<std::string> tool_commands() {
  std::set<std::string> commands;
  const auto section = [](const std::string& text, const std::string& title) {
    std::vector<std::string> names;
    const std::size_t at = text.find("\n" + title + ":\n");
    if (at == std::string::npos) return names;
    std::stringstream lines(text.substr(at + title.size() + 3));
    std::string line;
    while (std::getline(lines, line) && line.rfind("  ", 0) == 0) {
      std::stringstream words(line);
      std::string name;
      words >> name;
      names.push_back(name);
    }
    return names;
  };
  for (const std::string& part : section(run_cli("--help").out, "parts")) {
    for (const std::string& command : section(run_cli(part + " --help").out, "commands")) {
      commands.insert(part + " " + command);
    }
  }
  return commands;
}

// ---- bringing each case about ----

// Standard output is a pipe whose reader has gone: the first write fails with EPIPE.
cli_result run_with_closed_output(const std::vector<std::string>& args, const std::string& input = "") {
  const std::string in_path = temp_file("closed.in", input);
  const std::string err_path = temp_path("closed.err");
  int pipe_fds[2];
  cli_result result;
  if (::pipe(pipe_fds) != 0) return result;
  ::close(pipe_fds[0]);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int in = ::open(in_path.c_str(), O_RDONLY);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(in, 0);
    ::dup2(pipe_fds[1], 1);
    ::dup2(err, 2);
    std::vector<char*> argv;
    std::string tool = TRIONET_CLI_PATH;
    argv.push_back(tool.data());
    std::vector<std::string> copy = args;
    for (std::string& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(tool.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(pipe_fds[1]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.err = trionet::test::slurp(err_path);
  std::remove(in_path.c_str());
  std::remove(err_path.c_str());
  return result;
}

// A live command on a pty whose other side closes once the command has the port: the link is lost.
cli_result run_until_the_pty_closes(const std::string& args_after_port, const std::string& command) {
  auto pty = std::make_unique<pty_pair>();
  if (!pty->ok()) return {};
  const std::string err_path = temp_path("lost.err");
  std::vector<std::string> args;
  std::stringstream words(command + " " + pty->slave_path + " " + args_after_port);
  for (std::string w; words >> w;) args.push_back(w);
  tool_process tool(args, err_path);
  std::this_thread::sleep_for(std::chrono::milliseconds(400));  // the tool opens the port
  pty.reset();  // both ends of the pair close: the tool reads EIO
  cli_result result;
  result.exit_code = tool.wait(5000);
  result.out = tool.output();
  result.err = trionet::test::slurp(err_path);
  std::remove(err_path.c_str());
  return result;
}

// Hex text of a character transfer to BASIC address 10 whose text is longer than the decoder holds (256).
std::string over_long_message() {
  std::string hex = "89";
  for (int i = 0; i < 300; ++i) hex += " 41";
  return hex + " 88\n";
}

// Ring frames that give `ring learn crc` exactly one answer: direct variable transfers from the tool itself.
std::string ring_learning_frames() {
  std::string frames;
  const char* values[] = {"1", "-2.5", "99", "1234.5678", "0.001", "-77777", "3.25", "16000"};
  for (int i = 0; i < 8; ++i) {
    frames += run_cli("ring encode var --to 10 --vr " + std::to_string(100 + 37 * i) + " --value " + values[i]).out;
  }
  return frames;
}

// Genius transmissions that give `genius learn crc` exactly one answer.
std::string genius_learning_tokens() {
  std::string tokens;
  for (const char* data : {"5a", "1122", "a1b2c3", "00ff00ff", "0102030405", "9988776655443322"}) {
    tokens += run_cli(std::string("genius encode --from 3 --broadcast ") + data).out;
  }
  return tokens;
}

using case_runner = std::function<cli_result()>;

// How to run a command successfully (shell words after `trionet`, and standard input).
struct invocation {
  std::string args;
  std::string input;
};

// Every command's plain successful run (the live ones on `-` where they can be).
std::map<std::string, invocation> successful_runs() {
  const std::string hello = "91 48 45 4c 4c 4f 90\n";
  return {
      {"ring encode", {"ring encode print --to 11 HI", ""}},
      {"ring decode", {"ring decode", hello}},
      {"ring simulate", {"ring simulate example1 --byte-times 20000", ""}},
      {"ring monitor", {"ring monitor -", "\x91HELLO\x90"}},
      {"ring send", {"ring send - print --to 11 HI", ""}},
      {"ring learn", {"ring learn crc", ring_learning_frames()}},
      {"can encode", {"can encode --from 1 --to 4 --vr 1 --value 2.345", ""}},
      {"can decode", {"can decode", "028#0100000000020D7A\n"}},
      {"can table", {"can table", ""}},
      {"can monitor", {"can monitor -", "(1700000000.123456) can0 028#0100000000020D7A\n"}},
      {"can send", {"can send - --from 1 --to 4 --vr 1 --value 2", ""}},
      {"can node", {"can node - --node 4", "028#0100000000020D7A\nsend 3 7 12.25\nquit\n"}},
      {"genius encode", {"genius encode --from 3 --broadcast 5a", ""}},
      {"genius decode", {"genius decode", "c:23 5a c:75\n"}},
      {"genius timing", {"genius timing --rate 153.6s --after 4 --device 4@0 --device 5@2000", ""}},
      {"genius scan-time", {"genius scan-time --rate 153.6s --device 8", ""}},
      {"genius learn", {"genius learn crc", genius_learning_tokens()}},
      {"genius simulate", {"genius simulate --rate 153.6s --device 4@0 --device 5@2000 --scans 2", ""}},
      {"genius plan", {"genius plan --rate 153.6s --device a@0 --device b@2000", ""}},
      {"profile show", {"profile show", ""}},
      {"profile header", {"profile header", ""}},
  };
}

// Every case of the table that the page gives a number, by "command|column".
std::map<std::string, case_runner> cases() {
  std::map<std::string, case_runner> all;
  const std::map<std::string, invocation> runs = successful_runs();
  for (const auto& [command, run] : runs) {
    const invocation plain = run;
    all[command + "|success"] = [plain] { return run_cli(plain.args, plain.input); };
    all[command + "|bad argument"] = [plain] { return run_cli(plain.args + " --no-such-option", plain.input); };
    all[command + "|unwritable output"] = [plain] { return run_cli_redirected(plain.args + " >/dev/full", plain.input); };
    // Every command reads --profile FILE.
    all[command + "|unreadable input"] = [plain] {
      return run_cli(plain.args + " --profile /nonexistent/profile.json", plain.input);
    };
  }
  // The commands' own inputs, where they have one.
  all["ring decode|unreadable input"] = [] { return run_cli("ring decode --pcap /nonexistent/x.pcapng"); };
  all["ring simulate|unreadable input"] = [] { return run_cli("ring simulate --node mc:/nonexistent/x.bas --node mc"); };
  all["ring monitor|unreadable input"] = [] { return run_cli("ring monitor /nonexistent/ttyX"); };
  all["ring send|unreadable input"] = [] { return run_cli("ring send /nonexistent/ttyX print --to 11 A"); };
  all["ring learn|unreadable input"] = [] { return run_cli("ring learn crc /nonexistent/frames.hex"); };
  all["can decode|unreadable input"] = [] { return run_cli("can decode --pcap /dev/zero"); };
  all["genius decode|unreadable input"] = [] { return run_cli("genius decode --pcap /nonexistent/x.pcapng"); };
  all["genius learn|unreadable input"] = [] { return run_cli("genius learn crc /"); };
  all["profile show|unreadable input"] = [] { return run_cli("profile show /dev/zero"); };
  all["profile header|unreadable input"] = [] { return run_cli("profile header /nonexistent/p.json"); };

  // ring join needs a port: a pty.
  const auto join = [](const std::string& options, const std::string& input, const std::string& redirect = "") {
    pty_pair pty;
    return run_cli_redirected("ring join " + pty.slave_path + " " + options + redirect, input);
  };
  all["ring join|success"] = [join] { return join("--as mc", "quit\n"); };
  all["ring join|bad argument"] = [join] { return join("--as mc --no-such-option", "quit\n"); };
  all["ring join|unreadable input"] = [] { return run_cli("ring join /nonexistent/ttyX --as mc", "quit\n"); };
  all["ring join|unwritable output"] = [join] { return join("--as mc", "quit\n", " >/dev/full"); };

  // ring wire connects endpoints: two new ptys, or one that cannot be opened.
  all["ring wire|success"] = [] { return run_cli("ring wire pty pty", "quit\n"); };
  all["ring wire|bad argument"] = [] { return run_cli("ring wire pty pty --no-such-option", "quit\n"); };
  all["ring wire|unreadable input"] = [] { return run_cli("ring wire /nonexistent/ttyX pty", "quit\n"); };
  all["ring wire|unwritable output"] = [] { return run_cli_redirected("ring wire pty pty >/dev/full", "quit\n"); };
  all["ring wire|lost link"] = [] { return run_until_the_pty_closes("pty", "ring wire"); };

  // The link lost.
  all["ring monitor|lost link"] = [] { return run_until_the_pty_closes("", "ring monitor"); };
  all["ring join|lost link"] = [] { return run_until_the_pty_closes("--as mc", "ring join"); };
  all["ring send|lost link"] = [] { return run_with_closed_output({"ring", "send", "-", "print", "--to", "11", "A"}); };
  all["can send|lost link"] = [] {
    return run_with_closed_output({"can", "send", "-", "--from", "1", "--to", "4", "--vr", "1", "--value", "2"});
  };
  all["can monitor|lost link"] = [] {
    // Over candump text the link is standard input, whose end is a normal end; a lost link is a SocketCAN
    // interface that goes away, which only a vcan interface can show (LiveCan.OverSocketCanOnVcan).
    cli_result skipped;
    skipped.exit_code = -2;
    return skipped;
  };
  all["can node|lost link"] = all["can monitor|lost link"];

  // Limits.
  all["ring decode|limit reached"] = [] { return run_cli("ring decode", over_long_message()); };
  all["ring monitor|limit reached"] = [] {
    return run_cli("ring monitor -", "\x89" + std::string(300, 'A') + "\x88");
  };
  all["ring simulate|limit reached"] = [] { return run_cli("ring simulate example1 --byte-times 100"); };
  all["ring learn|limit reached"] = [] { return run_cli_redirected("ring learn crc --raw </dev/zero"); };
  all["can decode|limit reached"] = [] { return run_cli("can decode", std::string(9000, '1') + "\n"); };
  all["can monitor|limit reached"] = [] { return run_cli("can monitor -", std::string(9000, '1') + "\n"); };
  all["genius decode|limit reached"] = [] { return run_cli("genius decode", std::string(100000, 'q') + "\n"); };
  all["genius learn|limit reached"] = [] { return run_cli_redirected("genius learn crc --raw </dev/zero"); };
  all["genius simulate|limit reached"] = [] {  // nobody sends: no scan before the time bound (s37 item 4)
    return run_cli("genius simulate --rate 153.6s --device 4@0:0 --device 5@10:0 --scans 2");
  };
  const auto big_profile = [] {
    return temp_file("big.json", "{\"trionet_profile\": 1, \"name\": \"" + std::string(1 << 20, 'x') + "\"}");
  };
  all["profile show|limit reached"] = [big_profile] {
    const std::string path = big_profile();
    cli_result r = run_cli("profile show " + path);
    std::remove(path.c_str());
    return r;
  };
  all["profile header|limit reached"] = [big_profile] {
    const std::string path = big_profile();
    cli_result r = run_cli("profile header " + path);
    std::remove(path.c_str());
    return r;
  };

  // Checks that fail, learning that finds no single answer.
  all["ring learn|check failed"] = [] { return run_cli("ring learn crc", "91 48 49 90\n"); };
  all["genius learn|check failed"] = [] { return run_cli("genius learn crc", "c:01 02 11 c:5d\n"); };
  all["genius plan|check failed"] = [] {  // SBAs given whose margins are too small (s37 item 6)
    return run_cli("genius plan --rate 153.6s --device A@0=0 --device B@2000=1 --device C@0=2 --check");
  };
  all["genius timing|check failed"] = [] {
    return run_cli("genius timing --rate 153.6s --after 4 --device 4@0 --device 5@2000 --device 6@0 --check");
  };
  all["ring join|check failed"] = [] {
    // --learn-keypad with a "keypad" whose every key sends the same character: no profile can hold that.
    pty_pair pty;
    const std::string out = temp_path("learned.json");
    const std::string err_path = temp_path("learn.err");
    tool_process tool({"ring", "join", pty.slave_path, "--as", "mc", "--learn-keypad", "11", "-o", out}, err_path);
    pty.read_bytes(6, 3000);  // the keypad offset and keypad mode
    const std::string frame = run_cli("ring encode print --to 10 " + std::string(36, 'A')).out;
    std::vector<std::uint8_t> bytes;
    std::stringstream hex(frame);
    for (std::string b; hex >> b;) bytes.push_back(static_cast<std::uint8_t>(std::stoul(b, nullptr, 16)));
    pty.write_all(bytes);
    cli_result r;
    r.exit_code = tool.wait(5000);
    r.err = trionet::test::slurp(err_path);
    std::remove(err_path.c_str());
    std::remove(out.c_str());
    return r;
  };
  return all;
}

// The "trionet: " lines of a run's standard error.
std::size_t messages(const std::string& err) {
  std::size_t count = 0;
  std::stringstream lines(err);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("trionet: ", 0) == 0) ++count;
  }
  return count;
}

TEST(ExitStatusTable, EveryCommandOfTheToolHasARow) {
  const status_table table = read_table();
  ASSERT_FALSE(table.rows.empty()) << "docs/cli.md has no exit-status table";
  for (const std::string& command : tool_commands()) {
    EXPECT_EQ(table.rows.count(command), 1U)
        << "`trionet " << command << "` has no row in docs/cli.md's exit-status table (add one, and its cases "
        << "to tests/cli/exit_status_test.cpp)";
  }
  for (const auto& row : table.rows) {
    EXPECT_EQ(tool_commands().count(row.first), 1U) << "docs/cli.md names a command the tool does not have: "
                                                     << row.first;
  }
}

TEST(ExitStatusTable, EveryCellIsWhatTheToolDoes) {
  const status_table table = read_table();
  const std::map<std::string, case_runner> all = cases();
  std::size_t checked = 0;
  for (const auto& [command, cells] : table.rows) {
    for (const auto& [column, cell] : cells) {
      const std::string key = command + "|" + column;
      if (cell == "-") {
        EXPECT_EQ(all.count(key), 0U) << key << ": the page says it cannot arise, but this test brings it about";
        continue;
      }
      int expected = -1;
      ASSERT_TRUE(cell.size() == 1 && cell[0] >= '0' && cell[0] <= '4') << key << ": '" << cell << "'";
      expected = cell[0] - '0';
      const auto found = all.find(key);
      if (found == all.end()) {
        ADD_FAILURE() << key << " is " << cell << " on the page, but tests/cli/exit_status_test.cpp has no case for it";
        continue;
      }
      const cli_result r = found->second();
      if (r.exit_code == -2) continue;  // only SocketCAN shows it: tested where a vcan interface can be made
      ++checked;
      EXPECT_EQ(r.exit_code, expected) << key << "\nstdout: " << r.out.substr(0, 400) << "\nstderr: " << r.err;
      if (expected == 1 || expected == 2) {
        EXPECT_EQ(messages(r.err), 1U) << key << ": one message\n" << r.err;
      }
      if (column == "bad argument") {
        EXPECT_EQ(r.out, "") << key;
      }
    }
  }
  EXPECT_GE(checked, 90U) << "the table's cases were not found";
}

}  // namespace

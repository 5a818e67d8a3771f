// `trionet ring simulate ... --interactive`: the simulated ring in real time, its keypads' displays drawn live
// and the keyboard as the selected keypad's keys (keypad_terminal.hpp). Without a terminal on standard input,
// key words are read from it instead ("1:up", "2:7", "wait=MS", "quit"; the run ends when they are done) and
// display changes are printed.
#include <poll.h>
#include <unistd.h>

#include <cstdio>
#include <deque>
#include <string>
#include <vector>

#include "cli.hpp"
#include "keypad_terminal.hpp"
#include "live.hpp"
#include "ring_cli.hpp"
#include "ring_network.hpp"

namespace trionet::cli {
namespace {

std::string keypad_status(const host::node_report& r) {
  if (!r.network_mode) return "local mode (no keypad offset yet)";
  return "network mode: keys to BASIC " + std::to_string(r.offset + 9) + " (" + std::to_string(r.offset) +
         (r.offset == 1 ? " hop)" : " hops)");
}

}  // namespace

int ring_simulate_interactive(host::ring_network& net, double bit_rate, std::uint64_t max_byte_times) {
  std::vector<std::size_t> keypad_nodes;  // ring positions of the keypads, in keypad order
  for (std::size_t i = 1; i <= net.size(); ++i) {
    if (net.report(i).what == host::node_spec::kind::keypad) keypad_nodes.push_back(i);
  }
  raw_terminal terminal;
  const bool interactive = terminal.enter(STDIN_FILENO);
  terminal_screen screen;
  std::deque<std::string> recent;
  bool changed = true;
  net.on_event([&](const host::network_event& e) {
    if (e.kind == host::event_kind::message || e.kind == host::event_kind::frame_error) return;
    if (e.kind == host::event_kind::display) {
      changed = true;
      if (!interactive) {
        std::printf("t=%llu node %zu display |%s|%s|\n", static_cast<unsigned long long>(e.time), e.node,
                    e.display[0].c_str(), e.display[1].c_str());
        std::fflush(stdout);
      }
      return;
    }
    const std::string line = "t=" + std::to_string(e.time) + " node " + std::to_string(e.node) + " " + e.text;
    if (!interactive) {
      std::printf("%s\n", line.c_str());
      std::fflush(stdout);
      return;
    }
    recent.push_back(line);
    if (recent.size() > 5) recent.pop_front();
    changed = true;
  });

  live::signal_watch signals;
  live::line_reader input(STDIN_FILENO);
  key_decoder keys;
  key_script script;
  std::size_t selected = 0;  // index into keypad_nodes
  bool quit = false;
  const std::uint64_t started = live::now_ns();
  const std::uint64_t start_time = net.now();
  std::string error;
  const auto complain = [&](const std::string& why) {
    const std::string line = "error: " + why;
    if (interactive) {
      recent.push_back(line);
      if (recent.size() > 5) recent.pop_front();
      changed = true;
    } else {
      std::printf("%s\n", line.c_str());
    }
  };
  const auto press = [&](std::size_t keypad, const std::string& word) {
    if (!net.press(keypad, word, error)) complain(error);
  };
  const auto script_word = [&](const std::string& word) {
    long long number = 0;
    if (word == "quit") {
      quit = true;
    } else if (const std::size_t colon = word.find(':'); colon != std::string::npos &&
                                                        parse_integer(word.substr(0, colon), 1, 1000, number)) {
      press(static_cast<std::size_t>(number), word.substr(colon + 1));
    } else {
      press(selected + 1, word);
    }
  };

  while (!quit && !live::signal_watch::stop_requested()) {
    // The ring runs in real time: as many byte-times as the wall clock has had since the start.
    const double elapsed = static_cast<double>(live::now_ns() - started) / 1e9;
    const auto due = start_time + static_cast<std::uint64_t>(elapsed * bit_rate / 10.0);
    for (int i = 0; i < 100000 && net.now() < due && net.now() < max_byte_times; ++i) net.step();
    if (net.now() >= max_byte_times) break;
    if (interactive && screen.resized()) changed = true;
    if (changed && interactive) {
      std::vector<keypad_panel> panels;
      for (std::size_t k = 0; k < keypad_nodes.size(); ++k) {
        const host::node_report r = net.report(keypad_nodes[k]);
        keypad_panel panel;
        panel.title = "keypad " + std::to_string(k + 1) + " (node " + std::to_string(keypad_nodes[k]) + ")";
        panel.lines[0] = r.display.size() > 0 ? r.display[0] : "";
        panel.lines[1] = r.display.size() > 1 ? r.display[1] : "";
        panel.status = keypad_status(r);
        panel.selected = keypad_nodes.size() > 1 && k == selected;
        panels.push_back(panel);
      }
      std::vector<std::string> footer = keyboard_help(screen.size().columns, keypad_nodes.size() > 1);
      footer.push_back("t=" + std::to_string(net.now()) + " byte-times");
      screen.draw(panels, footer, std::vector<std::string>(recent.begin(), recent.end()));
      changed = false;
    }
    pollfd p{STDIN_FILENO, POLLIN, 0};
    if (input.ended()) p.fd = -1;
    if (::poll(&p, 1, 10) > 0 && (p.revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
      if (interactive) {
        for (const std::string& word : keys.read(STDIN_FILENO)) {
          if (word == "quit") {
            quit = true;
          } else if (word == "next") {
            selected = keypad_nodes.empty() ? 0 : (selected + 1) % keypad_nodes.size();
            changed = true;
          } else {
            press(selected + 1, word);
          }
        }
      } else {
        input.read_some();
        std::string line;
        while (input.next(line)) script.add_line(line);
      }
    }
    std::string word;
    bool bad_wait = false;
    while (!quit && script.next(live::now_ns(), word, bad_wait)) {
      if (bad_wait) {
        complain(word + ": wait=MS takes 0..3600000");
      } else {
        script_word(word);
      }
    }
    // Key words from a file or pipe: the run ends when they are done.
    if (!interactive && input.ended() && script.done(live::now_ns())) quit = true;
  }
  screen.leave();
  terminal.restore();
  for (std::size_t k = 0; k < keypad_nodes.size(); ++k) {
    const host::node_report r = net.report(keypad_nodes[k]);
    std::printf("keypad %zu at t=%llu: |%s|%s|\n", k + 1, static_cast<unsigned long long>(net.now()),
                r.display.size() > 0 ? r.display[0].c_str() : "", r.display.size() > 1 ? r.display[1].c_str() : "");
  }
  return exit_ok;
}

}  // namespace trionet::cli

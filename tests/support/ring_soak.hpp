// A fault-injection soak of the fibre ring (docs/protocol.md 1.5, 1.10): rings of Motion Coordinators and
// keypads in network mode carry a mix of PRINT#, SEND and lapping messages while the links flip bits, drop
// bytes or are cut; then the faults stop and every node sends probes. Every message is followed through the
// ring, so that each one's fate is known:
//
//   delivered intact      at its destination, exactly as sent
//   delivered corrupted   at its destination, changed on the way (a character transfer has no CRC)
//   misdelivered          at another node, or read as another type (the header is not covered by the CRC)
//   misaddressed, refused a direct variable transfer taken whole at another node, whose VR write policy
//                         refused it: each MC accepts only the VRs it owns (disjoint ranges), as a careful
//                         user configures a faulty ring (docs/liveness.md)
//   lost, counted         some node counted it (frame error, CRC error, forwarded message lost, ...)
//   lost, uncounted       no node could see it: every byte of it vanished on a link, or its header was lost
//                         (or arrived with A = 0) and the one error counted went to a neighbouring damaged
//                         message
//   lost, unexplained     none of the above: a defect
//
// How a message is followed: each link's transmitted bytes are cut into segments at headers (a node only
// ever transmits whole or cut-short messages). A segment is a node's own message (its header came from the
// transmit queue: the forward buffer was empty) or the next forwarded one (headers are forwarded in the
// order they arrived). Each counter a node increments while it takes a byte is the doing of the message
// that byte belongs to, or of the message the node had open before it (an interrupted, idle or bad message).
// In a simulator step every node transmits before any receives: a loss a node counts on the byte it takes
// finds the header it sent in that step already gone out.
//
// Episodes are wedged when the probes are not all delivered (and the ring quiet) within `recovery_limit`
// byte-times of the last fault; livelocked if the links were still busy then.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace trionet::soak {

enum class fault_kind { flip, drop, cut };

inline const char* to_string(fault_kind kind) {
  switch (kind) {
    case fault_kind::flip:
      return "flip";
    case fault_kind::drop:
      return "drop";
    case fault_kind::cut:
      return "cut";
  }
  return "?";
}

struct config {
  std::size_t nodes = 5;                  ///< ring size, 2..15
  std::size_t keypads = 1;                ///< how many of them are keypads (at least one MC remains)
  fault_kind kind = fault_kind::cut;      ///< what goes wrong on the links
  double rate = 1e-3;                     ///< flip, drop: chance per byte on every link
  std::uint32_t cut_length = 100;         ///< cut: byte-times a random link is cut, once per episode
  std::uint32_t episodes = 20;            ///< fault phase + recovery phase each
  std::uint32_t fault_byte_times = 1500;  ///< length of the fault phase
  std::uint32_t recovery_limit = 200000;  ///< byte-times after the last fault before an episode is wedged
  double load = 1.0 / 150;                ///< chance per byte-time that an MC sends a message
  double key_rate = 1.0 / 400;            ///< chance per byte-time that a keypad key is pressed
  /// Each MC's VR write policy: false (the soak's default), it accepts only the VRs it owns (16 per MC,
  /// disjoint); true, every VR in its table (the library's default policy), so that a misaddressed transfer
  /// is written.
  bool accept_all_vrs = false;
  std::uint64_t seed = 1;
};

/// The VRs MC `node` owns: every SEND to it writes one of these (16 * node + the sender).
constexpr std::uint16_t owned_vrs_per_node = 16;
/// The soak's VR tables: room for the VRs of 15 nodes.
constexpr std::size_t vr_table_size = 256;

struct report {
  std::uint64_t sent = 0, delivered_intact = 0, delivered_corrupted = 0, misdelivered = 0;
  std::uint64_t lost_counted = 0, lost_vanished = 0, lost_merged = 0, lost_unexplained = 0;
  /// Direct variable transfers written to a VR wrongly, by class (`wrong_vr_writes` is their sum):
  /// misaddressed (intact, at a node that is not its destination, and its write policy accepted it), its
  /// payload changed and the CRC missed it (2^-14 of corruptions), or from no message the soak sent.
  std::uint64_t wrong_vr_writes = 0, wrong_vr_misaddressed = 0, wrong_vr_crc_missed = 0, wrong_vr_no_message = 0;
  /// Direct variable transfers taken whole at a node that is not their destination and refused by its write
  /// policy: counted there (`variables_refused`), undetectable to the protocol (docs/protocol.md 1.3: the
  /// header and end of message are outside the CRC).
  std::uint64_t misaddressed_refused = 0;
  /// Writes the policy refused whose payload was not the one sent (the CRC missed a corruption): counted.
  std::uint64_t corrupted_refused = 0;
  /// Writes refused to their own destination: a defect of the soak's policy.
  std::uint64_t owned_refused = 0;
  std::uint64_t wedged = 0, livelocked = 0, episodes = 0;
  std::uint64_t probes = 0, probes_delivered = 0;
  std::uint64_t faults = 0;  ///< bytes flipped, dropped or cut
  /// Headers that left a node while the bookkeeping had no message for them: a defect of the soak itself.
  std::uint64_t untracked_headers = 0;
  /// Per episode, byte-times from the last fault until every node that had a message open then was out of
  /// it (0: none had).
  std::vector<std::uint64_t> open_closed;
  /// Per episode, byte-times from the last fault to the last error any node counted (0: none after it): when
  /// the last damaged message, wherever it was then, had been seen and ended.
  std::vector<std::uint64_t> damage_cleared;
  /// Per episode, byte-times from the end of the fault phase (when the probes are sent) until every probe was
  /// delivered and the ring was quiet.
  std::vector<std::uint64_t> probes_done;
  std::string first_problem;  ///< what the first wedge, livelock, wrong write, unexplained loss or untracked
                              ///< header was
  std::vector<std::string> wrong_writes;  ///< every wrong VR write: where, what, and how its message changed

  std::uint64_t lost() const { return lost_counted + lost_vanished + lost_merged + lost_unexplained; }
  /// Every message has exactly one fate.
  std::uint64_t fates() const {
    return delivered_intact + delivered_corrupted + misdelivered + misaddressed_refused + lost();
  }
};

inline std::uint64_t median(std::vector<std::uint64_t> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
inline std::uint64_t maximum(const std::vector<std::uint64_t>& v) {
  return v.empty() ? 0 : *std::max_element(v.begin(), v.end());
}

/// The liveness bound of docs/protocol.md 1.10: idle time + one longest message + one lap, in byte-times.
inline std::uint64_t recovery_bound(std::size_t nodes) {
  return ring::default_idle_byte_times + ring::default_max_characters + ring::framing_length + nodes;
}

namespace detail {

// The library's default Motion Coordinator. Every PRINT# of the soak is at most `max_text` characters, so it
// is one message, which the bookkeeping below follows as one.
using mc_type = ring::motion_coordinator<>;
constexpr std::size_t max_text = mc_type::max_own_frame - ring::framing_length;
using keypad_type = ring::keypad<>;
constexpr std::size_t no_id = static_cast<std::size_t>(-1);

/// The VR write policy of a soak MC (`vr_table`'s hook): accepts the VRs the node owns, or every one; and
/// remembers the last write it was asked about, so that the harness sees what was written or refused.
struct vr_owner {
  std::uint16_t first = 0, count = 0;
  bool accept_all = false;
  std::uint16_t last_vr = 0;
  std::int64_t last_value = 0;

  static bool policy(void* context, std::uint16_t vr, std::int64_t value) noexcept {
    auto* self = static_cast<vr_owner*>(context);
    self->last_vr = vr;
    self->last_value = value;
    return self->accept_all || (vr >= self->first && vr - self->first < self->count);
  }
};
using vr_table_type = vr_table<vr_table_size, std::int64_t>;

enum class kind { character, variable, key };

struct message_record {
  std::size_t sender = 0, destination = 0;
  kind type = kind::character;
  std::string text;        // character, key: what must arrive
  std::uint16_t vr = 0;    // variable
  std::int64_t value = 0;  // variable (Q32.32)
  bool probe = false;
  bool delivered = false, corrupted = false, misdelivered = false;
  bool counted = false;      // some node counted an error or a loss for it
  bool vanished = false;     // on some link none of its bytes arrived
  bool header_lost = false;  // on some link its header did not arrive as a header (or arrived with A = 0)
  bool refused = false;      // taken whole at another node and refused by its VR write policy
  // The first change of its header and of its end of message on a link (for the report of a wrong write).
  struct change {
    std::size_t link = no_id;
    std::uint8_t sent = 0, received = 0;
  } header_changed, end_changed;
};

/// What the harness reads off a node between steps.
struct snapshot {
  ring::link_counters link{};
  std::uint32_t frame_errors = 0, crc_errors = 0, overflows = 0, ignored = 0, characters = 0, variables = 0,
                refused = 0, displayed = 0;
  std::size_t backlog = 0;
};

struct node_state {
  bool keypad = false;
  std::unique_ptr<vr_owner> owner;
  std::unique_ptr<vr_table_type> vr;
  std::unique_ptr<mc_type> mc;
  std::unique_ptr<keypad_type> pad;
  std::deque<std::size_t> own;                                 // own wire messages, in queue order
  std::deque<std::pair<std::uint64_t, std::size_t>> forwards;  // (serial, id) of headers to forward
  std::uint64_t serial = 0;                                    // of the message being forwarded now
  std::size_t forward_id = no_id;                              // the message being forwarded now
  bool local_open = false;                                     // a message for this node is open
  std::size_t local_id = no_id;
  snapshot before;
  // The segment on this node's outgoing link.
  std::size_t tx_id = no_id;
  std::size_t tx_sent = 0, tx_delivered = 0;
  bool tx_header_ok = true;

  byte_port& port() { return keypad ? static_cast<byte_port&>(*pad) : static_cast<byte_port&>(*mc); }

  snapshot take() const {
    snapshot s;
    if (keypad) {
      s.link = pad->forwarding_counters();
      const auto& c = pad->counters();
      s.frame_errors = c.frame_errors;
      s.crc_errors = c.crc_errors;
      s.ignored = c.variables_ignored + c.dropped_in_local_mode;
      s.displayed = c.display_messages;
      s.backlog = pad->forward_backlog();
    } else {
      s.link = mc->forwarding_counters();
      const auto& c = mc->counters();
      s.frame_errors = c.frame_errors;
      s.crc_errors = c.crc_errors;
      s.overflows = c.receive_overflows;
      s.ignored = c.keypad_messages_ignored + c.variables_out_of_range + c.variables_value_out_of_range;
      s.characters = c.character_messages;
      s.variables = c.variables_written;
      s.refused = c.variables_refused;
      s.backlog = mc->forward_backlog();
    }
    return s;
  }
};

class harness {
 public:
  explicit harness(const config& cfg) : cfg_(cfg), rng_(cfg.seed), sim_(ring::default_idle_byte_times) {
    build();
  }

  report run() {
    setup_keypads();
    for (std::uint32_t e = 0; e < cfg_.episodes; ++e) episode();
    return report_;
  }

 private:
  // ---- the ring ----

  void build() {
    std::vector<bool> is_keypad(cfg_.nodes, false);
    std::size_t placed = 0;
    while (placed < cfg_.keypads && placed + 1 < cfg_.nodes) {
      const std::size_t at = 1 + rng_() % (cfg_.nodes - 1);  // node 0 stays an MC
      if (!is_keypad[at]) {
        is_keypad[at] = true;
        ++placed;
      }
    }
    nodes_.resize(cfg_.nodes);
    for (std::size_t i = 0; i < cfg_.nodes; ++i) {
      node_state& n = nodes_[i];
      n.keypad = is_keypad[i];
      if (n.keypad) {
        n.pad = std::make_unique<keypad_type>();
      } else {
        n.owner = std::make_unique<vr_owner>();
        n.owner->first = static_cast<std::uint16_t>(owned_vrs_per_node * i);
        n.owner->count = owned_vrs_per_node;
        n.owner->accept_all = cfg_.accept_all_vrs;
        n.vr = std::make_unique<vr_table_type>(&vr_owner::policy, n.owner.get());
        n.mc = std::make_unique<mc_type>(*n.vr);
        mcs_.push_back(i);
      }
      (void)sim_.add(n.port());
    }
    sim_.set_fault_hook(&harness::fault_for, this);
  }

  std::size_t next_mc_after(std::size_t at) const {
    for (std::size_t k = 1; k <= cfg_.nodes; ++k) {
      const std::size_t j = (at + k) % cfg_.nodes;
      if (!nodes_[j].keypad) return j;
    }
    return at;
  }

  // Fault-free: node 0 sends every keypad its offset (keys go to the next MC along the ring) and waits until
  // all are in network mode.
  void setup_keypads() {
    for (std::size_t i = 0; i < cfg_.nodes; ++i) {
      if (!nodes_[i].keypad) continue;
      const auto hops_to_keypad = static_cast<int>(i);  // node 0 -> node i
      const std::size_t target = next_mc_after(i);
      const int offset_hops = static_cast<int>((target + cfg_.nodes - i) % cfg_.nodes);
      const std::size_t id = new_message(0, i, kind::character);  // tracked as a message like any other
      records_[id].text.clear();
      nodes_[0].own.push_back(id);
      while (nodes_[0].mc->send_keypad_offset(hops_to_keypad + 9, offset_hops + 9) != ring::send_status::ok)
        step();
    }
    for (int t = 0; t < 20000; ++t) {
      step();
      bool all = true;
      for (auto& n : nodes_) all = all && (!n.keypad || n.pad->network_mode());
      if (all && sim_.quiet()) break;
    }
    for (auto& n : nodes_) {
      if (n.keypad && !n.pad->network_mode()) report_.first_problem = "a keypad never entered network mode";
    }
  }

  std::size_t new_message(std::size_t sender, std::size_t destination, kind type) {
    message_record r;
    r.sender = sender;
    r.destination = destination;
    r.type = type;
    records_.push_back(r);
    return records_.size() - 1;
  }

  // ---- traffic ----

  // One message from MC `i`, if its transmit queue has room for it whole: PRINT# (sometimes lapping the
  // ring), or SEND to an MC.
  bool send_from(std::size_t i, bool probe) {
    node_state& n = nodes_[i];
    const std::uint64_t pick = rng_() % 100;
    if (pick < 40 || probe) {  // PRINT# to any node, 1..15 hops (lapping when hops >= ring size)
      const auto hops = static_cast<int>(1 + rng_() % (pick < 15 ? 15 : cfg_.nodes));
      const std::size_t destination = (i + static_cast<std::size_t>(hops)) % cfg_.nodes;
      const std::size_t id = new_message(i, destination, kind::character);
      std::string text = "#" + std::to_string(id) + ":";
      const std::size_t length = 4 + rng_() % (max_text - 3);  // 4 .. max_text
      while (text.size() < length) text += static_cast<char>('A' + rng_() % 26);
      if (n.mc->transmit_free() < text.size() + ring::framing_length) {
        records_.pop_back();
        return false;
      }
      const ring::print_result r = n.mc->print(hops + 9, text.c_str());
      if (r.status != ring::send_status::ok) {
        records_.pop_back();
        return false;
      }
      records_[id].text = text;
      records_[id].probe = probe;
      n.own.push_back(id);
      return true;
    }
    // SEND(n,1,vr,value) to an MC: vr = one the destination owns (16 * destination + the sender), value = the
    // message number.
    const std::size_t destination = mcs_[rng_() % mcs_.size()];
    std::size_t hops = (destination + cfg_.nodes - i) % cfg_.nodes;
    if (hops == 0) hops = cfg_.nodes;
    if (rng_() % 4 == 0 && hops + cfg_.nodes <= 15) hops += cfg_.nodes;  // once round the ring first
    const std::size_t id = new_message(i, destination, kind::variable);
    records_[id].vr = static_cast<std::uint16_t>(owned_vrs_per_node * destination + i);
    records_[id].value = trionet::q32_from_integer(static_cast<std::int32_t>(id));
    if (n.mc->send_variable_q32(static_cast<int>(hops) + 9, records_[id].vr, records_[id].value) !=
        ring::send_status::ok) {
      records_.pop_back();
      return false;
    }
    records_[id].probe = probe;
    n.own.push_back(id);
    return true;
  }

  bool press_on(std::size_t i, bool probe) {
    node_state& n = nodes_[i];
    static constexpr ring::key keys[] = {ring::key::digit_1, ring::key::digit_7, ring::key::up, ring::key::yes,
                                         ring::key::start};
    const ring::key k = keys[rng_() % 5];
    const std::size_t destination = (i + n.pad->offset()) % cfg_.nodes;
    const std::size_t id = new_message(i, destination, kind::key);
    if (n.pad->press(k) != ring::key_status::ok) {
      records_.pop_back();
      return false;
    }
    records_[id].text = std::string(1, static_cast<char>(ring::default_keypad_codes[k]));
    records_[id].probe = probe;
    n.own.push_back(id);
    return true;
  }

  void traffic() {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t i = 0; i < cfg_.nodes; ++i) {
      if (nodes_[i].keypad) {
        if (u(rng_) < cfg_.key_rate) (void)press_on(i, false);
      } else if (u(rng_) < cfg_.load) {
        (void)send_from(i, false);
      }
    }
  }

  // ---- faults ----

  static ring::byte_fault fault_for(void* context, std::size_t link, std::uint64_t time, std::uint8_t) {
    auto* self = static_cast<harness*>(context);
    ring::byte_fault f;
    if (!self->faulting_ || self->cfg_.kind == fault_kind::cut) return f;
    std::uniform_real_distribution<double> u(0.0, 1.0);
    if (u(self->fault_rng_) >= self->cfg_.rate) return f;
    if (self->cfg_.kind == fault_kind::flip) {
      f.flip_mask = static_cast<std::uint8_t>(1u << (self->fault_rng_() % 8));
    } else {
      f.drop = true;
    }
    (void)link;
    self->last_fault_ = time;
    ++self->report_.faults;
    return f;
  }

  // ---- following messages ----

  void step() {
    for (auto& n : nodes_) n.before = n.take();
    const std::uint64_t faults = report_.faults;
    step_bytes_.clear();
    sim_.step(tracer{this});
    // Every node transmitted before any received (simulator.hpp), but the trace reports link by link: a node's
    // own transmitted byte is reported after the byte it received. So first what left every node, then what
    // every node took: a loss that a node counts on the byte it takes then finds a header sent in the same
    // step already gone out (the link cuts that message short, it does not remove it).
    for (const ring::link_byte& b : step_bytes_) sent(b);
    for (const ring::link_byte& b : step_bytes_) {
      if (b.delivered) received(nodes_[(b.link + 1) % cfg_.nodes], b.received, nodes_[b.link].tx_id, b.time);
    }
    if (report_.faults != faults) {  // a fault in this step: which nodes does it find inside a message?
      open_at_fault_.assign(nodes_.size(), false);
      for (std::size_t i = 0; i < nodes_.size(); ++i) open_at_fault_[i] = nodes_[i].port().in_message();
      open_closed_at_ = sim_.now();
    } else {
      for (std::size_t i = 0; i < open_at_fault_.size(); ++i) {
        if (open_at_fault_[i] && !nodes_[i].port().in_message()) {
          open_at_fault_[i] = false;
          open_closed_at_ = sim_.now();
        }
      }
    }
  }

  struct tracer {
    harness* h;
    void operator()(const ring::link_byte& b) const { h->step_bytes_.push_back(b); }
    void operator()(const ring::line_idle_event& e) const { h->on_idle(e); }
  };

  // A byte left node `b.link`: a header starts the next segment on its link.
  void sent(const ring::link_byte& b) {
    node_state& tx = nodes_[b.link];
    if (ring::classify(b.sent) == ring::byte_class::header) {
      close_segment(tx);
      // Between messages the forward buffer goes first: a header sent while it held bytes came from it.
      tx.tx_id = no_id;
      if (tx.before.backlog > 0) {
        if (!tx.forwards.empty()) {
          tx.tx_id = tx.forwards.front().second;
          tx.forwards.pop_front();
        }
      } else if (!tx.own.empty()) {
        tx.tx_id = tx.own.front();
        tx.own.pop_front();
      }
      if (tx.tx_id == no_id) {
        ++report_.untracked_headers;
        problem("a header left node " + std::to_string(b.link) + " with no message");
      }
      tx.tx_sent = tx.tx_delivered = 0;
      // A header that arrives with A = 0 is no message's header either: the next node skips that message, and
      // if it had a message open it counts one error (`interrupted`) for the two.
      tx.tx_header_ok = b.delivered && ring::classify(b.received) == ring::byte_class::header &&
                        ring::type_of(b.received) == ring::type_of(b.sent) && ring::hops_of(b.received) != 0;
    }
    ++tx.tx_sent;
    if (b.delivered) ++tx.tx_delivered;
    if (tx.tx_id != no_id && b.delivered && b.sent != b.received) {
      message_record& m = records_[tx.tx_id];
      const ring::byte_class c = ring::classify(b.sent);
      message_record::change* changed = c == ring::byte_class::header           ? &m.header_changed
                                        : c == ring::byte_class::end_of_message ? &m.end_changed
                                                                                : nullptr;
      if (changed != nullptr && changed->link == no_id) *changed = {b.link, b.sent, b.received};
    }
    if (!b.delivered || b.sent != b.received) {
      last_fault_ = b.time;
      if (cfg_.kind == fault_kind::cut) ++report_.faults;
    }
  }

  void close_segment(node_state& tx) {
    if (tx.tx_id == no_id) return;
    message_record& m = records_[tx.tx_id];
    if (tx.tx_sent > 0 && tx.tx_delivered == 0) m.vanished = true;
    if (!tx.tx_header_ok) m.header_lost = true;
    tx.tx_id = no_id;
  }

  void count_for(std::size_t id, std::uint64_t time) {
    if (id != no_id) records_[id].counted = true;
    last_error_ = time;
  }

  // Node `n` took byte `byte`, which belongs to message `id` on the way in.
  void received(node_state& n, std::uint8_t byte, std::size_t id, std::uint64_t time) {
    const snapshot now = n.take();
    const snapshot& was = n.before;
    const bool header = ring::classify(byte) == ring::byte_class::header;
    // Forwarding: a forwarded header joins the forward queue; a lost one leaves it if none of it went out.
    if (now.link.messages_forwarded != was.link.messages_forwarded) {
      n.forwards.emplace_back(++n.serial, id);
      n.forward_id = id;
    }
    if (now.link.forwards_lost != was.link.forwards_lost || now.link.forwards_cut != was.link.forwards_cut) {
      count_for(n.forward_id, time);
      if (!n.forwards.empty() && n.forwards.back().first == n.serial) n.forwards.pop_back();
    }
    if (now.link.messages_dropped != was.link.messages_dropped) count_for(id, time);
    // The node's own decoder: errors and deliveries belong to the message it had open, or to this one.
    const bool was_open = n.local_open;
    const std::size_t open_id = was_open ? n.local_id : id;
    // A header with A = 1 opens a message for the node; any other header ends it, and so does an end of
    // message (while one is open for the node, nothing passes through it, so every end of message is its).
    if (header && ring::hops_of(byte) == 1) {
      n.local_open = true;
      n.local_id = id;
    } else if (header || ring::classify(byte) == ring::byte_class::end_of_message) {
      n.local_open = false;
    }
    if (now.frame_errors != was.frame_errors || now.crc_errors != was.crc_errors ||
        now.overflows != was.overflows || now.ignored != was.ignored) {
      count_for(open_id, time);
    }
    if (now.characters != was.characters) deliver_characters(n, open_id);
    if (now.variables != was.variables) deliver_variable(n, open_id);
    if (now.refused != was.refused) refused_variable(n, open_id, time);
    if (now.displayed != was.displayed) deliver_display(n, open_id);
  }

  void on_idle(const ring::line_idle_event& e) {
    node_state& n = nodes_[(e.link + 1) % cfg_.nodes];
    const snapshot now = n.take();
    if (now.link.forwards_ended_idle != n.before.link.forwards_ended_idle) count_for(n.forward_id, e.time);
    if (now.frame_errors != n.before.frame_errors) count_for(n.local_open ? n.local_id : no_id, e.time);
    n.local_open = false;
    ++idle_events_;
  }

  std::size_t index_of(const node_state& n) const { return static_cast<std::size_t>(&n - nodes_.data()); }

  void deliver_characters(node_state& n, std::size_t id) {
    std::string got;
    while (auto c = n.mc->get(4)) got += static_cast<char>(c.value);
    if (id == no_id) return;
    message_record& m = records_[id];
    if (m.delivered) return;
    m.delivered = true;
    m.misdelivered = m.destination != index_of(n) || m.type == kind::variable;
    m.corrupted = !m.misdelivered && got != m.text;
  }

  // The write node `n`'s policy was last asked about is message `id`'s payload, as sent.
  bool payload_intact(const node_state& n, std::size_t id) const {
    return id != no_id && records_[id].type == kind::variable && records_[id].vr == n.owner->last_vr &&
           records_[id].value == n.owner->last_value;
  }

  // What a wrong write or refusal was: the write, and how the message's header and end of message changed.
  std::string describe_write(const node_state& n, std::size_t id) const {
    std::string s = "at node " + std::to_string(index_of(n)) + ": VR(" + std::to_string(n.owner->last_vr) +
                    ") = " + std::to_string(n.owner->last_value >> 32);
    if (id == no_id) return s + " from no message";
    const message_record& m = records_[id];
    s += " from message " + std::to_string(id) + " (node " + std::to_string(m.sender) + " to node " +
         std::to_string(m.destination) + ", VR(" + std::to_string(m.vr) + ") = " + std::to_string(m.value >> 32);
    for (const auto& [what, c] : {std::pair<const char*, message_record::change>{"header", m.header_changed},
                                  {"end of message", m.end_changed}}) {
      if (c.link == no_id) continue;
      s += std::string("; ") + what + " A " + std::to_string(ring::hops_of(c.sent)) + " -> " +
           std::to_string(ring::hops_of(c.received)) + " on link " + std::to_string(c.link);
    }
    return s + ")";
  }

  void deliver_variable(node_state& n, std::size_t id) {
    const bool intact = payload_intact(n, id);
    const bool right = intact && records_[id].destination == index_of(n);
    if (!right) {  // never hidden: each class counted, and the soak fails
      ++report_.wrong_vr_writes;
      if (id == no_id) {
        ++report_.wrong_vr_no_message;
      } else if (intact) {
        ++report_.wrong_vr_misaddressed;
      } else {
        ++report_.wrong_vr_crc_missed;
      }
      report_.wrong_writes.push_back("seed " + std::to_string(cfg_.seed) + ", episode " +
                                     std::to_string(report_.episodes) + ": wrong VR write " + describe_write(n, id));
      problem("wrong VR write " + describe_write(n, id));
    }
    if (id == no_id) return;
    message_record& m = records_[id];
    if (m.delivered) return;
    m.delivered = true;
    m.misdelivered = !right;
  }

  // Node `n`'s write policy refused a direct variable transfer (it took it whole and valid).
  void refused_variable(node_state& n, std::size_t id, std::uint64_t time) {
    last_error_ = time;
    if (!payload_intact(n, id)) {  // a corruption the CRC missed, refused: a counted loss
      ++report_.corrupted_refused;
      if (id != no_id) records_[id].counted = true;
      return;
    }
    message_record& m = records_[id];
    if (m.destination == index_of(n)) {  // the node owns every VR sent to it
      ++report_.owned_refused;
      problem("a write to its own VR refused " + describe_write(n, id));
    }
    if (m.delivered) return;
    m.delivered = true;
    m.refused = true;
  }

  void deliver_display(node_state& n, std::size_t id) {
    if (id == no_id) return;
    message_record& m = records_[id];
    if (m.delivered) return;
    m.delivered = true;
    m.misdelivered = m.destination != index_of(n) || m.type != kind::character;
    m.corrupted = false;  // a display's text cannot be read back exactly; counted as intact if it arrived
  }

  void problem(const std::string& what) {
    if (report_.first_problem.empty())
      report_.first_problem = "seed " + std::to_string(cfg_.seed) + ", episode " +
                              std::to_string(report_.episodes) + ": " + what;
  }

  // ---- episodes ----

  bool settled() {
    if (!sim_.quiet()) return false;
    for (auto& n : nodes_) {
      if (n.port().in_message() || !n.own.empty() || !n.forwards.empty()) return false;
    }
    for (std::size_t id = first_of_episode_; id < records_.size(); ++id) {
      if (records_[id].probe && !records_[id].delivered) return false;
    }
    return true;
  }

  void episode() {
    first_of_episode_ = records_.size();
    last_fault_ = sim_.now();
    open_at_fault_.clear();
    open_closed_at_ = sim_.now();
    last_error_ = 0;
    // Fault phase: traffic, and the faults.
    faulting_ = true;
    fault_rng_.seed(rng_());
    const std::uint64_t cut_at = cfg_.fault_byte_times > cfg_.cut_length
                                     ? rng_() % (cfg_.fault_byte_times - cfg_.cut_length)
                                     : 0;
    const std::size_t cut_link = rng_() % cfg_.nodes;
    for (std::uint32_t t = 0; t < cfg_.fault_byte_times; ++t) {
      if (cfg_.kind == fault_kind::cut) {
        if (t == cut_at) sim_.cut(cut_link, true);
        if (t == cut_at + cfg_.cut_length) sim_.cut(cut_link, false);
      }
      traffic();
      step();
    }
    if (cfg_.kind == fault_kind::cut) sim_.cut(cut_link, false);
    faulting_ = false;
    const std::uint64_t faults_end = last_fault_;
    // Recovery: every node sends a probe (waiting for room as BASIC's PRINT# does) until all are delivered.
    std::vector<bool> probed(cfg_.nodes, false);
    std::uint64_t done_at = 0;
    bool done = false;
    std::uint64_t busy_bytes = 0;
    const std::uint64_t probes_sent = sim_.now();
    while (sim_.now() - faults_end < cfg_.recovery_limit) {
      for (std::size_t i = 0; i < cfg_.nodes; ++i) {
        if (probed[i]) continue;
        probed[i] = nodes_[i].keypad ? press_on(i, true) : send_from(i, true);
        if (probed[i]) ++report_.probes;
      }
      const std::uint64_t delivered = sim_.bytes_delivered();
      step();
      if (sim_.now() - faults_end > cfg_.recovery_limit - 1000) busy_bytes += sim_.bytes_delivered() - delivered;
      if (std::all_of(probed.begin(), probed.end(), [](bool p) { return p; }) && settled()) {
        done = true;
        done_at = sim_.now();
        break;
      }
    }
    ++report_.episodes;
    if (!done) {
      if (busy_bytes > 500) {
        ++report_.livelocked;
        problem("livelock: probes not delivered and the links still busy");
      } else {
        ++report_.wedged;
        problem("wedged: probes not delivered");
      }
    } else {
      report_.probes_done.push_back(done_at - probes_sent);
      report_.damage_cleared.push_back(last_error_ > faults_end ? last_error_ - faults_end : 0);
      // (the step of the last fault ends at faults_end + 1)
      report_.open_closed.push_back(open_closed_at_ > faults_end + 1 ? open_closed_at_ - faults_end - 1 : 0);
    }
    for (auto& n : nodes_) close_segment(n);
    tally();
  }

  void tally() {
    for (std::size_t id = first_of_episode_; id < records_.size(); ++id) {
      const message_record& m = records_[id];
      ++report_.sent;
      if (m.probe && m.delivered && !m.corrupted && !m.misdelivered) ++report_.probes_delivered;
      if (m.delivered) {
        if (m.refused) {
          ++report_.misaddressed_refused;
        } else if (m.misdelivered) {
          ++report_.misdelivered;
        } else if (m.corrupted) {
          ++report_.delivered_corrupted;
        } else {
          ++report_.delivered_intact;
        }
      } else if (m.counted) {
        ++report_.lost_counted;
      } else if (m.vanished) {
        ++report_.lost_vanished;
      } else if (m.header_lost) {
        ++report_.lost_merged;
      } else {
        ++report_.lost_unexplained;
        problem("message " + std::to_string(id) + " from node " + std::to_string(m.sender) + " to node " +
                std::to_string(m.destination) + " lost and not counted");
      }
    }
  }

  config cfg_;
  std::mt19937_64 rng_;
  std::mt19937_64 fault_rng_;
  ring::simulator<15> sim_;
  std::vector<node_state> nodes_;
  std::vector<std::size_t> mcs_;
  std::vector<bool> open_at_fault_;   // nodes inside a message at the last fault, not yet out of it
  std::uint64_t open_closed_at_ = 0;  // when the last of them got out
  std::vector<message_record> records_;
  std::vector<ring::link_byte> step_bytes_;  // the bytes of the step being run, as traced
  std::size_t first_of_episode_ = 0;
  bool faulting_ = false;
  std::uint64_t last_fault_ = 0, last_error_ = 0, idle_events_ = 0;
  report report_;
};

}  // namespace detail

inline report run(const config& cfg) {
  detail::harness h(cfg);
  return h.run();
}

}  // namespace trionet::soak

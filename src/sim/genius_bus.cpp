// The simulated Genius bus (genius_bus.hpp): the line model, the UART model of each device, and the
// bookkeeping (turns, transmissions, collisions, deliveries) that the tool and the tests read.
#include "genius_bus.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <queue>
#include <random>

#include "trionet/genius/bus_controller.hpp"
#include "trionet/genius/transmission.hpp"

namespace trionet::host {
namespace {

namespace genius = trionet::genius;

// Host capacities: a turn of 31 blocks of 255 bytes, a large delivery queue.
using sim_device = genius::device<31 * 257, 16384, 64, 4>;
using sim_controller = genius::bus_controller<255, 255, sim_device>;

constexpr std::int64_t never = std::numeric_limits<std::int64_t>::max();

std::int64_t ps_of_us(double us) { return std::llround(us * 1e6); }
double us_of_ps(std::int64_t ps) { return static_cast<double>(ps) / 1e6; }

std::uint8_t pattern_byte(std::uint64_t seed, unsigned who, std::uint64_t turn, std::size_t i) {
  std::uint64_t x = seed * 0x9E3779B97F4A7C15ull ^ (std::uint64_t{who} << 40) ^ (turn << 12) ^ i;
  x ^= x >> 31;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 29;
  return static_cast<std::uint8_t>(x >> 24);
}

// A delivery as the device makes it.
struct record {
  genius::delivery_kind kind;
  std::uint8_t sender;
  std::vector<std::uint8_t> data;
};

// What a whole transmission carried, as the library's reference parser reads its words.
struct carried {
  bool valid = false;
  std::uint8_t sender = 0;
  bool broadcast = true;
  std::uint8_t destination = 0;
  struct part {
    bool block;
    std::uint8_t destination;
    std::vector<std::uint8_t> data;
  };
  std::vector<part> parts;
  std::uint32_t blocks_for = 0;  // bit d: a block for SBA d

  // The records device `d` must deliver (as `for_device` gives them): for a device no block or directed data is
  // for, the records every such device delivers, worked out once (most devices of a scan are such devices);
  // else worked out into `scratch`.
  const std::vector<record>& expected_by(std::uint8_t d, std::vector<record>& scratch, std::size_t& count) {
    if (((blocks_for >> (d & 31u)) & 1u) != 0 || (!broadcast && destination == d) || sender == d) {
      count = for_device(d, scratch);
      return scratch;
    }
    if (common_count < 0) common_count = static_cast<int>(for_device(d, common));
    count = static_cast<std::size_t>(common_count);
    return common;
  }

  // The records device `d` must deliver for it (as device.hpp groups them), into `out` (reused); how many.
  std::size_t for_device(std::uint8_t d, std::vector<record>& out) const {
    std::size_t count = 0;
    if (!valid || sender == d) return 0;
    const auto next = [&](genius::delivery_kind kind) -> record& {
      if (count == out.size()) out.emplace_back();
      record& rec = out[count++];
      rec.kind = kind;
      rec.sender = sender;
      rec.data.clear();
      return rec;
    };
    const bool plain_for_me = broadcast || destination == d;
    bool plain_open = false;
    for (const part& p : parts) {
      if (p.block) {
        if (p.destination == d) {
          next(genius::delivery_kind::block).data = p.data;
          plain_open = false;
        }
      } else if (plain_for_me) {
        if (!plain_open) {
          next(broadcast ? genius::delivery_kind::broadcast : genius::delivery_kind::directed);
          plain_open = true;
        }
        out[count - 1].data.insert(out[count - 1].data.end(), p.data.begin(), p.data.end());
      }
    }
    return count;
  }

 private:
  std::vector<record> common;  // expected_by's records of a device no block or directed data is for
  int common_count = -1;       // how many (-1: not worked out yet)
};

// A signal on the line: a device's run of back-to-back characters, or a noise burst.
struct source {
  int device = -1;   // the transmitting device's index; -1 for noise
  double position_ft = 0;
  std::vector<std::int64_t> prop;  // to each receiver
  std::int64_t farthest = 0;       // the largest of them
  std::int64_t start = 0;
  std::vector<std::uint16_t> words;  // 11-bit wire words, back to back from `start`
  std::vector<std::uint8_t> stops;   // per word: stop, unframed or other (below)
  std::vector<std::pair<std::int64_t, std::int64_t>> zeros;  // noise: 0 during [a, b)
  std::int64_t cut = never;  // quiet (1) from here on: power off
  std::int64_t lo = 0;       // the source may be 0 only in [lo, hi) of its own time
  std::int64_t hi = 0;
  std::int64_t zero_end = 0;  // and only before this (a closed run ends with a stop bit, 1)
  bool open = true;          // the device may append more words
  std::int64_t end = never;  // known once closed
  // bookkeeping
  int record_index = -1;  // into result.transmissions (record_turns)
  int stop_index = -1;    // into result.stops, once its Stop is appended
  std::int64_t stop_start = never;
  carried content;
  bool whole = false;
  int group = -1;  // collision group
  std::int64_t id = 0;
  std::size_t followed = 0;  // receivers following it
  // check_losses: each station's state when the transmission began
  struct listener {
    bool powered;
    std::uint64_t cycles;
    std::uint64_t heard;
    std::uint64_t errors;
  };
  std::vector<listener> listeners;
  std::uint32_t heard_by = 0;  // stations that heard it whole (bit per station index)
  std::uint32_t checked = 0;   // stations whose loss check is done
};

// The receivers following a run, in the order they began to: a list through the receivers' indices, so that
// one leaves it in a step (a catch-up at every Stop takes each follower out).
class follower_list {
 public:
  static constexpr std::size_t none = static_cast<std::size_t>(-1);
  bool empty() const { return count_ == 0; }
  std::size_t size() const { return count_; }
  std::size_t front() const { return head_; }
  std::size_t back() const { return tail_; }
  std::size_t next(std::size_t r) const { return links_[r].next; }
  void push_back(std::size_t r) {
    if (r >= links_.size()) links_.resize(r + 1);
    links_[r] = {tail_, none};
    (tail_ == none ? head_ : links_[tail_].next) = r;
    tail_ = r;
    ++count_;
  }
  void erase(std::size_t r) {
    link& l = links_[r];
    (l.prev == none ? head_ : links_[l.prev].next) = l.next;
    (l.next == none ? tail_ : links_[l.next].prev) = l.prev;
    l = {none, none};
    --count_;
  }
  // Calls `f(r)` for each receiver from the last to the first while `more()`; `f` may take `r` out of the list
  // and put it back at its end (it is not visited again).
  template <class More, class F>
  void each_backwards(More more, F f) {
    for (std::size_t r = tail_; r != none && more();) {
      const std::size_t before = links_[r].prev;
      f(r);
      r = before;
    }
  }

 private:
  struct link {
    std::size_t prev = none;
    std::size_t next = none;
  };
  std::vector<link> links_;
  std::size_t head_ = none;
  std::size_t tail_ = none;
  std::size_t count_ = 0;
};

// source::stops: what a word is, for a follower (anything else: 0).
constexpr std::uint8_t stop_word = 1;      // a Stop
constexpr std::uint8_t unframed_word = 2;  // not framed (a framing error, the full way)

struct cut_window {
  double position_ft;
  std::int64_t from;
  std::int64_t to;
};

struct receiver {
  int device = -1;  // -1: a monitor
  double position_ft = 0;
  bool receiving = false;
  std::int64_t idle_since = 0;
  std::int64_t edge = 0;
  std::int64_t who = -1;  // the source whose edge began the character
  std::uint32_t generation = 0;
  std::int64_t scheduled = never;  // the pending start-bit check
  std::int64_t follow = -1;        // following this source (see `follow_from`)
  std::size_t next = 0;            // following: its next character
  std::function<void(double, std::uint16_t)> on_word;
};

struct station_state {
  genius_station spec;
  std::unique_ptr<sim_device> plain;
  std::unique_ptr<sim_controller> controller;
  sim_device* dev = nullptr;
  bool powered = true;
  // The device's timer: when it expires (never: not armed). The devices' timers share one heap entry
  // (state::timers_entry), so a timer re-armed or cancelled costs no heap operation.
  std::int64_t timer_due = never;
  std::int64_t tx_source = -1;  // its open source
  std::uint64_t turn_number = 0;
  double stop_after_us = -1;  // a pending `stop` fault
  double stop_for_us = 0;
  std::int64_t off_for = 0;  // a pending power_off: how long
  // the turn armed after a Stop, for the records
  int turn_stop = -1;
  int turn_slot = -1;
  // loss accounting (check_losses)
  genius_device_report report;
  // its device's counters after the last transmission it was receiving ended (ended())
  genius::device_counters seen{};
};

enum class event_kind : std::uint8_t {
  fault,         // `who`: index into faults
  power_on,      // `who`: station
  power_off,     // `who`: station, `id`: off time in ps
  cut_edge,      // a cut window begins or ends: receivers look again
  start_check,   // `who`: receiver
  deliver,       // `who`: receiver
  catch_up,      // `who`: a following receiver
  timer,         // the devices' timers (state::timers_entry)
  tx_end,        // `who`: station
  loss_check,    // `generation`: index into the loss checks
};

// 16 bytes: the heap moves these most. Ties (same time and priority) pop in an order fixed by the heap's
// operations, so a run is deterministic.
struct event {
  std::uint64_t key;  // time << 3 | priority
  std::uint32_t generation;
  std::uint16_t who;
  event_kind kind;
  std::int64_t time() const { return static_cast<std::int64_t>(key >> 3); }
  bool operator>(const event& o) const { return key > o.key; }
};

std::uint8_t priority_of(event_kind k) {
  switch (k) {
    case event_kind::fault:
    case event_kind::power_off:
    case event_kind::power_on:
    case event_kind::cut_edge:
      return 0;
    case event_kind::start_check:  // a start bit detected at the moment a turn falls due wins (margin == detection)
      return 1;
    case event_kind::deliver:
    case event_kind::catch_up:
      return 2;
    case event_kind::timer:
      return 3;
    case event_kind::tx_end:
      return 4;
    case event_kind::loss_check:
      return 5;
  }
  return 6;
}

}  // namespace

std::string check_genius_bus(const std::vector<genius_station>& stations, const genius_bus_config& config) {
  if (stations.empty()) return "no devices";
  const genius::rate_properties props = genius::properties(config.rate);
  std::uint32_t seen = 0;
  for (const genius_station& s : stations) {
    if (s.sba > genius::max_sba) return "SBA " + std::to_string(s.sba) + " is out of range 0..31";
    if ((seen >> s.sba) & 1u) return "SBA " + std::to_string(s.sba) + " is given twice";
    seen |= 1u << s.sba;
    if (!std::isfinite(s.position_ft) || s.position_ft < 0 || s.position_ft > 1e6)
      return "a position must be 0..1000000 ft";
    if (s.input_bytes > 255 || s.output_bytes > 255) return "inputs and outputs are at most 255 bytes each";
  }
  if (stations.size() > props.max_devices) {
    return std::to_string(stations.size()) + " devices; " + props.name + " allows " +
           std::to_string(props.max_devices);
  }
  if (config.controller >= 0 && ((seen >> config.controller) & 1u) == 0)
    return "the controller's SBA " + std::to_string(config.controller) + " is not one of the devices";
  const double bit_us = genius::bit_time_us(config.rate);
  if (!(config.skip_us >= 0) || config.skip_us > 1000) return "the skip time must be 0..1000 us";
  if (!(config.propagation_us_per_2000ft >= 0) || config.propagation_us_per_2000ft > 1000)
    return "the propagation must be 0..1000 us per 2000 ft";
  if (config.detection_us >= 0 && !(config.detection_us < bit_us))
    return "the detection time must be below one bit time";
  if (config.scans < 1 || config.scans > 1000000) return "scans must be 1..1000000";
  for (const genius_fault& f : config.faults) {
    if (!(f.at_us >= 0) || !(f.duration_us >= 0) || f.at_us > 1e12 || f.duration_us > 1e12)
      return "a fault's time must be 0..1e12 us";
    if ((f.kind == genius_fault_kind::power_off || f.kind == genius_fault_kind::stop) &&
        ((seen >> f.sba) & 1u) == 0)
      return "a fault names SBA " + std::to_string(f.sba) + ", which is not one of the devices";
  }
  return "";
}

struct genius_bus::state {
  genius_bus_config config;
  std::vector<station_state> stations;
  std::vector<receiver> receivers;  // stations first, then monitors
  std::vector<std::unique_ptr<source>> sources;
  std::vector<std::unique_ptr<source>> spare_sources;  // pruned, for new sources to reuse their buffers
  std::int64_t source_base = 0;     // id of sources.front()
  std::vector<source*> active;  // sources that may still be heard
  std::vector<cut_window> cuts;
  std::vector<cut_window> cut_history;  // every cut (check_losses)
  std::priority_queue<event, std::vector<event>, std::greater<event>> events;
  std::uint64_t seq = 0;
  std::int64_t now = 0;
  std::int64_t bit = 0, character = 0, skip = 0, detection = 0, tick = 1, max_prop = 0;
  double ps_per_ft = 0;
  genius::device_timing timing{};
  int opener = -1;  // station index
  std::mt19937_64 rng;
  genius_bus_result result;
  std::function<void(const std::string&)> on_trace;
  std::vector<std::int64_t> recent;  // finished transmissions that a later one may overlap
  bool done = false;
  std::unique_ptr<genius::transmission_parser<8192, 64>> parser;  // reads what each transmission carried
  follower_list followers;
  std::vector<record> expected_scratch;
  std::vector<std::int64_t> loss_checks;  // sources to check (check_losses)
  std::vector<unsigned> loss_attempts;
  std::vector<bool> loss_done;
  std::size_t oldest_check = 0;  // every check before it is done: sources from its on are kept
  std::int64_t faults_end = 0;
  std::vector<std::int64_t> fault_starts;  // every fault's start, in order
  std::size_t pending_stops = 0;           // stations with a `stop` fault yet to take effect
  bool reading_ahead = false;              // read_back_ahead is under way
  std::int64_t limit = never;              // run(): no event after this time is processed
  std::vector<std::uint8_t> scratch;

  // ---- sources ----
  source& src(std::int64_t id) { return *sources[static_cast<std::size_t>(id - source_base)]; }
  // Turns and transmissions are recorded while the scans counted so far are within config.record_scans.
  bool recording() const { return config.record_turns && result.scan_ends_us.size() <= config.record_scans; }

  // A device's propagation times to each receiver, worked out at its first transmission (positions do not move).
  std::vector<std::vector<std::int64_t>> device_prop;
  // `s` in a source object: a pruned one where there is one, whose buffers (words, stops, propagation times)
  // keep their capacity, so that a transmission's characters are appended without allocating.
  std::unique_ptr<source> new_source(source&& s) {
    if (spare_sources.empty()) return std::make_unique<source>(std::move(s));
    std::unique_ptr<source> p = std::move(spare_sources.back());
    spare_sources.pop_back();
    std::vector<std::uint16_t> words = std::move(p->words);
    std::vector<std::uint8_t> stops = std::move(p->stops);
    std::vector<std::int64_t> prop = std::move(p->prop);
    *p = std::move(s);
    words.assign(p->words.begin(), p->words.end());
    stops.assign(p->stops.begin(), p->stops.end());
    prop.assign(p->prop.begin(), p->prop.end());
    p->words.swap(words);
    p->stops.swap(stops);
    p->prop.swap(prop);
    return p;
  }

  std::int64_t add_source(source from) {
    std::unique_ptr<source> made = new_source(std::move(from));
    source& s = *made;
    std::vector<std::int64_t>* known = nullptr;
    if (s.device >= 0) {
      if (device_prop.size() <= static_cast<std::size_t>(s.device)) device_prop.resize(static_cast<std::size_t>(s.device) + 1);
      known = &device_prop[static_cast<std::size_t>(s.device)];
    }
    if (known != nullptr && known->size() == receivers.size()) {
      s.prop.assign(known->begin(), known->end());
    } else {
      s.prop.resize(receivers.size());
      for (std::size_t r = 0; r < receivers.size(); ++r)
        s.prop[r] = std::llround(std::fabs(s.position_ft - receivers[r].position_ft) * ps_per_ft);
      if (known != nullptr) *known = s.prop;
    }
    s.farthest = s.prop.empty() ? 0 : *std::max_element(s.prop.begin(), s.prop.end());
    if (s.device < 0) {
      s.lo = s.zeros.empty() ? 0 : s.zeros.front().first;
      s.hi = s.zeros.empty() ? 0 : std::min(s.cut, s.zeros.back().second);
    } else {
      s.lo = s.start;
      s.hi = std::min(s.cut, s.start + static_cast<std::int64_t>(s.words.size()) * character);
    }
    s.zero_end = s.hi;
    sources.push_back(std::move(made));
    const std::int64_t id = source_base + static_cast<std::int64_t>(sources.size()) - 1;
    sources.back()->id = id;
    active.push_back(sources.back().get());
    return id;
  }

  static std::int64_t source_end(const source& s, std::int64_t character_ps) {
    if (s.device < 0) return std::min(s.cut, s.zeros.empty() ? s.start : s.zeros.back().second);
    return std::min(s.cut, s.start + static_cast<std::int64_t>(s.words.size()) * character_ps);
  }

  // Level of a source at its own time `t`.
  bool level(const source& s, std::int64_t t) const {
    if (t >= s.cut) return true;
    if (s.device < 0) {
      auto it = std::upper_bound(s.zeros.begin(), s.zeros.end(), std::make_pair(t, never));
      if (it == s.zeros.begin()) return true;
      --it;
      return !(t >= it->first && t < it->second);
    }
    if (t < s.start) return true;
    const std::int64_t rel = t - s.start;
    const std::int64_t k = rel / character;
    if (k >= static_cast<std::int64_t>(s.words.size())) return true;
    const std::int64_t b = (rel - k * character) / bit;
    return ((s.words[static_cast<std::size_t>(k)] >> b) & 1u) != 0;
  }

  // The first 1 -> 0 edge of a source at its own time >= t.
  std::int64_t next_edge(const source& s, std::int64_t t) const {
    if (s.device < 0) {
      auto it = std::lower_bound(s.zeros.begin(), s.zeros.end(), std::make_pair(t, std::int64_t{0}));
      if (it == s.zeros.end() || it->first >= s.cut) return never;
      return it->first;
    }
    if (t <= s.start) return s.start < s.cut ? s.start : never;
    const std::int64_t total = 11 * static_cast<std::int64_t>(s.words.size());
    std::int64_t j = (t - s.start + bit - 1) / bit;
    for (; j < total; ++j) {
      const auto word = static_cast<std::size_t>(j / 11);
      const auto b = static_cast<unsigned>(j % 11);
      const bool now_bit = ((s.words[word] >> b) & 1u) != 0;
      const bool before = b == 0 ? true : ((s.words[word] >> (b - 1)) & 1u) != 0;  // a stop bit precedes
      if (before && !now_bit) {
        const std::int64_t e = s.start + j * bit;
        return e < s.cut ? e : never;
      }
    }
    return never;
  }

  bool blocked(const source& s, const receiver& r, std::int64_t t) const {
    for (const cut_window& c : cuts) {
      if (t >= c.from && t < c.to && ((s.position_ft < c.position_ft) != (r.position_ft < c.position_ft)))
        return true;
    }
    return false;
  }

  bool line(std::size_t r, std::int64_t t) const {
    const receiver& rc = receivers[r];
    for (const source* sp : active) {
      const source& s = *sp;
      const std::int64_t at = t - s.prop[r];
      if (at < s.lo || at >= s.hi) continue;
      if (!level(s, at) && (cuts.empty() || !blocked(s, rc, t))) return false;
    }
    return true;
  }

  // True when no source but `who` can be 0 at receiver `r` during [from, to), and no cut is open then.
  bool alone(std::size_t r, std::int64_t who, std::int64_t from, std::int64_t to) const {
    for (const cut_window& c : cuts) {
      if (c.from < to && from < c.to) return false;
    }
    for (const source* sp : active) {
      const source& s = *sp;
      if (s.id == who) continue;
      if (s.lo + s.prop[r] < to && from < s.zero_end + s.prop[r]) return false;
    }
    return true;
  }

  // True when no source can be 0 at receiver `r` from `t` on and no cut is open: the line has no falling edge
  // there (until a source appends characters, which notifies the receivers).
  bool quiet_after(std::size_t r, std::int64_t t) const {
    if (!cuts.empty()) return false;
    for (const source* sp : active) {
      if (sp->zero_end + sp->prop[r] > t) return false;
    }
    return true;
  }

  // The first 0 -> 1 edge of a source at its own time > `t`, where it is 0 at `t`.
  std::int64_t next_rise(const source& s, std::int64_t t) const {
    if (s.device < 0) {
      auto it = std::upper_bound(s.zeros.begin(), s.zeros.end(), std::make_pair(t, never));
      return std::min(s.cut, it == s.zeros.begin() ? t + 1 : std::prev(it)->second);
    }
    const std::int64_t total = 11 * static_cast<std::int64_t>(s.words.size());
    std::int64_t j = (t - s.start) / bit + 1;
    for (; j < total; ++j) {
      if (((s.words[static_cast<std::size_t>(j / 11)] >> (j % 11)) & 1u) != 0) break;
    }
    return std::min(s.cut, s.start + j * bit);
  }

  // What end_of_low found, per receiver: the line was 0 throughout [from, to) there. Sources added or words
  // appended only add 0s, so it stays true until a cut or a power-off takes a 0 away (stale_low_ends). A
  // source pruned (over, out of `active`) was 0 there all the same: it is kept (else a receiver idle since
  // before the prune would walk the stretch again at each look: quadratic in its length).
  struct low_stretch {
    std::int64_t from = 0;
    std::int64_t to = 0;
  };
  mutable std::vector<low_stretch> lows;
  mutable std::uint64_t line_steps = 0;  // end_of_low's steps (genius_bus_result::line_steps)

  void stale_low_ends() { lows.assign(lows.size(), low_stretch{}); }

  // The first time >= `t` at which the line at receiver `r` is 1. Each step jumps to where the last of the
  // sources 0 there rises, so the work is linear in the edges passed over, however many sources overlap
  // (looking at every source's falling edge for one where all are 1 is exponential in that number).
  std::int64_t end_of_low(std::size_t r, std::int64_t t) const {
    const receiver& rc = receivers[r];
    if (lows.size() != receivers.size()) lows.assign(receivers.size(), low_stretch{});
    low_stretch& known = lows[r];
    std::int64_t from = t;
    std::int64_t u = t;
    if (known.from <= t && t < known.to) {
      from = known.from;
      u = known.to;
    }
    for (;;) {
      ++line_steps;
      std::int64_t until = u;
      for (const source* sp : active) {
        const source& s = *sp;
        const std::int64_t at = u - s.prop[r];
        if (at < s.lo || at >= s.hi || level(s, at)) continue;
        if (!cuts.empty() && blocked(s, rc, u)) continue;
        std::int64_t rise = next_rise(s, at) + s.prop[r];
        for (const cut_window& c : cuts) {  // heard here only until a cut comes between
          if (c.from > u && c.from < rise && ((s.position_ft < c.position_ft) != (rc.position_ft < c.position_ft)))
            rise = c.from;
        }
        until = std::max(until, rise);
      }
      if (until == u) break;
      u = until;
      if (known.from <= u && u < known.to) u = known.to;  // (a walk begun before what is known)
    }
    if (u > from) known = low_stretch{from, u};
    return u;
  }

  // The first falling edge of the line at receiver `r` at or after `t`; `who` the source that made it.
  std::int64_t line_edge(std::size_t r, std::int64_t t, std::int64_t& who) const {
    std::int64_t from = t;
    for (int guard = 0; guard < 100000; ++guard) {
      // A falling edge at `e` needs the line 1 at e - 1: none before the line is first 1.
      const std::int64_t high = end_of_low(r, from > 0 ? from - 1 : from);
      from = std::max(from, high + 1);
      std::int64_t best = never;
      std::int64_t best_id = -1;
      for (const source* sp : active) {
        const source& s = *sp;
        const std::int64_t e = next_edge(s, from - s.prop[r]);
        if (e == never) continue;
        const std::int64_t at = e + s.prop[r];
        if (at < best) {
          best = at;
          best_id = s.id;
        }
      }
      for (const cut_window& c : cuts) {  // a 0 from beyond a cut that ends
        if (c.to >= from && c.to < best && line(r, c.to - 1) && !line(r, c.to)) {
          best = c.to;
          best_id = -1;
        }
      }
      if (best == never) return never;
      if (best > 0 && line(r, best - 1) && !line(r, best)) {
        // Of the sources that fall at that moment, the one heard here (not behind a cut, 0 now).
        who = best_id;
        for (const source* sp : active) {
          const source& s = *sp;
          const std::int64_t at = best - s.prop[r];
          if (next_edge(s, at) == at && !level(s, at) && (cuts.empty() || !blocked(s, receivers[r], best))) {
            who = s.id;
            break;
          }
        }
        return best;
      }
      from = best + 1;
    }
    return never;
  }

  void schedule(std::int64_t time, event_kind kind, std::uint32_t who, std::uint32_t generation = 0) {
    events.push(event{(static_cast<std::uint64_t>(time) << 3) | priority_of(kind), generation,
                      static_cast<std::uint16_t>(who), kind});
  }

  // The next character of run `id` that begins at receiver `r` after it went idle, if that run alone can be 0
  // there until then (so that it is the line's first falling edge): its edge, else never. `continuing`: the
  // receiver took the run's earlier characters; else only the run's first character is considered.
  std::int64_t run_edge(std::size_t r, std::int64_t id, bool continuing) const {
    if (id < source_base || id - source_base >= static_cast<std::int64_t>(sources.size())) return never;
    const receiver& rc = receivers[r];
    const source& s = *sources[static_cast<std::size_t>(id - source_base)];
    if (s.device < 0) return never;
    const std::int64_t rel = rc.idle_since - s.prop[r] - s.start;
    if (rel >= 0 && !continuing) return never;
    const std::int64_t k = rel < 0 ? 0 : rel / character + 1;
    const std::int64_t next = s.start + k * character;
    // Continuing only in step with the run (the character it took began with the run's own start bit): out of
    // step, the rest of the character under way may hold falling edges before the next one begins.
    if (rel >= 0 && rc.edge != next - character + s.prop[r]) return never;
    if (k < static_cast<std::int64_t>(s.words.size()) && next < s.hi && next + s.prop[r] >= rc.idle_since &&
        alone(r, s.id, rc.idle_since, next + s.prop[r] + 1))
      return next + s.prop[r];
    return never;
  }

  // Receiver `r`, idle since `idle_since`: schedules the start-bit check of the next edge. `fresh`: a run that
  // has just begun (notify), whose first character is likely that edge.
  void look(std::size_t r, std::int64_t fresh = -1) {
    receiver& rc = receivers[r];
    std::int64_t who = -1;
    // The common cases: the next character of the same run, or the first of a new one, alone on the line
    // until it begins.
    // (Both cannot hold: each needs the other run quiet until its own edge.)
    std::int64_t e = fresh >= 0 && fresh != rc.who ? run_edge(r, fresh, false) : never;
    if (e != never) {
      who = fresh;
    } else {
      e = run_edge(r, rc.who, true);
      if (e != never) who = rc.who;
    }
    if (e == never && !quiet_after(r, rc.idle_since)) e = line_edge(r, rc.idle_since, who);
    if (e != never && who >= source_base) {
      const source& s = src(who);
      const std::int64_t rel = e - s.prop[r] - s.start;
      if (s.device >= 0 && rel >= 0 && rel % character == 0 &&
          follow_from(r, s, static_cast<std::size_t>(rel / character)))
        return;
    }
    ++rc.generation;
    rc.scheduled = never;
    if (e == never) return;
    rc.edge = e;
    rc.who = who;
    rc.scheduled = e + detection;
    schedule(rc.scheduled, event_kind::start_check, static_cast<std::uint32_t>(r), rc.generation);
  }

  // A new signal that reaches receiver `r` at `arrival` or later: look again if it may come first.
  void notify(std::int64_t id) {
    const source& s = src(id);
    followers.each_backwards([&] { return s.followed != followers.size(); },
                             [&](std::size_t r) {
                               if (receivers[r].follow != id) unfollow(r);
                             });
    // Every other receiver follows it, and the sender's own is reading back a character: no one to tell.
    if (s.device >= 0 && s.followed + 1 == receivers.size() && receivers[static_cast<std::size_t>(s.device)].receiving)
      return;
    std::int64_t first = s.device < 0 ? (s.zeros.empty() ? never : s.zeros.front().first) : s.start;
    if (s.device >= 0 && !s.words.empty()) first = s.start + (static_cast<std::int64_t>(s.words.size()) - 1) * character;
    if (first == never) return;
    // A run's first character, when every other source fell quiet everywhere on the line before a receiver
    // went idle: it is the line's next falling edge there, and the receiver may follow the run from it (what
    // `look` would find, without looking at each source again for each receiver).
    std::int64_t others_quiet = never;
    if (s.device >= 0 && s.words.size() == 1 && cuts.empty()) {
      others_quiet = 0;
      for (const source* sp : active) {
        if (sp->id != id) others_quiet = std::max(others_quiet, sp->zero_end + sp->farthest);
      }
    }
    for (std::size_t r = 0; r < receivers.size(); ++r) {
      receiver& rc = receivers[r];
      if (rc.receiving || rc.follow >= 0) continue;
      if (rc.device >= 0 && !stations[static_cast<std::size_t>(rc.device)].powered) continue;
      if (first + s.prop[r] + detection >= rc.scheduled) continue;
      if (others_quiet <= rc.idle_since && rc.idle_since < s.start + s.prop[r] && follow_from(r, s, 0, true)) continue;
      look(r, id);
    }
  }

  void prune() {
    const std::int64_t horizon = now - 13 * bit - max_prop - character;
    active.erase(std::remove_if(active.begin(), active.end(),
                                [&](const source* s) { return !s->open && source_end(*s, character) < horizon; }),
                 active.end());
    std::size_t drop = 0;
    for (; sources.size() - drop > 1; ++drop) {
      const source& f = *sources[drop];
      const std::int64_t id = source_base + static_cast<std::int64_t>(drop);
      if (f.open || source_end(f, character) >= horizon) break;
      if (std::find(recent.begin(), recent.end(), id) != recent.end()) break;
      if (oldest_check < loss_checks.size() && id >= loss_checks[oldest_check]) break;
    }
    for (std::size_t k = 0; k < drop && spare_sources.size() < 64; ++k) spare_sources.push_back(std::move(sources[k]));
    sources.erase(sources.begin(), sources.begin() + static_cast<std::ptrdiff_t>(drop));
    source_base += static_cast<std::int64_t>(drop);
    cuts.erase(std::remove_if(cuts.begin(), cuts.end(), [&](const cut_window& c) { return c.to < horizon; }),
               cuts.end());
  }

  void trace(const std::string& line_text) {
    if (!on_trace) return;
    char head[32];
    std::snprintf(head, sizeof head, "%14.3f us  ", us_of_ps(now));
    on_trace(head + line_text);
  }

  // ---- the devices' program side (what an application would do) ----

  void refresh_turn_data(station_state& st) {
    const std::uint64_t turn = st.turn_number++;
    const std::uint64_t t = config.new_data_every_turn ? turn : 0;
    if (st.controller) {
      for (const station_state& other : stations) {
        if (&other == &st || other.spec.output_bytes == 0) continue;
        scratch.resize(other.spec.output_bytes);
        for (std::size_t i = 0; i < scratch.size(); ++i) scratch[i] = pattern_byte(config.seed, 100u + other.spec.sba, t, i);
        (void)st.controller->set_outputs(other.spec.sba, byte_view(scratch.data(), scratch.size()));
      }
      (void)st.controller->publish_outputs();
      return;
    }
    scratch.resize(st.spec.input_bytes);
    for (std::size_t i = 0; i < scratch.size(); ++i) scratch[i] = pattern_byte(config.seed, st.spec.sba, t, i);
    (void)st.dev->set_turn_data(byte_view(scratch.data(), scratch.size()));
  }

  void make_device(station_state& st) {
    if (config.controller == st.spec.sba) {
      st.controller = std::make_unique<sim_controller>(st.spec.sba, timing);
      st.dev = st.controller.get();
    } else {
      st.plain = std::make_unique<sim_device>(st.spec.sba, timing);
      st.dev = st.plain.get();
    }
    st.seen = st.dev->counters();
    refresh_turn_data(st);
  }

  // ---- the link driver of each device ----

  // The devices' timers: one heap entry, at `timers_entry`, no later than the earliest timer due of a powered
  // device that is not following a run (a follower's timer cannot expire before its next start bit: see
  // follow_from; catching up arms it again). An entry at another time than `timers_entry` was overtaken.
  std::int64_t timers_entry = never;
  void timer_armed(std::int64_t due) {
    if (due >= timers_entry) return;
    timers_entry = due;
    schedule(due, event_kind::timer, 0);
  }
  // The timers' entry at `now`: every timer due by now expires, in station order; then the entry moves on to
  // the earliest timer left.
  void timers_due() {
    timers_entry = never;
    for (std::size_t i = 0; i < stations.size(); ++i) {
      station_state& st = stations[i];
      if (st.timer_due > now || !st.powered || receivers[i].follow >= 0) continue;
      st.timer_due = never;
      timer(i);
    }
    std::int64_t next = never;
    for (std::size_t i = 0; i < stations.size(); ++i) {
      const station_state& st = stations[i];
      if (st.powered && receivers[i].follow < 0) next = std::min(next, st.timer_due);
    }
    if (next != never) timer_armed(std::max(next, now));
  }

  void apply(std::size_t i, genius::link_request request, std::int64_t base) {
    station_state& st = stations[i];
    if (request.timer == genius::timer_action::arm) {
      st.timer_due = base + static_cast<std::int64_t>(request.ticks) * tick;
      timer_armed(st.timer_due);
    } else if (request.timer == genius::timer_action::cancel) {
      st.timer_due = never;
    }
    if (!request.transmit) return;
    std::uint16_t word = 0;
    if (!st.dev->transmit(word)) return;
    append(i, genius::wire_word(word));
  }

  void append(std::size_t i, std::uint16_t wire) {
    station_state& st = stations[i];
    std::int64_t id = st.tx_source;
    if (id >= 0) {
      source& s = src(id);
      const std::int64_t end = s.start + static_cast<std::int64_t>(s.words.size()) * character;
      if (end < now) {  // a gap: the run before it is over
        close_source(id);
        id = -1;
      }
    }
    if (id < 0) {
      source s;
      s.device = static_cast<int>(i);
      s.position_ft = st.spec.position_ft;
      s.start = now;
      id = add_source(std::move(s));
      st.tx_source = id;
      ++result.transmissions_started;
      if (recording()) {
        genius_transmission_record tr;
        tr.sba = st.spec.sba;
        tr.start_us = us_of_ps(now);
        src(id).record_index = static_cast<int>(result.transmissions.size());
        result.transmissions.push_back(tr);
      }
      if (on_trace) trace("SBA " + std::to_string(st.spec.sba) + " starts a transmission");
      if (st.stop_after_us >= 0 && us_of_ps(now) >= st.stop_after_us) {
        // The `stop` fault: it goes off half way through its second character.
        st.off_for = ps_of_us(st.stop_for_us);
        faults_end = std::max(faults_end, now + character + character / 2 + st.off_for);
        schedule(now + character + character / 2, event_kind::power_off, static_cast<std::uint32_t>(i));
        st.stop_after_us = -1;
        --pending_stops;
      }
    }
    source& s = src(id);
    const std::int64_t char_start = s.start + static_cast<std::int64_t>(s.words.size()) * character;
    s.words.push_back(wire);
    s.hi = std::min(s.cut, s.start + static_cast<std::int64_t>(s.words.size()) * character);
    s.zero_end = s.hi;  // until the Stop (below)
    const genius::character c = genius::from_uart_word(static_cast<std::uint16_t>(wire >> 1));
    const genius::control_kind kind = c.control ? genius::read_control(c.byte).kind : genius::control_kind::unknown;
    s.stops.push_back((wire & genius::stop_bit_mask) == 0 ? unframed_word : kind == genius::control_kind::stop ? stop_word : 0);
    if (kind == genius::control_kind::stop) {
      s.stop_start = char_start;
      s.zero_end = s.hi - bit;  // nothing follows a Stop: after its stop bit the run is quiet
      note_stop(id);
      for (std::size_t r = followers.front(); r != follower_list::none; r = followers.next(r)) {
        if (receivers[r].follow == id) schedule_catch_up(r);
      }
    }
    // (Reading back ahead, only the last character's end is an event: the ends before it would find the run
    // going on.)
    if (!reading_ahead) schedule(char_start + character, event_kind::tx_end, static_cast<std::uint32_t>(i));
    notify(id);
    if (config.check_losses && s.listeners.empty()) {
      for (const station_state& other : stations) {
        std::uint64_t heard = 0, errors = 0;
        totals(other, heard, errors);
        src(id).listeners.push_back({other.powered, other.report.power_cycles, heard, errors});
      }
    }
  }

  // What a station has heard and every error it has counted, over all its power cycles.
  static void totals(const station_state& st, std::uint64_t& heard, std::uint64_t& errors) {
    const genius::device_counters now = st.dev->counters();
    const genius::device_counters& before = st.report.counters;
    heard = std::uint64_t{before.transmissions_heard} + now.transmissions_heard;
    errors = std::uint64_t{before.framing_errors} + now.framing_errors + before.crc_errors + now.crc_errors +
             before.wire_errors + now.wire_errors + before.lost_transmissions + now.lost_transmissions +
             before.collisions + now.collisions + before.delivery_overflows + now.delivery_overflows +
             before.skipped + now.skipped;
  }

  void loss_check(std::size_t k) {
    const std::int64_t id = loss_checks[k];
    if (id < source_base) return;
    source& t = src(id);
    if (t.group >= 0 || !t.whole || t.listeners.size() != stations.size()) {
      loss_done[k] = true;
      while (oldest_check < loss_done.size() && loss_done[oldest_check]) ++oldest_check;
      return;
    }
    const unsigned attempt = loss_attempts[k]++;
    bool later = false;
    for (std::size_t i = 0; i < stations.size(); ++i) {
      if (((t.checked >> i) & 1u) != 0) continue;
      if (static_cast<int>(i) == t.device) continue;
      const station_state& st = stations[i];
      const source::listener& before = t.listeners[i];
      if (!before.powered || !st.powered || st.report.power_cycles != before.cycles) continue;
      bool cut_off = false;
      for (const cut_window& c : cut_history) {
        if (c.from < t.end + max_prop && t.start < c.to &&
            ((t.position_ft < c.position_ft) != (st.spec.position_ft < c.position_ft)))
          cut_off = true;
      }
      if (cut_off) continue;
      std::uint64_t heard = 0, errors = 0;
      totals(st, heard, errors);
      if (((t.heard_by >> i) & 1u) != 0 || errors != before.errors) {
        ++result.losses_checked;
        t.checked |= 1u << i;
        continue;
      }
      // Still inside what it takes for a transmission (noise may have stretched it): its gap timer will tell.
      if ((st.dev->in_transmission() || receivers[i].receiving) && attempt < 32) {
        later = true;
        continue;
      }
      ++result.losses_checked;
      t.checked |= 1u << i;
      ++result.losses_uncounted;
      if (result.loss_details.size() < 10) {
        result.loss_details.push_back("SBA " + std::to_string(st.spec.sba) + " neither heard nor counted SBA " +
                                      std::to_string(stations[static_cast<std::size_t>(t.device)].spec.sba) +
                                      "'s transmission of " + std::to_string(us_of_ps(t.start)) + " us");
      }
    }
    if (later) {
      schedule(now + character, event_kind::loss_check, 0, static_cast<std::uint32_t>(k));
      return;
    }
    loss_done[k] = true;
    while (oldest_check < loss_done.size() && loss_done[oldest_check]) ++oldest_check;
  }

  // A Stop was put on the bus: what the transmission carried, and a record for the turns it arms.
  void note_stop(std::int64_t id) {
    source& s = src(id);
    if (!parser) parser = std::make_unique<genius::transmission_parser<8192, 64>>();
    parser->reset();
    carried content;
    for (std::size_t k = 0; k < s.words.size(); ++k) {
      const genius::character_result cr = genius::decode_character(s.words[k]);
      const genius::parse_status ps = cr ? parser->push(cr.value) : parser->push_framing_error();
      if (k + 1 == s.words.size() && ps == genius::parse_status::ok) {
        const genius::transmission& t = parser->received();
        content.valid = true;
        content.sender = t.sender;
        content.broadcast = t.broadcast;
        content.destination = t.destination;
        for (const genius::segment& seg : t.segments)
        {
          content.parts.push_back({seg.block, seg.destination, std::vector<std::uint8_t>(seg.data.begin(), seg.data.end())});
          if (seg.block) content.blocks_for |= std::uint32_t{1} << (seg.destination & 31u);
        }
      }
    }
    s.content = std::move(content);
    if (recording()) {
      genius_stop_record rec;
      rec.sender = stations[static_cast<std::size_t>(s.device)].spec.sba;
      rec.end_us = us_of_ps(s.stop_start + character);
      s.stop_index = static_cast<int>(result.stops.size());
      result.stops.push_back(rec);
    }
  }

  void close_source(std::int64_t id) {
    source& s = src(id);
    if (!s.open) return;
    s.open = false;
    if (s.cut == never) s.zero_end = s.hi - bit;  // whole characters: the last bit is a stop bit
    followers.each_backwards([] { return true; },
                             [&](std::size_t r) {
                               if (receivers[r].follow == id) unfollow(r);
                             });
    s.end = source_end(s, character);
    const station_state& st = stations[static_cast<std::size_t>(s.device)];
    s.whole = !s.words.empty() && s.stop_start != never &&
              s.stop_start + character <= s.end;
    // Collisions: overlap anywhere on the line with a transmission already closed.
    for (const std::int64_t other_id : recent) {
      source& o = src(other_id);
      const std::int64_t p = std::llround(std::fabs(s.position_ft - o.position_ft) * ps_per_ft);
      const bool overlap = s.start - p < o.end && o.start < s.end + p;
      if (overlap) merge(id, other_id);
    }
    recent.push_back(id);
    const std::int64_t horizon = now - 2 * max_prop - 2 * character;
    recent.erase(std::remove_if(recent.begin(), recent.end(),
                                [&](std::int64_t r) { return r != id && src(r).end < horizon; }),
                 recent.end());
    if (s.record_index >= 0) {
      genius_transmission_record& tr = result.transmissions[static_cast<std::size_t>(s.record_index)];
      tr.end_us = us_of_ps(s.end);
      tr.characters = s.words.size();
      tr.whole = s.whole;
    }
    if (on_trace) trace("SBA " + std::to_string(st.spec.sba) + (s.whole ? " ends its transmission (" : " stops, cut short (") +
          std::to_string(s.words.size()) + " characters)");
    if (config.check_losses && s.whole) {
      loss_checks.push_back(id);
      loss_attempts.push_back(0);
      loss_done.push_back(false);
      schedule(s.end + max_prop + 2 * character + bit, event_kind::loss_check, 0,
               static_cast<std::uint32_t>(loss_checks.size() - 1));
    }
    if (s.whole && s.device == opener) {
      const double end = us_of_ps(s.stop_start + character);
      if (!result.scan_ends_us.empty()) result.scan_us.push_back(end - result.scan_ends_us.back());
      result.scan_ends_us.push_back(end);
      if (result.scan_ends_us.size() > config.scans) done = true;
    }
  }

  // Collision groups over sources (union by relabelling: groups are small).
  std::vector<std::vector<std::int64_t>> groups;
  void merge(std::int64_t a, std::int64_t b) {
    source& sa = src(a);
    source& sb = src(b);
    if (sa.group >= 0 && sa.group == sb.group) return;
    if (sa.group < 0 && sb.group < 0) {
      sa.group = sb.group = static_cast<int>(groups.size());
      groups.push_back({a, b});
      ++result.collisions;
      result.colliding_transmissions += 2;
      mark_collided(a);
      mark_collided(b);
      if (on_trace) trace("collision: SBA " + std::to_string(stations[static_cast<std::size_t>(sa.device)].spec.sba) +
            " and SBA " + std::to_string(stations[static_cast<std::size_t>(sb.device)].spec.sba));
      return;
    }
    if (sa.group < 0 || sb.group < 0) {
      const int g = sa.group >= 0 ? sa.group : sb.group;
      const std::int64_t loner = sa.group >= 0 ? b : a;
      src(loner).group = g;
      groups[static_cast<std::size_t>(g)].push_back(loner);
      ++result.colliding_transmissions;
      mark_collided(loner);
      return;
    }
    const int keep = sa.group, gone = sb.group;
    for (const std::int64_t id : groups[static_cast<std::size_t>(gone)]) {
      if (id - source_base >= 0) src(id).group = keep;
      groups[static_cast<std::size_t>(keep)].push_back(id);
    }
    groups[static_cast<std::size_t>(gone)].clear();
    --result.collisions;
  }
  void mark_collided(std::int64_t id) {
    const source& s = src(id);
    if (s.record_index >= 0) result.transmissions[static_cast<std::size_t>(s.record_index)].collided = true;
  }

  // ---- receiver events ----

  // ---- what a receiver hands its device ----

  // A start bit confirmed at `at` (the edge at `edge`, made by source `who`).
  genius::link_request device_start_bit(std::size_t i, std::int64_t edge, std::int64_t who, std::int64_t at) {
    station_state& st = stations[i];
    if (st.dev->turn_armed() && st.turn_stop >= 0 && config.record_turns) {
      auto& t = result.stops[static_cast<std::size_t>(st.turn_stop)].turns[static_cast<std::size_t>(st.turn_slot)];
      t.cancelled = true;
      t.arrived_us = us_of_ps(edge);
      t.detected_us = us_of_ps(at);
      t.by = who >= source_base && src(who).device >= 0 ? stations[static_cast<std::size_t>(src(who).device)].spec.sba
                                                         : 0xFF;
      st.turn_stop = -1;
    }
    return st.dev->start_bit();
  }

  // A character received: the word (or a framing error) to the device; what it asks (timers from `end`).
  genius::link_request device_word(std::size_t i, const receiver& rc, std::uint16_t wire, std::int64_t end) {
    station_state& st = stations[i];
    const bool framed = (wire & genius::stop_bit_mask) != 0;
    const genius::character c = genius::from_uart_word(static_cast<std::uint16_t>(wire >> 1));
    const genius::control_kind kind = c.control ? genius::read_control(c.byte).kind : genius::control_kind::unknown;
    const bool stop = framed && kind == genius::control_kind::stop;
    const bool was_sending = st.dev->sending();
    const bool was_open = st.dev->in_transmission();
    const genius::link_request request =
        framed ? st.dev->receive(static_cast<std::uint16_t>(wire >> 1)) : st.dev->framing_error();
    if (was_open && !st.dev->in_transmission()) ended(i, rc);
    if (stop && !was_sending) heard_stop(i, rc, request, end);
    if (was_sending && !st.dev->sending()) refresh_turn_data(st);  // its transmission is over (whole or cut)
    return request;
  }

  // The transmission device `i` was receiving ended at the word just received (rc.who's): a CRC-6 check
  // failed (a corruption, counted once for all the devices that check it), or it was heard whole. Only such an
  // end changes those two counters (the other ends are errors, or silence): `seen` holds them as they were
  // after the last one.
  void ended(std::size_t i, const receiver& rc) {
    station_state& st = stations[i];
    const genius::device_counters after = st.dev->counters();
    if (after.crc_errors != st.seen.crc_errors) note_event(rc.who, false);
    if (after.transmissions_heard != st.seen.transmissions_heard) {
      if (source* s = origin_of(i, rc)) s->heard_by |= 1u << i;
    }
    st.seen = after;
  }

  void start_check(std::size_t r) {
    receiver& rc = receivers[r];
    rc.scheduled = never;
    if (line(r, now)) {  // the line went back to 1: no start bit
      rc.idle_since = now;
      look(r);
      return;
    }
    rc.receiving = true;
    ++rc.generation;
    schedule(now + 10 * bit, event_kind::deliver, static_cast<std::uint32_t>(r), rc.generation);
    if (rc.device < 0) return;
    const auto i = static_cast<std::size_t>(rc.device);
    apply(i, device_start_bit(i, rc.edge, rc.who, now), now);
  }

  void deliver(std::size_t r) {
    receiver& rc = receivers[r];
    std::uint16_t wire = 0;  // start bit 0
    bool known = false;
    std::size_t k = 0;
    if (rc.who >= source_base) {
      // The common case: one transmission's character, alone on the line here.
      const source& s = src(rc.who);
      const std::int64_t rel = rc.edge - s.prop[r] - s.start;
      if (s.device >= 0 && rel >= 0 && rel % character == 0 && rc.edge - s.prop[r] + character <= s.hi &&
          alone(r, rc.who, rc.edge, now + 1)) {
        k = static_cast<std::size_t>(rel / character);
        if (k < s.words.size()) {
          wire = s.words[k];
          known = true;
        }
      }
    }
    for (unsigned b = 1; !known && b <= 10; ++b) {
      if (line(r, rc.edge + detection + static_cast<std::int64_t>(b) * bit)) wire = static_cast<std::uint16_t>(wire | (1u << b));
    }
    rc.idle_since = now;
    if (rc.on_word) rc.on_word(us_of_ps(rc.edge), wire);
    if (rc.device >= 0) {  // still `receiving`: what its device sends now is no news to its own receiver
      const auto i = static_cast<std::size_t>(rc.device);
      apply(i, device_word(i, rc, wire, rc.edge + character), rc.edge + character);
    }
    if (known && rc.device >= 0 && read_back_ahead(r)) return;
    rc.receiving = false;
    if (known && follow_from(r, src(rc.who), k + 1)) return;
    look(r);
  }

  // A sender that has read back a character of its own reads back the next ones ahead, each with the calls and
  // at the simulated times an event per start bit and per word would give (the clock set to each), while
  // nothing else can be heard or begin: no other signal anywhere on the line, no fault under way or to come,
  // and every other device powered follows this run (it hears these characters in step, so its timer cannot
  // expire before the run's Stop: only a timer starts a transmission). The followers take the characters as
  // before (a run's words are read by time). Then it goes on as after any character read back. False:
  // nothing read ahead.
  bool read_back_ahead(std::size_t r) {
    receiver& rc = receivers[r];
    const auto i = static_cast<std::size_t>(rc.device);
    station_state& st = stations[i];
    if (!config.follow || on_trace || !cuts.empty() || now < faults_end || pending_stops != 0) return false;
    if (st.tx_source < 0 || st.tx_source != rc.who || !st.dev->sending()) return false;
    const std::int64_t id = st.tx_source;
    std::size_t k = static_cast<std::size_t>((rc.edge - src(id).prop[r] - src(id).start) / character) + 1;
    if (k >= src(id).words.size()) return false;
    for (std::size_t j = 0; j < stations.size(); ++j) {
      if (j != i && stations[j].powered && receivers[j].follow != id) return false;
    }
    const auto next_fault = std::upper_bound(fault_starts.begin(), fault_starts.end(), now);
    const std::int64_t fault_at = next_fault != fault_starts.end() ? *next_fault : never;
    // (Quiet everywhere: a device still hearing another signal may yet arm a timer due earlier.)
    for (const source* sp : active) {
      if (sp->id != id && sp->zero_end + sp->farthest > now) return false;
    }
    const std::int64_t real_now = now;
    bool ahead = false;
    rc.receiving = true;  // its own characters: no news to it (notify)
    reading_ahead = true;
    const std::size_t words_before = src(id).words.size();
    while (k < src(id).words.size() && st.dev->sending()) {
      const source& s = src(id);
      const std::int64_t edge = s.start + static_cast<std::int64_t>(k) * character + s.prop[r];
      // (Not past the run's bound: a character is read back there only if its events come by then.)
      if (edge + character >= fault_at || edge + detection + 10 * bit > limit) break;
      now = edge + detection;  // the start bit confirmed
      rc.edge = edge;
      apply(i, device_start_bit(i, edge, id, now), now);
      now = edge + detection + 10 * bit;  // the word
      rc.idle_since = now;
      if (rc.on_word) rc.on_word(us_of_ps(edge), src(id).words[k]);
      apply(i, device_word(i, rc, src(id).words[k], edge + character), edge + character);
      ahead = true;
      ++k;
    }
    reading_ahead = false;
    const source& run = src(id);
    if (run.words.size() > words_before) {  // the end of the last character appended
      schedule(run.start + static_cast<std::int64_t>(run.words.size()) * character, event_kind::tx_end,
               static_cast<std::uint32_t>(i));
    }
    if (ahead) {
      rc.receiving = false;
      if (!follow_from(r, src(id), k)) look(r);
    }
    now = real_now;
    return ahead;
  }

  // ---- following: a listener takes a clean run of one transmission's characters in one go ----
  //
  // A device that is only listening, alone with one transmission on the line, does nothing anyone else can
  // see until that transmission ends: its start bits cancel a gap timer that its next character re-arms,
  // and it cannot transmit. So after one character received the exact way, it "follows" the transmission:
  // its next characters are handed to it in a batch (in order, each with its own times) when the
  // transmission's Stop reaches it, or earlier, up to the moment anything else appears on the line (another
  // transmission, noise, a cut, a power change), after which it goes back to an event per start bit and
  // per word. The calls the device sees, and their times, are the same.

  // Follower `r` takes source `s`'s characters from `k` on, if nothing else can be heard: no other source
  // from the moment it went idle on, no cut, its device listening, and the device's timer not due before
  // character k's start bit (that start bit cancels it: a timer due earlier must expire the exact way).
  bool follow_from(std::size_t r, const source& s, std::size_t k, bool others_quiet = false) {
    receiver& rc = receivers[r];
    if (!config.follow || !cuts.empty() || !s.open || s.device < 0) return false;
    if (rc.device >= 0) {
      const station_state& st = stations[static_cast<std::size_t>(rc.device)];
      if (!st.powered || st.dev->sending()) return false;
      if (st.timer_due <= s.start + static_cast<std::int64_t>(k) * character + s.prop[r] + detection) return false;
    }
    if (!others_quiet) {
      for (const source* sp : active) {
        if (sp->id != s.id && sp->zero_end + sp->prop[r] > rc.idle_since) return false;
      }
    }
    rc.follow = s.id;
    ++src(s.id).followed;
    rc.next = k;
    ++rc.generation;
    rc.scheduled = never;
    followers.push_back(r);
    if (s.stop_start != never) schedule_catch_up(r);
    return true;
  }

  std::int64_t delivered_at(std::size_t r, const source& s, std::size_t k) const {
    return s.start + static_cast<std::int64_t>(k) * character + s.prop[r] + detection + 10 * bit;
  }

  void schedule_catch_up(std::size_t r) {
    receiver& rc = receivers[r];
    const source& s = src(rc.follow);
    ++rc.generation;
    schedule(std::max(now, delivered_at(r, s, s.words.size() - 1)), event_kind::catch_up,
             static_cast<std::uint32_t>(r), rc.generation);
  }

  // Hands follower `r` every character of its transmission delivered by `until`.
  void catch_up(std::size_t r, std::int64_t until) {
    receiver& rc = receivers[r];
    const source& s = src(rc.follow);
    const int device = rc.device;
    std::int64_t due = device >= 0 ? stations[static_cast<std::size_t>(device)].timer_due : never;
    const auto take = [&](const genius::link_request& q, std::int64_t base) {
      if (q.timer == genius::timer_action::arm) due = base + static_cast<std::int64_t>(q.ticks) * tick;
      if (q.timer == genius::timer_action::cancel) due = never;
    };
    // The characters it takes: whole ones (within the run's `hi`) delivered by `until`.
    const std::int64_t start_here = s.start + s.prop[r];
    std::size_t last = s.words.size();
    if (s.hi < never) last = std::min<std::size_t>(last, static_cast<std::size_t>(std::max<std::int64_t>(0, (s.hi - s.start) / character)));
    const std::int64_t latest = until - start_here - detection - 10 * bit;  // the last character's edge, relative
    last = latest < 0 ? std::min<std::size_t>(last, 0) : std::min<std::size_t>(last, static_cast<std::size_t>(latest / character) + 1);
    sim_device* const dev = device >= 0 ? stations[static_cast<std::size_t>(device)].dev : nullptr;
    const std::size_t first = rc.next;
    const bool monitor = static_cast<bool>(rc.on_word);
    const auto i = static_cast<std::size_t>(device);
    // A character (a device's words are framed) to a device that is listening and has no turn on record takes
    // the device's two calls, ended() if it ended what the device was receiving, and heard_stop() for a Stop:
    // device_start_bit and device_word would do nothing more (a device that listens does not begin to send on
    // a character). Only a Stop can change either condition.
    const auto plain = [&]() { return dev != nullptr && stations[i].turn_stop < 0 && !dev->sending(); };
    bool fast = plain();
    const std::uint16_t* const words = s.words.data();
    const std::uint8_t* const stops = s.stops.data();
    std::size_t next = rc.next;
    if (dev == nullptr) {  // a monitor
      for (; monitor && next < last; ++next) rc.on_word(us_of_ps(start_here + static_cast<std::int64_t>(next) * character), words[next]);
      next = std::max(next, last);
    }
    for (; next < last; ++next) {
      const std::int64_t edge = start_here + static_cast<std::int64_t>(next) * character;
      const std::uint16_t wire = words[next];
      if (fast && stops[next] != unframed_word) {
        take(dev->start_bit(), edge + detection);
        const bool was_open = dev->in_transmission();
        const genius::link_request q = dev->receive(static_cast<std::uint16_t>(wire >> 1));
        take(q, edge + character);
        if (was_open && !dev->in_transmission()) {
          rc.edge = edge;
          rc.who = s.id;
          ended(i, rc);
        }
        if (stops[next] == stop_word) {  // device_word's Stop heard, the rest of it being nothing here
          rc.edge = edge;
          rc.who = s.id;
          heard_stop(i, rc, q, edge + character);
          fast = plain();
        }
        continue;
      }
      rc.edge = edge;
      rc.who = s.id;
      take(device_start_bit(i, edge, s.id, edge + detection), edge + detection);
      take(device_word(i, rc, wire, edge + character), edge + character);
      fast = plain();
    }
    rc.next = next;
    if (rc.next > first) {
      const std::int64_t edge = start_here + static_cast<std::int64_t>(rc.next - 1) * character;
      rc.edge = edge;
      rc.who = s.id;
      rc.idle_since = edge + detection + 10 * bit;
    }
    if (device >= 0) {
      station_state& st = stations[static_cast<std::size_t>(device)];
      st.timer_due = due;
      if (due != never) timer_armed(std::max(due, now));
    }
  }

  // Follower `r`'s catch-up at the Stop's delivery (`now`): it takes the run's characters, and listens again.
  void caught_up(std::size_t r) {
    receiver& rc = receivers[r];
    catch_up(r, now);
    if (rc.next >= src(rc.follow).words.size()) {
      --src(rc.follow).followed;
      rc.follow = -1;
      followers.erase(r);
      look(r);
    }
  }

  // Follower `r` goes back to an event per start bit and per word, from `now`.
  void unfollow(std::size_t r) {
    catch_up(r, now);
    receiver& rc = receivers[r];
    source& s = src(rc.follow);
    --s.followed;
    rc.follow = -1;
    followers.erase(r);
    if (rc.next < s.words.size()) {
      const std::int64_t edge = s.start + static_cast<std::int64_t>(rc.next) * character + s.prop[r];
      if (edge - s.prop[r] < s.hi && edge + detection <= now) {
        // Its start bit is already confirmed: the start bit now, the word at its time.
        rc.edge = edge;
        rc.who = s.id;
        rc.receiving = true;
        ++rc.generation;
        schedule(edge + detection + 10 * bit, event_kind::deliver, static_cast<std::uint32_t>(r), rc.generation);
        if (rc.device >= 0) {
          const auto i = static_cast<std::size_t>(rc.device);
          apply(i, device_start_bit(i, edge, s.id, edge + detection), now);
        }
        return;
      }
    }
    look(r);
  }

  void unfollow_all() {
    while (!followers.empty()) unfollow(followers.back());
  }

  // A corrupted transmission met a CRC-6 check (`escaped`: and passed it), keyed by the source whose edge
  // began the character: once per corruption, however many devices saw it.
  std::vector<std::pair<std::int64_t, bool>> events_seen;
  void note_event(std::int64_t key, bool escaped) {
    for (auto& e : events_seen) {
      if (e.first != key) continue;
      if (escaped && !e.second) {
        e.second = true;
        ++result.escape_events;
      }
      return;
    }
    events_seen.emplace_back(key, escaped);
    if (events_seen.size() > 64) events_seen.erase(events_seen.begin());
    ++result.corrupt_events;
    if (escaped) ++result.escape_events;
  }

  // The transmission whose Stop receiver `i` was sampling: the source whose edge began the character, or
  // failing that (noise that fell a moment earlier began it) the transmission whose Stop began within a bit
  // of that edge.
  source* origin_of(std::size_t i, const receiver& rc) {
    if (rc.who >= source_base && rc.who - source_base < static_cast<std::int64_t>(sources.size())) {
      source& s = src(rc.who);
      if (s.device >= 0 && s.stop_start != never && s.stop_start + s.prop[i] == rc.edge) return &s;
    }
    for (source* s : active) {
      if (s->device >= 0 && s->stop_start != never && std::llabs(s->stop_start + s->prop[i] - rc.edge) < bit) return s;
    }
    return nullptr;
  }

  // Device `i` heard a Stop: the turn it armed (for the records) and its deliveries (checked).
  void heard_stop(std::size_t i, const receiver& rc, const genius::link_request& request, std::int64_t end) {
    station_state& st = stations[i];
    source* origin = origin_of(i, rc);
    if (recording() && origin != nullptr && origin->stop_index >= 0 && st.dev->turn_armed() &&
        request.timer == genius::timer_action::arm) {
      genius_stop_record& rec = result.stops[static_cast<std::size_t>(origin->stop_index)];
      rec.turns.push_back(genius_stop_record::armed{
          st.spec.sba, us_of_ps(end + static_cast<std::int64_t>(request.ticks) * tick), false, 0, 0, 0, false, false});
      st.turn_stop = origin->stop_index;
      st.turn_slot = static_cast<int>(rec.turns.size()) - 1;
    } else {
      st.turn_stop = -1;
    }
    // Deliveries: what the program side reads now, against what the sender put on the line (the records it
    // must deliver worked out at the first delivery: most Stops deliver something).
    const std::vector<record>* expected_records = &expected_scratch;
    std::size_t expected_count = 0;
    std::size_t count = 0;
    const auto take = [&](const genius::delivery_result& d, byte_view data) {
      if (count == 0 && origin != nullptr)
        expected_records = &origin->content.expected_by(st.spec.sba, expected_scratch, expected_count);
      const std::vector<record>& expected = *expected_records;
      const std::size_t k = count++;
      ++result.deliveries;
      ++st.report.deliveries_checked;
      const bool right_data = k < expected_count && data.size() == expected[k].data.size() &&
                              std::equal(data.begin(), data.end(), expected[k].data.begin());
      if (right_data && d.kind == expected[k].kind && d.sender == expected[k].sender) return;
      ++result.wrong_deliveries;
      ++st.report.wrong_deliveries;
      if (!right_data) {
        ++result.wrong_data;
        ++st.report.wrong_data;
        note_event(rc.who, true);
      }
      if (on_trace) {
        const auto hex = [](genius::delivery_kind kind, std::uint8_t sender, byte_view bytes) {
          std::string text = std::string(genius::to_string(kind)) + " from " + std::to_string(sender) + ":";
          char byte[4];
          for (const std::uint8_t b : bytes) {
            std::snprintf(byte, sizeof byte, " %02x", b);
            text += byte;
          }
          return text;
        };
        const std::string sent =
            k < expected_count
                ? "; sent " + hex(expected[k].kind, expected[k].sender,
                                  byte_view(expected[k].data.data(), expected[k].data.size()))
                : "; nothing sent";
        trace("SBA " + std::to_string(st.spec.sba) + ": a delivery its sender did not send (" +
              hex(d.kind, d.sender, data) + sent + ")");
      }
    };
    if (st.controller) {
      (void)st.controller->collect(take);
    } else {
      for (;;) {
        std::uint8_t data[255];
        const genius::delivery_result d = st.dev->read(byte_buffer(data, sizeof data));
        if (!d) break;
        take(d, byte_view(data, d.length));
      }
    }
  }

  void timer(std::size_t i) {
    station_state& st = stations[i];
    const bool turn = st.dev->turn_armed();
    const genius::link_request request = st.dev->timer_expired();
    if (turn && st.turn_stop >= 0 && config.record_turns) {
      auto& t = result.stops[static_cast<std::size_t>(st.turn_stop)].turns[static_cast<std::size_t>(st.turn_slot)];
      t.transmitted = request.transmit;
      t.passed = !request.transmit;
    }
    st.turn_stop = -1;
    if (turn && !request.transmit && on_trace) trace("SBA " + std::to_string(st.spec.sba) + " lets its turn pass");
    apply(i, request, now);
  }

  void power_off(std::size_t i, std::int64_t off_for) {
    station_state& st = stations[i];
    if (!st.powered) return;
    st.powered = false;                          // first: so that catching up does not follow anew
    if (receivers[i].follow >= 0) unfollow(i);  // what it received up to now
    st.timer_due = never;
    receiver& rc = receivers[i];
    rc.receiving = false;
    ++rc.generation;
    rc.scheduled = never;
    if (st.tx_source >= 0) {
      source& s = src(st.tx_source);
      if (s.open) {
        s.cut = now;
        s.hi = std::min(s.hi, now);
        stale_low_ends();
        s.zero_end = s.hi;
        close_source(st.tx_source);
      }
      st.tx_source = -1;
    }
    if (on_trace) trace("SBA " + std::to_string(st.spec.sba) + " powered off");
    schedule(now + off_for, event_kind::power_on, static_cast<std::uint32_t>(i));
    // Everyone listening looks again: the line may have gone quiet earlier than they expected.
    for (std::size_t r = 0; r < receivers.size(); ++r) {
      if (!receivers[r].receiving && receivers[r].follow < 0 && r != i) look(r);
    }
  }

  void power_on(std::size_t i) {
    station_state& st = stations[i];
    st.report.counters = add(st.report.counters, st.dev->counters());
    ++st.report.power_cycles;
    st.powered = true;
    st.plain.reset();
    st.controller.reset();
    make_device(st);
    if (on_trace) trace("SBA " + std::to_string(st.spec.sba) + " powered on");
    receiver& rc = receivers[i];
    rc.idle_since = now;
    apply(i, st.dev->power_on(), now);
    look(i);
  }

  static genius::device_counters add(genius::device_counters a, const genius::device_counters& b) {
    a.turns_taken += b.turns_taken;
    a.turns_passed += b.turns_passed;
    a.transmissions_sent += b.transmissions_sent;
    a.collisions += b.collisions;
    a.characters += b.characters;
    a.framing_errors += b.framing_errors;
    a.transmissions_heard += b.transmissions_heard;
    a.crc_errors += b.crc_errors;
    a.wire_errors += b.wire_errors;
    a.lost_transmissions += b.lost_transmissions;
    a.deliveries += b.deliveries;
    a.delivery_overflows += b.delivery_overflows;
    a.idle_restarts += b.idle_restarts;
    a.skipped += b.skipped;
    return a;
  }

  void fault(std::size_t k) {
    const genius_fault& f = config.faults[k];
    switch (f.kind) {
      case genius_fault_kind::noise: {
        source s;
        s.position_ft = f.position_ft;
        s.start = now;
        std::int64_t t = now;
        const std::int64_t end = now + ps_of_us(f.duration_us);
        bool zero = true;
        while (t < end) {
          const auto length = static_cast<std::int64_t>(static_cast<double>(bit) * (0.3 + 2.7 * std::uniform_real_distribution<double>(0, 1)(rng)));
          const std::int64_t to = std::min(end, t + std::max<std::int64_t>(1, length));
          if (zero) s.zeros.emplace_back(t, to);
          zero = !zero;
          t = to;
        }
        s.open = false;
        s.end = end;
        faults_end = std::max(faults_end, end);
        if (on_trace) trace("noise burst at " + std::to_string(f.position_ft) + " ft for " + std::to_string(f.duration_us) + " us");
        notify(add_source(std::move(s)));
        break;
      }
      case genius_fault_kind::power_off:
        faults_end = std::max(faults_end, now + ps_of_us(f.duration_us));
        for (std::size_t i = 0; i < stations.size(); ++i) {
          if (stations[i].spec.sba == f.sba) power_off(i, ps_of_us(f.duration_us));
        }
        break;
      case genius_fault_kind::stop:
        faults_end = std::max(faults_end, now);  // until it takes effect (append)
        for (station_state& st : stations) {
          if (st.spec.sba == f.sba) {
            if (st.stop_after_us < 0) ++pending_stops;
            st.stop_after_us = us_of_ps(now);
            st.stop_for_us = f.duration_us;
          }
        }
        break;
      case genius_fault_kind::cut:
        cuts.push_back(cut_window{f.position_ft, now, now + ps_of_us(f.duration_us)});
        cut_history.push_back(cuts.back());
        stale_low_ends();  // a source behind the cut is 0 there no more
        faults_end = std::max(faults_end, now + ps_of_us(f.duration_us));
        unfollow_all();  // no one follows while a cut is open
        if (on_trace) trace("line cut at " + std::to_string(f.position_ft) + " ft for " + std::to_string(f.duration_us) + " us");
        schedule(now, event_kind::cut_edge, 0);
        schedule(now + ps_of_us(f.duration_us), event_kind::cut_edge, 0);
        break;
    }
  }

  void tx_end(std::size_t i) {
    station_state& st = stations[i];
    if (st.tx_source < 0) return;
    source& s = src(st.tx_source);
    if (!s.open) return;
    const std::int64_t end = s.start + static_cast<std::int64_t>(s.words.size()) * character;
    if (end > now) return;  // another character was appended
    close_source(st.tx_source);
    st.tx_source = -1;
  }
};

genius_bus::genius_bus(const std::vector<genius_station>& stations, const genius_bus_config& config)
    : s_(std::make_unique<state>()) {
  state& s = *s_;
  s.config = config;
  s.rng.seed(config.seed);
  const double bit_us = genius::bit_time_us(config.rate);
  s.bit = ps_of_us(bit_us);
  s.character = 11 * s.bit;
  s.skip = config.skip_us > 0 ? ps_of_us(config.skip_us)
                              : static_cast<std::int64_t>(genius::properties(config.rate).skip_bits) * s.bit;
  s.detection = config.detection_us >= 0 ? ps_of_us(config.detection_us) : s.bit / 2;
  s.ps_per_ft = config.propagation_us_per_2000ft * 1e6 / 2000.0;
  // The timer counts picoseconds, or coarser ticks when its longest wait would not fit 32 bits.
  s.tick = 1;
  while ((32 * s.skip + 2 * s.character) / s.tick > 0xFFFFFFFFll) s.tick *= 10;
  s.timing = genius::device_timing{static_cast<std::uint32_t>(s.skip / s.tick),
                                   static_cast<std::uint32_t>(s.character / s.tick), 2};
  double lowest = 1e300, highest = -1e300;
  for (const genius_station& spec : stations) {
    station_state st;
    st.spec = spec;
    st.report.sba = spec.sba;
    s.stations.push_back(std::move(st));
    lowest = std::min(lowest, spec.position_ft);
    highest = std::max(highest, spec.position_ft);
  }
  s.max_prop = std::llround((highest - lowest) * s.ps_per_ft);
  for (std::size_t i = 0; i < s.stations.size(); ++i) {
    receiver rc;
    rc.device = static_cast<int>(i);
    rc.position_ft = s.stations[i].spec.position_ft;
    s.receivers.push_back(rc);
    s.make_device(s.stations[i]);
  }
  // The scans' opener: the controller, else the lowest SBA that sends.
  for (std::size_t i = 0; i < s.stations.size(); ++i) {
    const genius_station& spec = s.stations[i].spec;
    if (config.controller >= 0) {
      if (spec.sba == config.controller) s.opener = static_cast<int>(i);
    } else if (spec.input_bytes > 0 &&
               (s.opener < 0 || spec.sba < s.stations[static_cast<std::size_t>(s.opener)].spec.sba)) {
      s.opener = static_cast<int>(i);
    }
  }
  if (s.opener < 0) s.opener = 0;
  s.result.opener = s.stations[static_cast<std::size_t>(s.opener)].spec.sba;
}

genius_bus::~genius_bus() = default;

void genius_bus::monitor(double position_ft, std::function<void(double, std::uint16_t)> on_word) {
  receiver rc;
  rc.position_ft = position_ft;
  rc.on_word = std::move(on_word);
  s_->receivers.push_back(std::move(rc));
}

void genius_bus::trace(std::function<void(const std::string&)> on_trace) { s_->on_trace = std::move(on_trace); }

std::int64_t genius_bus::bit_ps() const { return s_->bit; }
std::int64_t genius_bus::skip_ps() const { return s_->skip; }
std::int64_t genius_bus::detection_ps() const { return s_->detection; }

genius_bus_result genius_bus::run() {
  state& s = *s_;
  // The time bound: generous room for every scan, the faults and the idle restarts.
  std::int64_t scan_bound = 64 * s.skip + 8 * s.character;
  for (const station_state& st : s.stations)
    scan_bound += (st.spec.input_bytes + st.spec.output_bytes + 70) * s.character + 2 * s.max_prop;
  std::int64_t& limit = s.limit;
  limit = static_cast<std::int64_t>(s.config.scans + 4) * scan_bound;
  for (std::size_t k = 0; k < s.config.faults.size(); ++k) {
    const genius_fault& f = s.config.faults[k];
    limit = std::max(limit, ps_of_us(f.at_us + f.duration_us) + static_cast<std::int64_t>(s.config.scans + 4) * scan_bound);
    s.schedule(ps_of_us(f.at_us), event_kind::fault, static_cast<std::uint32_t>(k));
    s.fault_starts.push_back(ps_of_us(f.at_us));
  }
  std::sort(s.fault_starts.begin(), s.fault_starts.end());
  if (s.config.max_us > 0) limit = ps_of_us(s.config.max_us);
  for (std::size_t i = 0; i < s.stations.size(); ++i) s.apply(i, s.stations[i].dev->power_on(), 0);
  for (std::size_t r = 0; r < s.receivers.size(); ++r) s.look(r);

  std::uint64_t since_prune = 0;
  bool finishing = false;
  while (!s.events.empty()) {
    if (s.done && !finishing) {
      // The last scan is complete: run on until every device has heard its opening Stop.
      finishing = true;
      limit = std::min(limit, s.now + s.max_prop + 2 * s.character);
    }
    const event e = s.events.top();
    if (e.time() > limit) break;
    s.events.pop();
    s.now = e.time();
    ++s.result.events;
    switch (e.kind) {
      case event_kind::fault:
        s.fault(e.who);
        break;
      case event_kind::power_off:
        s.power_off(e.who, s.stations[e.who].off_for);
        break;
      case event_kind::power_on:
        s.power_on(e.who);
        break;
      case event_kind::cut_edge:
        s.unfollow_all();
        for (std::size_t r = 0; r < s.receivers.size(); ++r) {
          if (!s.receivers[r].receiving) s.look(r);
        }
        break;
      case event_kind::start_check: {
        receiver& rc = s.receivers[e.who];
        if (e.generation != rc.generation) break;
        if (rc.device >= 0 && !s.stations[static_cast<std::size_t>(rc.device)].powered) break;
        s.start_check(e.who);
        break;
      }
      case event_kind::deliver: {
        receiver& rc = s.receivers[e.who];
        if (e.generation != rc.generation) break;
        if (rc.device >= 0 && !s.stations[static_cast<std::size_t>(rc.device)].powered) break;
        s.deliver(e.who);
        break;
      }
      case event_kind::catch_up: {
        receiver& rc = s.receivers[e.who];
        if (e.generation != rc.generation || rc.follow < 0) break;
        s.caught_up(e.who);
        break;
      }
      case event_kind::timer:
        if (e.time() == s.timers_entry) s.timers_due();  // (else an older entry, overtaken by an earlier one)
        break;
      case event_kind::tx_end:
        s.tx_end(e.who);
        break;
      case event_kind::loss_check:
        s.loss_check(e.generation);
        break;
    }
    if (++since_prune >= 256) {
      since_prune = 0;
      s.prune();
    }
  }
  // Followers take what they would have received by then, as an event per word would have given them.
  // The clock stops at the bound, unless nothing at all was left to happen.
  s.now = s.events.empty() ? s.now : limit;
  s.config.follow = false;
  s.unfollow_all();
  s.result.end_us = us_of_ps(s.now);
  s.result.faults_end_us = us_of_ps(s.faults_end);
  s.result.complete = s.done;
  s.result.line_steps = s.line_steps;
  // The first scan's turns: those armed by the opener's first Stop, in SBA order after it.
  if (s.config.record_turns) {
    for (const genius_stop_record& rec : s.result.stops) {
      if (rec.sender != s.result.opener) continue;
      std::vector<genius_stop_record::armed> turns = rec.turns;
      std::sort(turns.begin(), turns.end(), [&](const auto& a, const auto& b) {
        return genius::sba_offset(rec.sender, a.sba) < genius::sba_offset(rec.sender, b.sba);
      });
      for (const auto& t : turns) {
        genius_turn_record tr;
        tr.sba = t.sba;
        tr.due_us = t.due_us - rec.end_us;
        tr.cancelled = t.cancelled;
        tr.by = t.by;
        tr.arrived_us = t.cancelled ? t.arrived_us - rec.end_us : 0;
        tr.detected_us = t.cancelled ? t.detected_us - rec.end_us : 0;
        tr.transmitted = t.transmitted;
        tr.passed = t.passed;
        s.result.first_scan_turns.push_back(tr);
      }
      break;
    }
  }
  for (station_state& st : s.stations) {
    genius_device_report report = st.report;
    report.counters = state::add(report.counters, st.dev->counters());
    report.netstat = st.dev->netstat();
    s.result.devices.push_back(report);
  }
  return s.result;
}

}  // namespace trionet::host

// A CAN bus model for tests and tools: several stations on one bus, arbitration by lowest identifier, frame
// times from the worst-case stuffed frame length, and the delivery latency of every queued frame.
//
// Frame length. A classic data frame with an 11-bit identifier and n data bytes is
//
//   SOF 1 | identifier 11 | RTR 1 | IDE 1 | r0 1 | DLC 4 | data 8n | CRC 15 || CRC delim 1 | ACK 2 | EOF 7 |
//   IFS 3
//   \_____________________ g + 8n bits, g = 34, subject to stuffing _____/  \______ 13 bits, never stuffed
//   ___/
//
// i.e. 47 + 8n bits unstuffed, intermission (IFS) included. The transmitter inserts a complementary stuff bit
// after 5 equal bits; a stuff bit itself starts the next run, so the worst case is one stuff bit after the
// first 5 bits and then one after every further 4: floor((g + 8n - 1) / 4) stuff bits (Davis, Burns, Bril,
// Lukkien, "CAN schedulability analysis: refuted, revisited, and revised", 2007). For n = 8:
// 34 + 64 + 13 + floor(97 / 4) = 111 + 24 = 135 bits. (29-bit identifiers: g = 54, 160 bits for 8 bytes.)
// At 125k, 250k, 500k and 1M bit/s that is 1080, 540, 270 and 135 us per frame.
//
// Time. The model has no clock: time is a number of bit times that only `advance_to` moves forward, so a
// simulation is exact and independent of the bit rate; `nanoseconds` converts for reporting.
//
// Queues. Each station has a transmit queue of `QueueDepth` frames. At each arbitration every station offers
// its highest-priority queued frame (lowest identifier; equal identifiers in queue order, as a controller
// with priority-ordered mailboxes does), and the lowest identifier on the bus wins (identical identifiers
// from two stations would be an error on a real bus; the model lets the lower station index win). A frame
// starts the moment the bus is idle, occupies it for its length and is delivered to the listener when it
// ends.
//
// Cost: RAM about Stations * QueueDepth * 32 bytes; `send` is O(1); each arbitration is
// O(Stations * QueueDepth). Not for an ISR: it is a host/test tool (no heap, no exceptions, though).
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/can/frame.hpp"
#include "trionet/can/port.hpp"

namespace trionet::can {

/// Bits of a classic CAN data frame with `data_bytes` (0..8) data bytes, intermission included, no stuffing.
[[nodiscard]] constexpr std::uint32_t unstuffed_frame_bits(std::uint8_t data_bytes,
                                                           bool extended = false) noexcept {
  return (extended ? 54U : 34U) + 8U * data_bytes + 13U;
}

/// Worst-case number of stuff bits in such a frame: floor((g + 8n - 1) / 4).
[[nodiscard]] constexpr std::uint32_t worst_case_stuff_bits(std::uint8_t data_bytes,
                                                            bool extended = false) noexcept {
  return ((extended ? 54U : 34U) + 8U * data_bytes - 1U) / 4U;
}

/// Worst-case stuffed length of a classic CAN data frame, intermission included: 135 bits for an 11-bit
/// identifier and 8 data bytes.
[[nodiscard]] constexpr std::uint32_t worst_case_frame_bits(std::uint8_t data_bytes,
                                                            bool extended = false) noexcept {
  return unstuffed_frame_bits(data_bytes, extended) + worst_case_stuff_bits(data_bytes, extended);
}

/// `bits` bit times at `bit_rate` bit/s, in nanoseconds (rounded down; exact for the standard rates).
[[nodiscard]] constexpr std::uint64_t nanoseconds(std::uint64_t bits, std::uint32_t bit_rate) noexcept {
  return bit_rate == 0 ? 0 : bits * 1000000000ULL / bit_rate;
}

/// The bit rates TN20-17 controllers are commonly run at, bit/s.
constexpr std::uint32_t standard_bit_rates[] = {125000, 250000, 500000, 1000000};

/// How the model sizes a frame on the bus.
enum class stuffing : std::uint8_t {
  worst_case,  ///< every frame takes its worst-case stuffed length (the safe figure for analysis)
  none,        ///< every frame takes its unstuffed length (the best case)
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(stuffing value) noexcept {
  switch (value) {
    case stuffing::worst_case:
      return "worst_case";
    case stuffing::none:
      return "none";
  }
  return "unknown";
}

/// One frame that went over the bus: who sent it, and when it was queued, won arbitration and was delivered
/// (end of its intermission), in bit times.
struct bus_delivery {
  std::size_t station = 0;         ///< the sending station, 0..Stations-1
  frame sent{};                    ///< the frame
  std::uint64_t queued_at = 0;     ///< when its port queued it
  std::uint64_t started_at = 0;    ///< when it started the arbitration it won
  std::uint64_t delivered_at = 0;  ///< the end of its intermission

  /// Time from queueing to delivery, bit times.
  [[nodiscard]] constexpr std::uint64_t latency() const noexcept { return delivered_at - queued_at; }
};

/// Receives every frame the bus model delivers. Every station hears every frame, the sender included (as with
/// a controller's own-message reception); the listener decides who handles it.
class bus_listener {
 public:
  /// Called once for every frame the bus delivers, in delivery order.
  virtual void on_delivery(const bus_delivery& delivery) noexcept = 0;

 protected:
  bus_listener() = default;
  bus_listener(const bus_listener&) = default;             ///< copyable by implementations only
  bus_listener& operator=(const bus_listener&) = default;  ///< assignable by implementations only
  ~bus_listener() = default;
};

/// `Stations` CAN controllers on one bus, each with a transmit queue of `QueueDepth` frames and a `port` that
/// queues into it. See the header comment for the timing and arbitration rules.
template <std::size_t Stations, std::size_t QueueDepth = 8>
class bus_model {
  static_assert(Stations > 0, "a bus has at least one station");
  static_assert(QueueDepth > 0, "a station queues at least one frame");

 public:
  /// An idle bus at time 0 whose frames take the length `sizing` gives them.
  explicit bus_model(stuffing sizing = stuffing::worst_case) noexcept : sizing_(sizing) {
    for (std::size_t i = 0; i < Stations; ++i) ports_[i].attach(this, i);
  }
  bus_model(const bus_model&) = delete;
  bus_model& operator=(const bus_model&) = delete;

  /// The port through which station `station` (< Stations) transmits.
  [[nodiscard]] port& station_port(std::size_t station) noexcept { return ports_[station]; }

  /// Queues `outgoing` at station `station` at the current time; `busy` if its queue is full.
  [[nodiscard]] transmit_status send(std::size_t station, const frame& outgoing) noexcept {
    if (station >= Stations) return transmit_status::failed;
    queue& q = queues_[station];
    if (q.count == QueueDepth) return transmit_status::busy;
    q.entries[q.count++] = entry{outgoing, now_, next_sequence_++};
    return transmit_status::ok;
  }

  /// Runs the bus up to `time` (bit times): every frame whose transmission ends at or before `time` is
  /// delivered to `listener`, in order. The listener may queue new frames; they join the next arbitration.
  /// A `time` before now is treated as now.
  void advance_to(std::uint64_t time, bus_listener& listener) noexcept {
    for (;;) {
      if (in_flight_) {
        if (current_.delivered_at > time) break;
        now_ = current_.delivered_at;
        in_flight_ = false;
        ++delivered_;
        listener.on_delivery(current_);
        continue;
      }
      if (!start_next()) break;
    }
    if (time > now_) now_ = time;
  }

  /// Runs until nothing is queued or in flight (or `limit` bit times is reached); returns the time then.
  std::uint64_t run_until_idle(bus_listener& listener, std::uint64_t limit = ~std::uint64_t{0}) noexcept {
    while (!idle() && now_ < limit) {
      const std::uint64_t next = in_flight_ ? current_.delivered_at : now_;
      advance_to(next < limit ? next : limit, listener);
    }
    return now_;
  }

  /// The model's time, bit times since construction.
  [[nodiscard]] std::uint64_t now() const noexcept { return now_; }
  /// True if no frame is queued or on the bus.
  [[nodiscard]] bool idle() const noexcept { return !in_flight_ && queued() == 0; }
  /// Frames waiting at `station` (not counting one on the bus).
  [[nodiscard]] std::size_t queued(std::size_t station) const noexcept {
    return station < Stations ? queues_[station].count : 0;
  }
  /// Frames waiting at all stations.
  [[nodiscard]] std::size_t queued() const noexcept {
    std::size_t total = 0;
    for (const queue& q : queues_) total += q.count;
    return total;
  }
  /// Bit times the bus has been occupied by started frames.
  [[nodiscard]] std::uint64_t busy_bits() const noexcept { return busy_bits_; }
  /// Frames delivered so far.
  [[nodiscard]] std::uint64_t delivered() const noexcept { return delivered_; }
  /// Length of `f` on this bus, bit times.
  [[nodiscard]] std::uint32_t frame_bits(const frame& f) const noexcept {
    return sizing_ == stuffing::worst_case ? worst_case_frame_bits(f.data_length(), f.extended())
                                           : unstuffed_frame_bits(f.data_length(), f.extended());
  }

  /// The arbitration field as a number: the lower wins. Standard frames: identifier, RTR, IDE = 0;
  /// extended frames: base identifier, SRR = 1, IDE = 1, extension, RTR (ISO 11898-1 bit order).
  [[nodiscard]] static constexpr std::uint64_t arbitration_key(const frame& f) noexcept {
    const std::uint64_t rtr = f.remote() ? 1 : 0;
    if (!f.extended()) return std::uint64_t{f.identifier()} << 21U | rtr << 20U;
    const std::uint64_t id = f.identifier();
    return (id >> 18U) << 21U | 1ULL << 20U | 1ULL << 19U | (id & 0x3FFFFU) << 1U | rtr;
  }

 private:
  struct entry {
    frame queued_frame{};
    std::uint64_t queued_at = 0;
    std::uint64_t sequence = 0;
  };
  struct queue {
    entry entries[QueueDepth] = {};
    std::size_t count = 0;
  };
  class queue_port final : public port {
   public:
    void attach(bus_model* bus, std::size_t station) noexcept {
      bus_ = bus;
      station_ = station;
    }
    [[nodiscard]] transmit_status send(const frame& outgoing) noexcept override {
      return bus_->send(station_, outgoing);
    }

   private:
    bus_model* bus_ = nullptr;
    std::size_t station_ = 0;
  };

  // Arbitration at now_: the lowest key wins; within a station, equal keys go in queue order.
  bool start_next() noexcept {
    bool found = false;
    std::size_t best_station = 0;
    std::size_t best_index = 0;
    std::uint64_t best_key = 0;
    std::uint64_t best_sequence = 0;
    for (std::size_t s = 0; s < Stations; ++s) {
      const queue& q = queues_[s];
      for (std::size_t i = 0; i < q.count; ++i) {
        const std::uint64_t key = arbitration_key(q.entries[i].queued_frame);
        const bool better = !found || key < best_key ||
                            (key == best_key && s == best_station && q.entries[i].sequence < best_sequence);
        if (better) {
          found = true;
          best_station = s;
          best_index = i;
          best_key = key;
          best_sequence = q.entries[i].sequence;
        }
      }
    }
    if (!found) return false;
    queue& q = queues_[best_station];
    const entry won = q.entries[best_index];
    for (std::size_t i = best_index + 1; i < q.count; ++i) q.entries[i - 1] = q.entries[i];
    --q.count;
    const std::uint32_t bits = frame_bits(won.queued_frame);
    current_ = bus_delivery{best_station, won.queued_frame, won.queued_at, now_, now_ + bits};
    busy_bits_ += bits;
    in_flight_ = true;
    return true;
  }

  stuffing sizing_;
  queue queues_[Stations] = {};
  queue_port ports_[Stations];
  bus_delivery current_{};
  bool in_flight_ = false;
  std::uint64_t now_ = 0;
  std::uint64_t next_sequence_ = 0;
  std::uint64_t busy_bits_ = 0;
  std::uint64_t delivered_ = 0;
};

}  // namespace trionet::can

// The learning figures (docs/profile.md): how many frames the CRC and layout learners need and how long they
// take, over the CRC RevEng catalogue and random parameter sets. Run it with scripts/learn-figures.
//
//   trionet_learn_figures [--quick] [--rivals]
//
// Ring CRC: for every 16-bit catalogue CRC in both group orders (10 captures each) and for random parameter
// sets (odd polynomial, any init and xorout, all four reflection pairs, both group orders): 8 random frames
// are learned, then a separate capture of 1000 frames is decoded by the ring decoder holding the learned CRC.
// Frames needed = the smallest k for which the first k frames give exactly one class. Times are wall-clock
// (steady_clock) per learn_ring_crc call on the 8 frames; median and worst. Also: captures of one VR counting
// up (0, 1, 2, ...), with even polynomials admitted, and the one- and two-frame calls.
// Layout: both group orders and the CRC input from 4 frames. Genius: the catalogue's CRC-6 and 32 drawn ones,
// samples needed from transmissions made by genius::encode_transmission.
// --rivals: for each catalogue CRC, the rank (on valid frames, 14 transmitted bits) of the difference to its
// closest rival among all odd polynomials and reflections: a rival of rank r survives each random frame
// with probability 2^-r.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "learn/crc_catalogue.hpp"
#include "learn/genius_crc_learn.hpp"
#include "learn/ring_capture.hpp"
#include "learn/ring_crc_learn.hpp"
#include "learn/ring_layout_learn.hpp"
#include "trionet/genius.hpp"
#include "trionet/ring.hpp"

namespace ring = trionet::ring;
namespace genius = trionet::genius;
namespace learn = trionet::learn;
using clock_type = std::chrono::steady_clock;

namespace {

struct tally {
  std::vector<double> milliseconds;
  std::map<std::size_t, int> needed;  // frames needed -> count (0: not within the frames given)
  std::size_t runs = 0, ok = 0, validated = 0, validation_frames = 0;

  void add(const tally& other) {
    milliseconds.insert(milliseconds.end(), other.milliseconds.begin(), other.milliseconds.end());
    for (const auto& [k, n] : other.needed) needed[k] += n;
    runs += other.runs;
    ok += other.ok;
    validated += other.validated;
    validation_frames += other.validation_frames;
  }
  double median() {
    if (milliseconds.empty()) return 0;
    std::sort(milliseconds.begin(), milliseconds.end());
    return milliseconds[milliseconds.size() / 2];
  }
  double worst() const {
    return milliseconds.empty() ? 0 : *std::max_element(milliseconds.begin(), milliseconds.end());
  }
  std::string histogram() const {
    std::string out;
    for (const auto& [k, n] : needed) {
      out += (k == 0 ? std::string("more") : std::to_string(k)) + ":" + std::to_string(n) + " ";
    }
    return out;
  }
  std::size_t max_needed() const {
    return needed.count(0) != 0 ? 0 : (needed.empty() ? 0 : needed.rbegin()->first);
  }
};

std::vector<learn::sent_variable> random_sent(std::mt19937_64& rng, std::size_t count) {
  std::vector<learn::sent_variable> sent;
  for (std::size_t i = 0; i < count; ++i) {
    sent.push_back({static_cast<std::uint16_t>(rng() % 16384), static_cast<std::int64_t>(rng())});
  }
  return sent;
}

std::vector<learn::sent_variable> counting_sent(std::mt19937_64& rng, std::size_t count) {
  std::vector<learn::sent_variable> sent;
  const auto vr = static_cast<std::uint16_t>(rng() % 16384);
  const auto start = static_cast<std::int32_t>(rng() % 1000);
  for (std::size_t i = 0; i < count; ++i) {
    sent.push_back({vr, trionet::q32_from_integer(start + static_cast<std::int32_t>(i))});
  }
  return sent;
}

std::size_t decoded_correctly(const std::vector<learn::variable_frame>& frames,
                              const std::vector<learn::sent_variable>& sent, const ring::crc16_parameters& crc,
                              const ring::variable_layout_parameters& layout) {
  std::size_t good = 0;
  ring::with_variable_layout(layout, [&](auto policy) {
    ring::decoder<256, ring::crc16_runtime, decltype(policy)> d{ring::crc16_runtime(crc)};
    for (std::size_t i = 0; i < frames.size(); ++i) {
      (void)d.push(ring::make_header(1, 2));
      ring::decode_result last;
      for (std::uint8_t b : frames[i]) last = d.push(b);
      last = d.push(ring::make_end_of_message(1));
      good += last.status == ring::decode_status::ok && last.msg.vr == sent[i].vr &&
              last.msg.value == sent[i].value;
    }
  });
  return good;
}

// One hidden CRC: learn from `count` frames (timed), frames needed, validation.
void ring_run(tally& t, const ring::crc16_parameters& hidden, const ring::variable_layout_parameters& layout,
              std::mt19937_64& rng, bool counting, const learn::crc_learn_options& options, std::size_t count,
              std::size_t validation) {
  const auto sent = counting ? counting_sent(rng, count) : random_sent(rng, count);
  const auto frames = learn::encode_capture(sent, hidden, layout);
  learn::crc_learn_options o = options;
  o.layout = layout;
  std::size_t needed = 0;
  for (std::size_t k = 1; k <= count && needed == 0; ++k) {
    const std::vector<learn::variable_frame> first(frames.begin(), frames.begin() + static_cast<long>(k));
    if (learn::learn_ring_crc(first, o).status == learn::crc_learn_status::ok) needed = k;
  }
  const auto start = clock_type::now();
  const auto learned = learn::learn_ring_crc(frames, o);
  t.milliseconds.push_back(std::chrono::duration<double, std::milli>(clock_type::now() - start).count());
  ++t.runs;
  ++t.needed[needed];
  if (!learned) return;
  ++t.ok;
  if (validation == 0) return;
  const auto check_sent = random_sent(rng, validation);
  const auto check = learn::encode_capture(check_sent, hidden, layout);
  t.validated += decoded_correctly(check, check_sent, learned.classes[0].members[0].parameters, layout);
  t.validation_frames += validation;
}

void print_tally(const char* what, tally& t) {
  std::printf("  %-44s runs %5zu  ok %5zu  validation %zu/%zu  time median %.2f ms worst %.2f ms\n", what, t.runs,
              t.ok, t.validated, t.validation_frames, t.median(), t.worst());
  std::printf("  %-44s frames needed: %s(max %s)\n", "", t.histogram().c_str(),
              t.max_needed() == 0 ? "beyond the capture" : std::to_string(t.max_needed()).c_str());
}

// ---- Genius: static policies for the encoder ----

constexpr std::uint64_t mix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
template <std::size_t I>
struct drawn {
  static constexpr std::uint64_t h = mix(I + 1000);
  static constexpr genius::crc6_parameters parameters{static_cast<std::uint8_t>((h & 0x3f) | 1),
                                                      static_cast<std::uint8_t>((h >> 8) & 0x3f), ((h >> 16) & 1) != 0,
                                                      ((h >> 17) & 1) != 0, static_cast<std::uint8_t>((h >> 24) & 0x3f)};
  using type = genius::crc6<parameters.polynomial, parameters.initial, parameters.reflect_in, parameters.reflect_out,
                            parameters.xor_out>;
};

template <class Crc>
std::vector<learn::crc6_sample> genius_samples(std::mt19937_64& rng, int transmissions) {
  std::vector<genius::character> chars;
  for (int t = 0; t < transmissions; ++t) {
    std::vector<std::vector<std::uint8_t>> data(1 + rng() % 3);
    std::vector<genius::segment> segments;
    for (auto& bytes : data) {
      bytes.resize(1 + rng() % 12);
      for (auto& b : bytes) b = static_cast<std::uint8_t>(rng());
      segments.push_back({(rng() & 1) != 0, static_cast<std::uint8_t>(rng() % 32), {bytes.data(), bytes.size()}});
    }
    genius::transmission tx;
    tx.sender = static_cast<std::uint8_t>(rng() % 32);
    tx.broadcast = (rng() & 1) != 0;
    tx.destination = static_cast<std::uint8_t>(rng() % 32);
    tx.segments = {segments.data(), segments.size()};
    genius::character out[64];
    const auto encoded = genius::encode_transmission<Crc>(trionet::span<genius::character>(out), tx);
    chars.insert(chars.end(), out, out + encoded.length);
  }
  const auto found = learn::genius_crc_samples({chars.data(), chars.size()});
  std::vector<learn::crc6_sample> all = found.blocks;
  all.insert(all.end(), found.stops.begin(), found.stops.end());
  return all;
}

template <class Crc>
void genius_run(tally& t, std::mt19937_64& rng) {
  const auto samples = genius_samples<Crc>(rng, 8);
  std::size_t needed = 0;
  for (std::size_t k = 1; k <= samples.size() && needed == 0; ++k) {
    const std::vector<learn::crc6_sample> first(samples.begin(), samples.begin() + static_cast<long>(k));
    if (learn::learn_genius_crc(first).status == learn::crc_learn_status::ok) needed = k;
  }
  const auto start = clock_type::now();
  const auto learned = learn::learn_genius_crc(samples);
  t.milliseconds.push_back(std::chrono::duration<double, std::milli>(clock_type::now() - start).count());
  ++t.runs;
  ++t.needed[needed];
  if (!learned) return;
  ++t.ok;
  const genius::crc6_runtime crc(learned.classes[0].members[0].parameters);
  for (const auto& s : genius_samples<Crc>(rng, 100)) {
    t.validated += crc.compute({s.data.data(), s.data.size()}) == s.crc;
    ++t.validation_frames;
  }
}

template <std::size_t... I>
void genius_drawn(tally& t, std::mt19937_64& rng, std::index_sequence<I...>) {
  (genius_run<typename drawn<I>::type>(t, rng), ...);
}

// ---- rivals ----

std::uint16_t reverse16(std::uint16_t v) {
  std::uint16_t out = 0;
  for (unsigned i = 0; i < 16; ++i) out = static_cast<std::uint16_t>(out | (((v >> i) & 1u) << (15 - i)));
  return out;
}

// The images of the 78 valid message bits (default layout: X9's bits 6..1 excluded) on the 14 bits.
std::array<std::uint16_t, 78> valid_columns(std::uint16_t polynomial, bool reflect_in, bool reflect_out) {
  std::array<std::uint16_t, 96> power{};
  unsigned reg = polynomial;
  for (auto& p : power) {
    p = static_cast<std::uint16_t>(reg);
    reg = ((reg << 1) & 0xFFFFu) ^ ((reg & 0x8000u) != 0 ? polynomial : 0u);
  }
  std::array<std::uint16_t, 78> out{};
  std::size_t n = 0;
  for (std::size_t j = 0; j < 12; ++j) {
    for (std::size_t i = 0; i < 7; ++i) {
      if (j == 11 && i >= 1) continue;
      const std::size_t step = 8 * j + (reflect_in ? i : 7 - i);
      const std::uint16_t c = power[95 - step];
      out[n++] = static_cast<std::uint16_t>((reflect_out ? reverse16(c) : c) & 0x7F7F);
    }
  }
  return out;
}

int rank_of(const std::array<std::uint16_t, 78>& a, const std::array<std::uint16_t, 78>& b) {
  std::uint16_t basis[16] = {};
  int rank = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    std::uint16_t x = static_cast<std::uint16_t>(a[k] ^ b[k]);
    for (int bit = 15; bit >= 0 && x != 0; --bit) {
      if (((x >> bit) & 1u) == 0) continue;
      if (basis[bit] == 0) {
        basis[bit] = x;
        ++rank;
        break;
      }
      x = static_cast<std::uint16_t>(x ^ basis[bit]);
    }
  }
  return rank;
}

void rivals() {
  std::printf("\nclosest rivals (odd polynomials, all reflections; rank r survives a random frame with 2^-r):\n");
  for (const auto& e : learn::crc_catalogue()) {
    if (e.width != 16) continue;
    const auto truth = valid_columns(e.polynomial, e.reflect_in, e.reflect_out);
    std::map<int, int> ranks;
    for (int ri = 0; ri < 2; ++ri) {
      for (int ro = 0; ro < 2; ++ro) {
        for (unsigned p = 1; p <= 0xFFFF; p += 2) {
          if (p == e.polynomial && (ri != 0) == e.reflect_in && (ro != 0) == e.reflect_out) continue;
          ++ranks[rank_of(truth, valid_columns(static_cast<std::uint16_t>(p), ri != 0, ro != 0))];
        }
      }
    }
    std::printf("  %-26s closest rank %2d (%d of them); ranks below 14:", e.name.c_str(), ranks.begin()->first,
                ranks.begin()->second);
    for (const auto& [r, n] : ranks) {
      if (r < 14) std::printf(" %d:%d", r, n);
    }
    std::printf("\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, with_rivals = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) quick = true;
    else if (std::strcmp(argv[i], "--rivals") == 0) with_rivals = true;
    else {
      std::fprintf(stderr, "usage: trionet_learn_figures [--quick] [--rivals]\n");
      return 2;
    }
  }
  const std::size_t repeats = quick ? 2 : 10;
  const std::size_t random_sets = quick ? 100 : 1000;
  const std::size_t validation = quick ? 200 : 1000;
  std::mt19937_64 rng(2024);
  const ring::variable_layout_parameters orders[2] = {
      {}, {ring::group_order::most_significant_first, ring::group_order::most_significant_first, ring::crc_input::as_sent}};

  std::printf("ring CRC, 8 random frames learned, a separate capture of %zu frames decoded with the result\n",
              validation);
  tally catalogue_all;
  for (const auto& e : learn::crc_catalogue()) {
    if (e.width != 16) continue;
    tally t;
    for (const auto& layout : orders) {
      for (std::size_t r = 0; r < repeats; ++r) {
        ring_run(t, {e.polynomial, e.initial, e.reflect_in, e.reflect_out, e.xor_out}, layout, rng, false, {}, 8,
                 validation);
      }
    }
    std::printf("  %-26s ok %2zu/%2zu  frames needed %-16s median %.2f ms  worst %.2f ms\n", e.name.c_str(), t.ok,
                t.runs, t.histogram().c_str(), t.median(), t.worst());
    catalogue_all.add(t);
  }
  print_tally("catalogue (31 CRCs x 2 group orders)", catalogue_all);

  tally random_all;
  for (std::size_t r = 0; r < random_sets; ++r) {
    const ring::crc16_parameters hidden{static_cast<std::uint16_t>(rng() | 1), static_cast<std::uint16_t>(rng()),
                                        (r & 1) != 0, (r & 2) != 0, static_cast<std::uint16_t>(rng())};
    ring_run(random_all, hidden, orders[(r >> 2) & 1], rng, false, {}, 8, validation / 10);
  }
  print_tally("random parameter sets", random_all);

  tally counting;
  for (const auto& e : learn::crc_catalogue()) {
    if (e.width != 16) continue;
    for (std::size_t r = 0; r < repeats; ++r) {
      ring_run(counting, {e.polynomial, e.initial, e.reflect_in, e.reflect_out, e.xor_out}, orders[r & 1], rng, true,
               {}, 32, 0);
    }
  }
  print_tally("catalogue, one VR counting up (32 frames)", counting);

  learn::crc_learn_options with_even;
  with_even.even_polynomials = true;
  tally even;
  for (const auto& e : learn::crc_catalogue()) {
    if (e.width != 16) continue;
    for (std::size_t r = 0; r < repeats; ++r) {
      ring_run(even, {e.polynomial, e.initial, e.reflect_in, e.reflect_out, e.xor_out}, orders[r & 1], rng, false,
               with_even, 32, 0);
    }
  }
  print_tally("catalogue, even polynomials admitted (32)", even);

  // The calls that cannot decide: one and two frames.
  for (std::size_t count : {1u, 2u}) {
    std::vector<double> ms;
    std::map<std::string, int> statuses;
    std::size_t classes = 0;
    for (std::size_t r = 0; r < (quick ? 5u : 20u); ++r) {
      const auto frames = learn::encode_capture(random_sent(rng, count), ring::crc16_parameters{});
      const auto start = clock_type::now();
      const auto learned = learn::learn_ring_crc(frames);
      ms.push_back(std::chrono::duration<double, std::milli>(clock_type::now() - start).count());
      ++statuses[learn::to_string(learned.status)];
      classes += learned.classes.size();
    }
    std::sort(ms.begin(), ms.end());
    std::printf("  %zu frame(s): ", count);
    for (const auto& [s, n] : statuses) std::printf("%s x%d ", s.c_str(), n);
    std::printf(" mean classes listed %.1f  median %.2f ms  worst %.2f ms\n",
                static_cast<double>(classes) / static_cast<double>(ms.size()), ms[ms.size() / 2], ms.back());
  }

  std::printf("\nlayout, 4 random frames and the sent list (CRC learned both ways when an order is not the default)\n");
  std::map<std::string, int> layout_outcomes;
  int layout_right = 0, layout_runs = 0;
  std::vector<learn::catalogue_entry> sixteen;
  for (const auto& e : learn::crc_catalogue()) {
    if (e.width == 16) sixteen.push_back(e);
  }
  for (std::size_t r = 0; r < (quick ? 50u : 500u); ++r) {
    const ring::variable_layout_parameters layout{
        (r & 1) != 0 ? ring::group_order::most_significant_first : ring::group_order::least_significant_first,
        (r & 2) != 0 ? ring::group_order::most_significant_first : ring::group_order::least_significant_first,
        (r & 4) != 0 && (r & 3) != 0 ? ring::crc_input::least_significant_first : ring::crc_input::as_sent};
    const auto& e = sixteen[r % sixteen.size()];
    const auto sent = random_sent(rng, 4);
    const auto frames = learn::encode_capture(sent, {e.polynomial, e.initial, e.reflect_in, e.reflect_out, e.xor_out},
                                              layout);
    const auto learned = learn::learn_layout(frames, sent);
    ++layout_runs;
    ++layout_outcomes[std::string(learn::to_string(learned.status)) + "/" + learn::to_string(learned.crc)];
    layout_right += learned && learned.layout == layout;
  }
  std::printf("  right layout (both orders and the CRC input) %d/%d;", layout_right, layout_runs);
  for (const auto& [s, n] : layout_outcomes) std::printf(" %s x%d", s.c_str(), n);
  std::printf("\n");

  std::printf("\nGenius CRC-6, samples from 8 transmissions (blocks and stops), 100 more transmissions checked\n");
  tally genius_all;
  for (std::size_t r = 0; r < repeats; ++r) {
    genius_run<genius::crc6<0x27, 0x3f, false, false, 0x00>>(genius_all, rng);
    genius_run<genius::crc6<0x07, 0x3f, false, false, 0x00>>(genius_all, rng);
    genius_run<genius::crc6<0x19, 0x00, true, true, 0x00>>(genius_all, rng);
    genius_run<genius::crc6_g704>(genius_all, rng);
    genius_run<genius::crc6<0x2f, 0x00, false, false, 0x3f>>(genius_all, rng);
    genius_drawn(genius_all, rng, std::make_index_sequence<32>{});
  }
  print_tally("5 catalogue + 32 drawn CRC-6", genius_all);

  if (with_rivals) rivals();
  return 0;
}

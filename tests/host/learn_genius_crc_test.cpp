// Learning the Genius CRC-6 (src/learn/genius_crc_learn.hpp) from transmissions made by the library's own
// encoder under hidden CRCs: the CRC RevEng catalogue's 6-bit CRCs and pseudo-random ones.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "learn/crc_catalogue.hpp"
#include "learn/genius_crc_learn.hpp"
#include "trionet/genius.hpp"

namespace genius = trionet::genius;
namespace learn = trionet::learn;
using trionet::byte_view;

namespace {

constexpr std::uint8_t check_bytes[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};

// The catalogue's CRC-6 as static policies (for the encoder), in catalogue order.
using cdma2000_a = genius::crc6<0x27, 0x3f, false, false, 0x00>;
using cdma2000_b = genius::crc6<0x07, 0x3f, false, false, 0x00>;
using darc = genius::crc6<0x19, 0x00, true, true, 0x00>;
using g704 = genius::crc6_g704;
using gsm = genius::crc6<0x2f, 0x00, false, false, 0x3f>;

// Pseudo-random parameters drawn from an index (the same at compile time and at run time).
constexpr std::uint64_t mix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
constexpr genius::crc6_parameters drawn_parameters(std::size_t i) {
  const std::uint64_t h = mix(i + 6);
  return {static_cast<std::uint8_t>((h & 0x3f) | 1), static_cast<std::uint8_t>((h >> 8) & 0x3f),
          ((h >> 16) & 1) != 0, ((h >> 17) & 1) != 0, static_cast<std::uint8_t>((h >> 24) & 0x3f)};
}
// A few of them as static policies too, to check the run-time CRC against.
template <std::size_t I>
struct drawn {
  static constexpr genius::crc6_parameters parameters = drawn_parameters(I);
  using type = genius::crc6<parameters.polynomial, parameters.initial, parameters.reflect_in,
                            parameters.reflect_out, parameters.xor_out>;
};

// Random transmissions encoded with `crc` (a static policy or a crc6_runtime): broadcast or directed, one to
// three segments, plain data or blocks, 1..12 data bytes each.
template <class Crc>
std::vector<genius::character> transmissions(std::mt19937_64& rng, int count, const Crc& crc = Crc{}) {
  std::vector<genius::character> out;
  for (int t = 0; t < count; ++t) {
    std::vector<std::vector<std::uint8_t>> data;
    std::vector<genius::segment> segments;
    const int n = 1 + static_cast<int>(rng() % 3);
    data.resize(static_cast<std::size_t>(n));
    for (int s = 0; s < n; ++s) {
      auto& bytes = data[static_cast<std::size_t>(s)];
      bytes.resize(1 + rng() % 12);
      for (auto& b : bytes) b = static_cast<std::uint8_t>(rng());
      genius::segment seg;
      seg.block = (rng() & 1) != 0;
      seg.destination = static_cast<std::uint8_t>(rng() % 32);
      seg.data = byte_view(bytes.data(), bytes.size());
      segments.push_back(seg);
    }
    genius::transmission tx;
    tx.sender = static_cast<std::uint8_t>(rng() % 32);
    tx.broadcast = (rng() & 1) != 0;
    tx.destination = static_cast<std::uint8_t>(rng() % 32);
    tx.segments = trionet::span<const genius::segment>(segments.data(), segments.size());
    std::vector<genius::character> chars(64);
    const auto encoded =
        genius::encode_transmission(trionet::span<genius::character>(chars.data(), chars.size()), tx, crc);
    EXPECT_TRUE(encoded);
    out.insert(out.end(), chars.begin(), chars.begin() + static_cast<long>(encoded.length));
  }
  return out;
}

// Every CRC sample of the characters, blocks and stops in the order they close.
std::vector<learn::crc6_sample> samples_of(const std::vector<genius::character>& chars) {
  const auto found =
      learn::genius_crc_samples(trionet::span<const genius::character>(chars.data(), chars.size()));
  EXPECT_EQ(found.skipped_characters, 0u);
  std::vector<learn::crc6_sample> all = found.blocks;
  all.insert(all.end(), found.stops.begin(), found.stops.end());
  return all;
}

bool equivalent(const genius::crc6_parameters& a, const genius::crc6_parameters& b, std::mt19937_64& rng) {
  const genius::crc6_runtime ca(a), cb(b);
  std::vector<std::uint8_t> m;
  for (int k = 0; k < 400; ++k) {
    m.resize(1 + rng() % 40);
    for (auto& byte : m) byte = static_cast<std::uint8_t>(rng());
    if (ca.compute(byte_view(m.data(), m.size())) != cb.compute(byte_view(m.data(), m.size()))) return false;
  }
  return true;
}

struct outcome {
  learn::crc6_learn_result learned;
  std::size_t samples_needed = 0;
  std::size_t validated = 0;
  std::size_t validation_samples = 0;
};

template <class Crc>
outcome learn_and_validate(const Crc& crc, const genius::crc6_parameters& hidden, std::mt19937_64& rng) {
  outcome o;
  const auto samples = samples_of(transmissions(rng, 6, crc));
  for (std::size_t k = 2; k <= samples.size() && o.samples_needed == 0; ++k) {  // one sample fits every CRC
    const std::vector<learn::crc6_sample> first(samples.begin(), samples.begin() + static_cast<long>(k));
    if (learn::learn_genius_crc(first).status == learn::crc_learn_status::ok) o.samples_needed = k;
  }
  o.learned = learn::learn_genius_crc(samples);
  if (!o.learned) return o;
  EXPECT_TRUE(equivalent(o.learned.classes[0].members[0].parameters, hidden, rng));
  // A separate capture: every Stop and End of block verifies with what was learned.
  const auto validation = samples_of(transmissions(rng, 50, crc));
  const genius::crc6_runtime learned(o.learned.classes[0].members[0].parameters);
  o.validation_samples = validation.size();
  for (const auto& s : validation)
    o.validated += learned.compute(byte_view(s.data.data(), s.data.size())) == s.crc;
  return o;
}

template <class Crc>
void check_against_policy(const genius::crc6_parameters& p, std::mt19937_64& rng) {
  const genius::crc6_runtime runtime(p);
  std::vector<std::uint8_t> m;
  for (int k = 0; k < 50; ++k) {
    m.resize(rng() % 30);
    for (auto& byte : m) byte = static_cast<std::uint8_t>(rng());
    ASSERT_EQ(runtime.compute(byte_view(m.data(), m.size())), Crc::compute(byte_view(m.data(), m.size())));
  }
}

}  // namespace

TEST(LearnGeniusCrc, TheRuntimeCrcMatchesTheCatalogueAndTheStaticPolicies) {
  std::mt19937_64 rng(40);
  std::map<std::string, genius::crc6_parameters> by_name;
  for (const auto& e : learn::crc_catalogue()) {
    if (e.width != 6) continue;
    const genius::crc6_parameters p{static_cast<std::uint8_t>(e.polynomial),
                                    static_cast<std::uint8_t>(e.initial), e.reflect_in, e.reflect_out,
                                    static_cast<std::uint8_t>(e.xor_out)};
    EXPECT_EQ(genius::crc6_runtime(p).compute(check_bytes), e.check) << e.name;
    by_name[e.name] = p;
  }
  ASSERT_EQ(by_name.size(), 5u);
  EXPECT_EQ(by_name["CRC-6/G-704"], genius::crc6_parameters{});  // the Genius default
  check_against_policy<cdma2000_a>(by_name["CRC-6/CDMA2000-A"], rng);
  check_against_policy<cdma2000_b>(by_name["CRC-6/CDMA2000-B"], rng);
  check_against_policy<darc>(by_name["CRC-6/DARC"], rng);
  check_against_policy<g704>(by_name["CRC-6/G-704"], rng);
  check_against_policy<gsm>(by_name["CRC-6/GSM"], rng);
  check_against_policy<drawn<1>::type>(drawn<1>::parameters, rng);
  check_against_policy<drawn<2>::type>(drawn<2>::parameters, rng);
  check_against_policy<drawn<3>::type>(drawn<3>::parameters, rng);
}

TEST(LearnGeniusCrc, SamplesAreTheStopsAndBlocksOfEachTransmission) {
  const std::uint8_t plain[] = {1, 2, 3};
  const std::uint8_t inside[] = {9, 8};
  const genius::segment segments[] = {{false, 0, byte_view(plain)}, {true, 7, byte_view(inside)}};
  genius::transmission tx;
  tx.sender = 4;
  tx.broadcast = false;
  tx.destination = 12;
  tx.segments = trionet::span<const genius::segment>(segments);
  genius::character chars[16];
  const auto encoded = genius::encode_transmission(trionet::span<genius::character>(chars), tx);
  ASSERT_TRUE(encoded);
  std::vector<genius::character> stream = {genius::data_character(5)};  // stray data first
  stream.insert(stream.end(), chars, chars + encoded.length);
  const auto found =
      learn::genius_crc_samples(trionet::span<const genius::character>(stream.data(), stream.size()));
  EXPECT_EQ(found.skipped_characters, 1u);
  ASSERT_EQ(found.stops.size(), 1u);
  ASSERT_EQ(found.blocks.size(), 1u);
  EXPECT_EQ(found.stops[0].data, (std::vector<std::uint8_t>{12, 1, 2, 3, 9, 8}));  // the destination SBA too
  EXPECT_EQ(found.stops[0].crc, genius::crc6_g704::compute(byte_view(found.stops[0].data.data(), 6)));
  EXPECT_EQ(found.blocks[0].data, (std::vector<std::uint8_t>{9, 8}));
  // A transmission cut short by the next Start is skipped whole.
  std::vector<genius::character> cut(chars, chars + encoded.length - 1);
  cut.insert(cut.end(), chars, chars + encoded.length);
  const auto again =
      learn::genius_crc_samples(trionet::span<const genius::character>(cut.data(), cut.size()));
  EXPECT_EQ(again.stops.size(), 1u);
  EXPECT_EQ(again.blocks.size(), 2u);  // the block closed before the cut is still a sample
  EXPECT_EQ(again.skipped_characters, encoded.length - 1);
}

TEST(LearnGeniusCrc, EveryCatalogueCrcAndDrawnOnesAreLearnedBack) {
  std::mt19937_64 rng(41);
  std::map<std::size_t, int> needed;
  const auto run = [&](const auto& crc, const genius::crc6_parameters& hidden, const char* name) {
    const outcome o = learn_and_validate(crc, hidden, rng);
    ASSERT_EQ(o.learned.status, trionet::learn::crc_learn_status::ok) << name;
    EXPECT_EQ(o.learned.rejected, 0u);
    EXPECT_GT(o.validation_samples, 50u);
    EXPECT_EQ(o.validated, o.validation_samples) << name;
    EXPECT_NE(o.samples_needed, 0u) << name;  // 0: not within the capture
    EXPECT_LE(o.samples_needed, 8u) << name;
    ++needed[o.samples_needed];
  };
  run(cdma2000_a{}, {0x27, 0x3f, false, false, 0x00}, "CRC-6/CDMA2000-A");
  run(cdma2000_b{}, {0x07, 0x3f, false, false, 0x00}, "CRC-6/CDMA2000-B");
  run(darc{}, {0x19, 0x00, true, true, 0x00}, "CRC-6/DARC");
  run(g704{}, {0x03, 0x00, true, true, 0x00}, "CRC-6/G-704");
  run(gsm{}, {0x2f, 0x00, false, false, 0x3f}, "CRC-6/GSM");
  // The drawn ones with the run-time CRC (checked against static policies above).
  for (std::size_t i = 0; i < 32; ++i) run(genius::crc6_runtime(drawn_parameters(i)), drawn_parameters(i), "drawn");
  std::string histogram;
  for (const auto& [samples, count] : needed)
    histogram += std::to_string(samples) + ": " + std::to_string(count) + "  ";
  std::printf("samples needed over 5 catalogue + 32 drawn CRC-6: %s\n", histogram.c_str());
}

TEST(LearnGeniusCrc, TheCatalogueNamesTheLearnedCrc) {
  std::mt19937_64 rng(42);
  const auto samples = samples_of(transmissions<g704>(rng, 6));
  const auto learned = learn::learn_genius_crc(samples);
  ASSERT_TRUE(learned);
  EXPECT_EQ(learned.classes[0].members[0].name, "CRC-6/G-704");
  EXPECT_EQ(learned.classes[0].members[0].parameters, genius::crc6_parameters{});
}

TEST(LearnGeniusCrc, OneLengthCannotTellInitFromXorout) {
  std::mt19937_64 rng(43);
  std::vector<learn::crc6_sample> samples;
  const genius::crc6_runtime crc(genius::crc6_parameters{0x2f, 0x15, false, false, 0x3f});
  for (int i = 0; i < 12; ++i) {
    learn::crc6_sample s;
    s.data.resize(5);
    for (auto& b : s.data) b = static_cast<std::uint8_t>(rng());
    s.crc = crc.compute(byte_view(s.data.data(), s.data.size()));
    samples.push_back(s);
  }
  const auto one_length = learn::learn_genius_crc(samples);
  EXPECT_EQ(one_length.status, learn::crc_learn_status::ambiguous);
  // Every init fits, each with its xorout: 64 pairs. The generator x^6 + x^5 + x^3 + x^2 + x + 1 is
  // divisible by x + 1, so two inits that differ by G / (x + 1) give the same CRC on every length (that
  // difference times x^8 + 1 = (x + 1)^8 is 0 mod G): 32 classes of two.
  ASSERT_EQ(one_length.classes.size(), 32u);
  for (const auto& c : one_length.classes) EXPECT_EQ(c.members.size(), 2u);
  // One sample of another length settles it.
  learn::crc6_sample longer;
  longer.data = {1, 2, 3, 4, 5, 6, 7};
  longer.crc = crc.compute(byte_view(longer.data.data(), longer.data.size()));
  samples.push_back(longer);
  const auto two_lengths = learn::learn_genius_crc(samples);
  ASSERT_EQ(two_lengths.status, learn::crc_learn_status::ok);
  EXPECT_EQ(two_lengths.classes[0].members[0].parameters,
            (genius::crc6_parameters{0x2f, 0x15, false, false, 0x3f}));
}

TEST(LearnGeniusCrc, BadSamplesAndNoCandidate) {
  EXPECT_EQ(learn::learn_genius_crc({}).status, learn::crc_learn_status::no_frames);
  std::vector<learn::crc6_sample> samples = {{{1, 2}, 5}, {{}, 3}};
  auto bad = learn::learn_genius_crc(samples);
  EXPECT_EQ(bad.status, learn::crc_learn_status::bad_frame);
  EXPECT_EQ(bad.bad_sample_index, 1u);
  samples[1] = {{4}, 64};
  EXPECT_EQ(learn::learn_genius_crc(samples).status, learn::crc_learn_status::bad_frame);
  // The same data with two different CRCs: nothing fits.
  samples = {{{1, 2, 3}, 5}, {{1, 2, 3}, 6}};
  EXPECT_EQ(learn::learn_genius_crc(samples).status, learn::crc_learn_status::no_candidate);
}

// Repeated samples say nothing more: the search runs over the distinct ones, so a capture of a few
// transmissions repeated many times learns what the few give (s37 item 8: 3,125,000 copies of one sample
// took 18 minutes). The outcome is the same with and without the repeats; the count is of the distinct.
TEST(LearnGeniusCrc, RepeatedSamplesAreSearchedOnceAndChangeNothing) {
  std::mt19937_64 rng(44);
  const auto few = samples_of(transmissions<g704>(rng, 6));
  std::vector<learn::crc6_sample> many;
  for (int copy = 0; copy < 20000; ++copy) many.insert(many.end(), few.begin(), few.end());
  const auto once = learn::learn_genius_crc(few);
  const auto repeated = learn::learn_genius_crc(many);
  ASSERT_TRUE(once);
  ASSERT_TRUE(repeated);
  EXPECT_EQ(repeated.samples, many.size());
  EXPECT_EQ(repeated.distinct_samples, once.distinct_samples);
  EXPECT_LE(repeated.distinct_samples, few.size());
  EXPECT_EQ(repeated.survivors, once.survivors);
  EXPECT_EQ(repeated.classes[0].members[0].parameters, genius::crc6_parameters{});
  // One sample repeated: as one sample (every init with its xorout fits: too many classes to name).
  const std::vector<learn::crc6_sample> one(50000, few[0]);
  const auto single = learn::learn_genius_crc(one);
  EXPECT_EQ(single.distinct_samples, 1u);
  EXPECT_EQ(single.survivors, learn::learn_genius_crc({few[0]}).survivors);
  EXPECT_EQ(single.status, learn::learn_genius_crc({few[0]}).status);
}

#include "learn/genius_crc_learn.hpp"

#include <algorithm>
#include <map>

#include "learn/gf2.hpp"
#include "trionet/genius/transmission.hpp"

namespace trionet::learn {
namespace {

constexpr unsigned width = 6;
constexpr unsigned top_bit = 1u << (width - 1);
constexpr unsigned mask = (1u << width) - 1;

// The non-reflected register after `data` (each byte most significant bit first, or least significant
// first when reflected in), from `reg`.
unsigned feed(unsigned reg, unsigned polynomial, bool reflect_in, const std::vector<std::uint8_t>& data) {
  for (std::uint8_t byte : data) {
    for (unsigned k = 0; k < 8; ++k) {
      const unsigned value = byte;
      const unsigned bit = reflect_in ? (value >> k) & 1u : (value >> (7 - k)) & 1u;
      const unsigned top = ((reg & top_bit) != 0 ? 1u : 0u) ^ bit;
      reg = (reg << 1) & mask;
      if (top != 0) reg ^= polynomial;
    }
  }
  return reg;
}

unsigned output(unsigned reg, bool reflect_out) {
  return reflect_out ? reflect_bits(static_cast<std::uint16_t>(reg), width) : reg;
}

// What a parameter set does to every message of 1..max_length bytes: the output image of each message bit
// (byte b from the end, bit i), which does not depend on the length, and the constant for each length.
// Bit i of the byte b from the end is fed 8b + i steps before the end (8b + 7 - i when reflected in), so it
// contributes x^(6 + that) mod the generator.
std::vector<std::uint16_t> signature_of(const genius::crc6_parameters& p, std::size_t max_length) {
  std::vector<std::uint16_t> power(8 * max_length);
  unsigned reg = p.polynomial;  // x^6 mod (x^6 + polynomial)
  for (auto& entry : power) {
    entry = static_cast<std::uint16_t>(reg);
    reg = ((reg << 1) & mask) ^ ((reg & top_bit) != 0 ? p.polynomial : 0u);
  }
  std::vector<std::uint16_t> s;
  s.reserve(9 * max_length);
  for (std::size_t b = 0; b < max_length; ++b) {
    for (std::size_t i = 0; i < 8; ++i) {
      s.push_back(
          static_cast<std::uint16_t>(output(power[8 * b + (p.reflect_in ? 7 - i : i)], p.reflect_out)));
    }
  }
  reg = p.initial;
  for (std::size_t n = 1; n <= max_length; ++n) {
    for (int k = 0; k < 8; ++k) reg = ((reg << 1) & mask) ^ ((reg & top_bit) != 0 ? p.polynomial : 0u);
    s.push_back(static_cast<std::uint16_t>(output(reg, p.reflect_out) ^ p.xor_out));
  }
  return s;
}

}  // namespace

sample_extraction genius_crc_samples(span<const genius::character> characters, const genius::control_layout& layout) {
  sample_extraction out;
  bool open = false, in_block = false;
  std::size_t pending = 0;  // characters of the open transmission, skipped if it breaks
  crc6_sample stop, block;
  const auto abandon = [&] {
    out.skipped_characters += pending;
    pending = 0;
    open = in_block = false;
  };
  for (const genius::character& c : characters) {
    if (!c.control) {
      if (!open) {
        ++out.skipped_characters;
        continue;
      }
      ++pending;
      stop.data.push_back(c.byte);
      if (in_block) block.data.push_back(c.byte);
      continue;
    }
    const genius::control_fields f = genius::read_control(c.byte, layout);
    switch (f.kind) {
      case genius::control_kind::start:
        abandon();
        open = true;
        pending = 1;
        stop.data.clear();
        break;
      case genius::control_kind::start_of_block:
        if (!open || in_block) {
          abandon();
          ++out.skipped_characters;
          break;
        }
        ++pending;
        in_block = true;
        block.data.clear();
        break;
      case genius::control_kind::end_of_block:
        if (!open || !in_block || block.data.empty()) {
          abandon();
          ++out.skipped_characters;
          break;
        }
        ++pending;
        in_block = false;
        block.crc = f.crc;
        out.blocks.push_back(block);
        break;
      case genius::control_kind::stop:
        if (!open || in_block || stop.data.empty()) {
          abandon();
          ++out.skipped_characters;
          break;
        }
        stop.crc = f.crc;
        out.stops.push_back(stop);
        pending = 0;
        open = false;
        break;
      case genius::control_kind::unknown:
        abandon();
        ++out.skipped_characters;
        break;
    }
  }
  abandon();
  return out;
}

namespace {
crc6_learn_result search(const std::vector<crc6_sample>& samples, const crc6_learn_options& options,
                         crc6_learn_result& result);
}  // namespace

crc6_learn_result learn_genius_crc(const std::vector<crc6_sample>& samples,
                                   const crc6_learn_options& options) {
  crc6_learn_result result;
  result.samples = samples.size();
  if (samples.empty()) return result;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (samples[i].data.empty() || samples[i].crc > mask) {
      result.status = crc_learn_status::bad_frame;
      result.bad_sample_index = i;
      return result;
    }
  }
  // A sample repeated says nothing more: the search and the final check run over distinct samples only
  // (in the order they first came), so that a capture of one transmission repeated costs what one costs.
  std::vector<std::size_t> order(samples.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto same = [&](std::size_t a, std::size_t b) {
    return samples[a].crc == samples[b].crc && samples[a].data == samples[b].data;
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (samples[a].crc != samples[b].crc) return samples[a].crc < samples[b].crc;
    return samples[a].data < samples[b].data;
  });
  std::vector<bool> repeated(samples.size(), false);
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (same(order[k - 1], order[k])) repeated[order[k]] = true;
  }
  std::vector<crc6_sample> distinct_samples;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!repeated[i]) distinct_samples.push_back(samples[i]);
  }
  result.distinct_samples = distinct_samples.size();
  return search(distinct_samples, options, result);
}

namespace {
crc6_learn_result search(const std::vector<crc6_sample>& samples, const crc6_learn_options& options,
                         crc6_learn_result& result) {
  std::vector<genius::crc6_parameters> survivors;
  for (unsigned polynomial = 0; polynomial <= mask; ++polynomial) {
    if (options.progress) options.progress(polynomial, mask + 1);
    if (!options.even_polynomials && (polynomial & 1u) == 0) continue;
    for (bool reflect_in : {false, true}) {
      for (bool reflect_out : {false, true}) {
        for (unsigned initial = 0; initial <= mask; ++initial) {
          const unsigned xor_out =
              output(feed(initial, polynomial, reflect_in, samples[0].data), reflect_out) ^ samples[0].crc;
          bool fits = true;
          for (std::size_t i = 1; i < samples.size() && fits; ++i) {
            fits = (output(feed(initial, polynomial, reflect_in, samples[i].data), reflect_out) ^ xor_out) ==
                   samples[i].crc;
          }
          if (fits) {
            survivors.push_back({static_cast<std::uint8_t>(polynomial), static_cast<std::uint8_t>(initial),
                                 reflect_in, reflect_out, static_cast<std::uint8_t>(xor_out)});
          }
        }
      }
    }
  }
  result.survivors = survivors.size();
  if (survivors.empty()) {
    result.status = crc_learn_status::no_candidate;
    return result;
  }
  // Collapse by signature; a cheap lower bound first (distinct one-byte signatures are distinct classes),
  // so that one or two samples do not build thousands of long signatures.
  {
    std::vector<std::vector<std::uint16_t>> prefixes;
    for (const auto& p : survivors) prefixes.push_back(signature_of(p, 1));
    std::sort(prefixes.begin(), prefixes.end());
    const auto distinct =
        static_cast<std::size_t>(std::unique(prefixes.begin(), prefixes.end()) - prefixes.begin());
    if (distinct > options.max_classes) {
      result.status = crc_learn_status::too_many_candidates;
      return result;
    }
  }
  std::map<std::vector<std::uint16_t>, crc6_class> classes;
  for (const auto& p : survivors) {
    crc6_member m{p, {}};
    if (options.catalogue != nullptr) {
      for (const catalogue_entry& e : *options.catalogue) {
        if (e.width == width && e.polynomial == p.polynomial && e.initial == p.initial &&
            e.reflect_in == p.reflect_in && e.reflect_out == p.reflect_out && e.xor_out == p.xor_out) {
          m.name = e.name;
        }
      }
    }
    const genius::crc6_runtime crc(p);
    bool all = true;
    for (const auto& s : samples) all = all && crc.compute(byte_view(s.data.data(), s.data.size())) == s.crc;
    if (!all) {
      ++result.rejected;
      continue;
    }
    classes[signature_of(p, options.max_length)].members.push_back(std::move(m));
  }
  if (classes.size() > options.max_classes) {
    result.status = crc_learn_status::too_many_candidates;
    return result;
  }
  for (auto& entry : classes) result.classes.push_back(std::move(entry.second));
  finish_classes(result);
  return result;
}
}  // namespace

}  // namespace trionet::learn

#include "learn/ring_crc_learn.hpp"

#include <algorithm>

#include "learn/gf2.hpp"
#include "trionet/ring/bytes.hpp"

namespace trionet::learn {
namespace {

constexpr std::uint16_t wire_mask = 0x7F7F;  // the CRC bits that travel: 14..8 and 6..0
constexpr std::size_t message_bytes = 12;
constexpr std::size_t message_bits = 8 * message_bytes;
using message = std::array<std::uint8_t, message_bytes>;

std::uint16_t output(std::uint16_t reg, bool reflect_out) {
  return reflect_out ? reflect_bits16(reg) : reg;
}

// The register of the non-reflected model after the bits of `m` (each byte most significant bit first),
// starting from 0: the part of the CRC that is linear in the message.
std::uint16_t linear_part(std::uint16_t polynomial, const message& m) {
  unsigned reg = 0;
  for (std::uint8_t byte : m) {
    reg ^= static_cast<unsigned>(byte) << 8;
    for (int k = 0; k < 8; ++k) reg = ((reg << 1) & 0xFFFFu) ^ (polynomial & (0u - ((reg >> 15) & 1u)));
  }
  return static_cast<std::uint16_t>(reg);
}

// The register after twelve zero bytes from `initial`: the part that is linear in init.
std::uint16_t initial_part(std::uint16_t polynomial, std::uint16_t initial) {
  unsigned reg = initial;
  for (std::size_t k = 0; k < message_bits; ++k)
    reg = ((reg << 1) & 0xFFFFu) ^ (polynomial & (0u - ((reg >> 15) & 1u)));
  return static_cast<std::uint16_t>(reg);
}

// The 12 bytes the CRC covers, each byte's bits reversed when the input is reflected (the model then feeds
// them to the same non-reflected register).
message covered(const variable_frame& frame, const ring::variable_layout_parameters& layout,
                bool reflect_in) {
  message m{};
  if (layout.crc == ring::crc_input::least_significant_first) {
    ring::reorder_variable_fields(frame.data(), m.data(), layout.vr, layout.value);
  } else {
    std::copy(frame.begin(), frame.begin() + message_bytes, m.begin());
  }
  if (reflect_in) {
    for (auto& byte : m) byte = reflect_bits8(byte);
  }
  return m;
}

message exclusive_or(const message& a, const message& b) {
  message out{};
  for (std::size_t i = 0; i < message_bytes; ++i) out[i] = static_cast<std::uint8_t>(a[i] ^ b[i]);
  return out;
}

struct hypothesis {
  std::uint16_t polynomial;
  bool reflect_in;
  bool reflect_out;
  std::uint16_t constant;  // the 14 transmitted bits of the CRC of twelve zero bytes
};

// The message bits a valid direct variable transfer can vary: bits 6..0 of every byte, but only bit 0 of the
// value's top group (its bits 6..1 are zero in every valid frame). `top` is that group's index among the
// bytes the CRC covers.
bool valid_bit(std::size_t byte, std::size_t bit, std::size_t top) {
  return bit < 7 && (byte != top || bit == 0);
}
constexpr std::size_t valid_bits = 12 * 7 - 6;

// What a hypothesis does to every valid frame, on the 14 bits that travel: the image of each valid message
// bit and the constant. Two hypotheses with the same signature give the same C0 C1 for every valid frame.
using signature = std::array<std::uint16_t, valid_bits + 1>;

// x^(16 + k) mod the generator, k = 0..count-1: the end contribution of the message bit fed k steps before
// the last.
template <std::size_t Count>
std::array<std::uint16_t, Count> powers(std::uint16_t polynomial) {
  std::array<std::uint16_t, Count> power{};
  unsigned reg = polynomial;  // x^16 mod (x^16 + polynomial)
  for (std::size_t k = 0; k < Count; ++k) {
    power[k] = static_cast<std::uint16_t>(reg);
    reg = ((reg << 1) & 0xFFFFu) ^ (polynomial & (0u - ((reg >> 15) & 1u)));
  }
  return power;
}

std::size_t step_of(std::size_t byte, std::size_t bit, bool reflect_in) {
  return 8 * byte + (reflect_in ? bit : 7 - bit);
}

signature signature_of(const hypothesis& h, std::size_t top) {
  const auto power = powers<message_bits>(h.polynomial);
  signature s{};
  std::size_t n = 0;
  for (std::size_t j = 0; j < message_bytes; ++j) {
    for (std::size_t i = 0; i < 8; ++i) {
      if (!valid_bit(j, i, top)) continue;
      const std::uint16_t column = power[message_bits - 1 - step_of(j, i, h.reflect_in)];
      s[n++] = static_cast<std::uint16_t>(output(column, h.reflect_out) & wire_mask);
    }
  }
  s[valid_bits] = h.constant;
  return s;
}

// A hash of part of the signature (the last two bytes' columns and the constant): equal signatures have
// equal hashes, and it costs 16 shift steps instead of 96.
std::uint64_t hash_of(const hypothesis& h, std::size_t top) {
  const auto power = powers<16>(h.polynomial);
  std::uint64_t hash = 0xcbf29ce484222325ull ^ h.constant;  // FNV-1a over 16-bit words
  for (std::size_t j = message_bytes - 2; j < message_bytes; ++j) {
    for (std::size_t i = 0; i < 8; ++i) {
      if (!valid_bit(j, i, top)) continue;
      const std::uint16_t column = power[message_bits - 1 - step_of(j, i, h.reflect_in)];
      hash = (hash ^ (output(column, h.reflect_out) & wire_mask)) * 0x100000001b3ull;
    }
  }
  return hash;
}

// 64 polynomials at once (base .. base + 63), one bit of each word per polynomial: the register of the
// non-reflected model after the bits of `m` from 0, as 16 words (bit j of every register in word j).
using sliced = std::array<std::uint64_t, 16>;

sliced sliced_linear_part(unsigned base, const message& m) {
  static constexpr std::uint64_t low_bits[6] = {0xAAAAAAAAAAAAAAAAull, 0xCCCCCCCCCCCCCCCCull,
                                                0xF0F0F0F0F0F0F0F0ull, 0xFF00FF00FF00FF00ull,
                                                0xFFFF0000FFFF0000ull, 0xFFFFFFFF00000000ull};
  sliced polynomial{};
  for (unsigned j = 0; j < 16; ++j) {
    polynomial[j] = j < 6 ? low_bits[j] : (((base >> j) & 1u) != 0 ? ~0ull : 0ull);
  }
  sliced reg{};
  for (std::uint8_t byte : m) {
    for (int bit = 7; bit >= 0; --bit) {
      const std::uint64_t top = reg[15] ^ (((static_cast<unsigned>(byte) >> bit) & 1u) != 0 ? ~0ull : 0ull);
      for (unsigned j = 15; j > 0; --j) reg[j] = reg[j - 1] ^ (top & polynomial[j]);
      reg[0] = top & polynomial[0];
    }
  }
  return reg;
}

// The polynomials of a batch whose register, output reflected or not, has `want` in the 14 bits that travel:
// bit 0 of the result for reflect_out false, bit 1 of each... as two masks.
std::array<std::uint64_t, 2> sliced_matches(const sliced& reg, std::uint16_t want) {
  std::uint64_t wrong[2] = {0, 0};
  for (unsigned j = 0; j < 16; ++j) {
    if (((static_cast<unsigned>(wire_mask) >> j) & 1u) == 0) continue;
    const std::uint64_t bit = ((static_cast<unsigned>(want) >> j) & 1u) != 0 ? ~0ull : 0ull;
    wrong[0] |= reg[j] ^ bit;       // output bit j is register bit j
    wrong[1] |= reg[15 - j] ^ bit;  // reflected: output bit j is register bit 15 - j
  }
  return {~wrong[0], ~wrong[1]};
}

// The init/xorout representative of a hypothesis' class, preferring a catalogue entry, then the usual
// all-zeros/all-ones values, then xorout 0 or 0xFFFF with a solved init, else init 0.
crc16_member representative(const hypothesis& h, const std::vector<catalogue_entry>* catalogue) {
  const auto constant_of = [&](std::uint16_t initial, std::uint16_t xor_out) {
    return static_cast<std::uint16_t>((output(initial_part(h.polynomial, initial), h.reflect_out) ^ xor_out) &
                                      wire_mask);
  };
  const auto member = [&](std::uint16_t initial, std::uint16_t xor_out, std::string name) {
    return crc16_member{ring::crc16_parameters{h.polynomial, initial, h.reflect_in, h.reflect_out, xor_out},
                        std::move(name)};
  };
  if (catalogue != nullptr) {
    for (const catalogue_entry& e : *catalogue) {
      if (e.width == 16 && e.polynomial == h.polynomial && e.reflect_in == h.reflect_in &&
          e.reflect_out == h.reflect_out && constant_of(e.initial, e.xor_out) == h.constant) {
        return member(e.initial, e.xor_out, e.name);
      }
    }
  }
  static constexpr std::uint16_t plain[][2] = {
      {0xFFFF, 0x0000}, {0x0000, 0x0000}, {0xFFFF, 0xFFFF}, {0x0000, 0xFFFF}};
  for (const auto& pair : plain) {
    if (constant_of(pair[0], pair[1]) == h.constant) return member(pair[0], pair[1], {});
  }
  gf2_solver<16> solver;
  for (unsigned k = 0; k < 16; ++k) {
    const auto bit = static_cast<std::uint16_t>(1u << k);
    solver.add(static_cast<std::uint16_t>(output(initial_part(h.polynomial, bit), h.reflect_out) & wire_mask),
               bit);
  }
  for (std::uint16_t xor_out : {std::uint16_t{0x0000}, std::uint16_t{0xFFFF}}) {
    std::uint16_t initial = 0;
    if (solver.solve(static_cast<std::uint16_t>((h.constant ^ xor_out) & wire_mask), initial))
      return member(initial, xor_out, {});
  }
  return member(0x0000, h.constant, {});
}

}  // namespace

bool frame_crc_matches(const ring::crc16_parameters& parameters, const variable_frame& frame,
                       const ring::variable_layout_parameters& layout) {
  const message m = covered(frame, layout, false);
  const ring::crc16_runtime crc(parameters);
  return ring::crc_wire_bits(crc.compute(m.data(), m.size())) == transmitted_crc(frame);
}

crc_learn_result learn_ring_crc(const std::vector<variable_frame>& frames, const crc_learn_options& options) {
  crc_learn_result result;
  result.frames = frames.size();
  if (frames.empty()) return result;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    for (std::uint8_t byte : frames[f]) {
      if (!ring::is_data(byte)) {
        result.status = crc_learn_status::bad_frame;
        result.bad_frame_index = f;
        return result;
      }
    }
  }

  // Each frame's difference with the first: init and xorout cancel. Identical messages carry nothing (or,
  // with different CRCs, rule out every CRC).
  std::vector<std::size_t> informative;
  for (std::size_t f = 1; f < frames.size(); ++f) {
    const bool same = std::equal(frames[f].begin(), frames[f].begin() + message_bytes, frames[0].begin());
    if (!same) {
      informative.push_back(f);
    } else if (transmitted_crc(frames[f]) != transmitted_crc(frames[0])) {
      result.status = crc_learn_status::no_candidate;
      return result;
    }
  }

  std::vector<hypothesis> survivors;
  const std::uint64_t considered = options.even_polynomials ? ~0ull : 0xAAAAAAAAAAAAAAAAull;  // odd ones
  for (bool reflect_in : {false, true}) {
    const message first = covered(frames[0], options.layout, reflect_in);
    std::vector<message> differences;
    std::vector<std::uint16_t> crc_differences;
    for (std::size_t f : informative) {
      differences.push_back(exclusive_or(covered(frames[f], options.layout, reflect_in), first));
      crc_differences.push_back(
          static_cast<std::uint16_t>(transmitted_crc(frames[f]) ^ transmitted_crc(frames[0])));
    }
    for (unsigned base = 0; base <= 0xFFFF; base += 64) {
      if (options.progress) options.progress((reflect_in ? 0x10000 : 0) + base, 0x20000);
      std::array<std::uint64_t, 2> fits = {considered, considered};  // reflect_out false, true
      for (std::size_t d = 0; d < differences.size() && (fits[0] | fits[1]) != 0; ++d) {
        const auto matches = sliced_matches(sliced_linear_part(base, differences[d]), crc_differences[d]);
        fits[0] &= matches[0];
        fits[1] &= matches[1];
      }
      for (std::size_t out = 0; out < 2; ++out) {
        for (std::uint64_t bits = fits[out]; bits != 0; bits &= bits - 1) {
          const auto polynomial =
              static_cast<std::uint16_t>(base + static_cast<unsigned>(__builtin_ctzll(bits)));
          const auto constant = static_cast<std::uint16_t>(
              (transmitted_crc(frames[0]) ^ output(linear_part(polynomial, first), out != 0)) & wire_mask);
          survivors.push_back(hypothesis{polynomial, reflect_in, out != 0, constant});
        }
      }
    }
  }
  result.survivors = survivors.size();
  if (survivors.empty()) {
    result.status = crc_learn_status::no_candidate;
    return result;
  }

  // Collapse the hypotheses that are the same function on valid frames: sort by a hash of part of the
  // signature, then split each run of equal hashes by the whole signature. Distinct hashes are distinct
  // classes, so too many of them settle the answer before any signature is computed.
  const std::size_t top = options.layout.crc == ring::crc_input::least_significant_first
                              ? ring::top_value_group(ring::group_order::least_significant_first)
                              : ring::top_value_group(options.layout.value);
  std::vector<std::pair<std::uint64_t, std::size_t>> order;
  order.reserve(survivors.size());
  for (std::size_t i = 0; i < survivors.size(); ++i) order.emplace_back(hash_of(survivors[i], top), i);
  std::sort(order.begin(), order.end());
  std::size_t distinct_hashes = 0;
  for (std::size_t i = 0; i < order.size(); ++i)
    distinct_hashes += i == 0 || order[i].first != order[i - 1].first;
  if (distinct_hashes > options.max_classes) {
    result.status = crc_learn_status::too_many_candidates;
    return result;
  }
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t run = 0; run < order.size();) {
    std::size_t end = run;
    while (end < order.size() && order[end].first == order[run].first) ++end;
    std::vector<std::pair<signature, std::vector<std::size_t>>> distinct;
    for (std::size_t k = run; k < end; ++k) {
      const signature s = signature_of(survivors[order[k].second], top);
      auto found =
          std::find_if(distinct.begin(), distinct.end(), [&](const auto& d) { return d.first == s; });
      if (found == distinct.end()) {
        distinct.emplace_back(s, std::vector<std::size_t>{order[k].second});
      } else {
        found->second.push_back(order[k].second);
      }
    }
    for (auto& d : distinct) groups.push_back(std::move(d.second));
    run = end;
  }
  if (groups.size() > options.max_classes) {
    result.status = crc_learn_status::too_many_candidates;
    return result;
  }

  // Representatives, each proved on every frame with a full CRC.
  for (const auto& group : groups) {
    crc16_class c;
    c.constant = survivors[group.front()].constant;
    for (std::size_t index : group) {
      crc16_member m = representative(survivors[index], options.catalogue);
      bool all = true;
      for (const variable_frame& frame : frames)
        all = all && frame_crc_matches(m.parameters, frame, options.layout);
      if (!all) {
        ++result.rejected;
        continue;
      }
      c.members.push_back(std::move(m));
    }
    if (!c.members.empty()) result.classes.push_back(std::move(c));
  }
  finish_classes(result);
  return result;
}

}  // namespace trionet::learn

#include "learn/ring_layout_learn.hpp"

#include <algorithm>

#include "trionet/ring/bytes.hpp"

namespace trionet::learn {
namespace {

constexpr ring::group_order lsf = ring::group_order::least_significant_first;
constexpr ring::group_order msf = ring::group_order::most_significant_first;

bool reads_as_sent(const variable_frame& frame, const sent_variable& sent, ring::group_order vr_order,
                   ring::group_order value_order) {
  std::uint16_t vr = 0;
  std::int64_t value = 0;
  ring::read_variable_fields(frame.data(), vr, value, vr_order, value_order);
  return (frame[ring::top_value_group(value_order)] & 0x7E) == 0 && vr == sent.vr && value == sent.value;
}

// Whether a CRC fits with the layout's orders and the given CRC input.
bool crc_fits(const std::vector<variable_frame>& frames, const ring::variable_layout_parameters& layout,
              const layout_learn_options& options, bool& decided) {
  if (options.crc != nullptr) {
    decided = true;
    return std::all_of(frames.begin(), frames.end(),
                       [&](const variable_frame& f) { return frame_crc_matches(*options.crc, f, layout); });
  }
  crc_learn_options learning = options.crc_learning;
  learning.layout = layout;
  const crc_learn_result learned = learn_ring_crc(frames, learning);
  decided = learned.status != crc_learn_status::too_many_candidates;
  return learned.status == crc_learn_status::ok || learned.status == crc_learn_status::ambiguous ||
         learned.status == crc_learn_status::too_many_candidates;
}

}  // namespace

layout_learn_result learn_layout(const std::vector<variable_frame>& frames,
                                 const std::vector<sent_variable>& sent,
                                 const layout_learn_options& options) {
  layout_learn_result result;
  const ring::group_order pairs[4][2] = {{lsf, lsf}, {lsf, msf}, {msf, lsf}, {msf, msf}};
  for (std::size_t p = 0; p < 4; ++p) {
    result.orders[p].vr = pairs[p][0];
    result.orders[p].value = pairs[p][1];
  }
  if (frames.empty()) return result;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (std::any_of(frames[f].begin(), frames[f].end(), [](std::uint8_t b) { return !ring::is_data(b); })) {
      result.status = layout_learn_status::bad_frame;
      result.bad_frame_index = f;
      return result;
    }
  }
  const std::size_t common = std::min(frames.size(), sent.size());
  std::size_t fitting = 0;
  for (order_fit& fit : result.orders) {
    fit.fits = true;
    for (std::size_t i = 0; i < common && fit.fits; ++i) {
      if (!reads_as_sent(frames[i], sent[i], fit.vr, fit.value)) {
        fit.fits = false;
        fit.first_contradiction = i;
      }
    }
    fitting += fit.fits ? 1 : 0;
  }
  if (frames.size() != sent.size()) {
    result.status = layout_learn_status::count_mismatch;
    return result;
  }
  if (fitting == 0) {
    result.status = layout_learn_status::no_layout_fits;
    return result;
  }
  if (fitting > 1) {
    result.status = layout_learn_status::ambiguous;
    return result;
  }
  result.status = layout_learn_status::ok;
  const auto found =
      std::find_if(result.orders.begin(), result.orders.end(), [](const order_fit& f) { return f.fits; });
  result.layout.vr = found->vr;
  result.layout.value = found->value;
  if (found->vr == lsf && found->value == lsf) {
    result.crc = crc_input_finding::same_bytes;
    return result;
  }
  bool decided_sent = false, decided_default = false;
  ring::variable_layout_parameters as_sent = result.layout;
  as_sent.crc = ring::crc_input::as_sent;
  ring::variable_layout_parameters in_default_order = result.layout;
  in_default_order.crc = ring::crc_input::least_significant_first;
  const bool fits_sent = crc_fits(frames, as_sent, options, decided_sent);
  const bool fits_default = crc_fits(frames, in_default_order, options, decided_default);
  if (!decided_sent || !decided_default) {
    result.crc = crc_input_finding::undecided;
  } else if (fits_sent && fits_default) {
    result.crc = crc_input_finding::both_fit;
  } else if (fits_sent) {
    result.crc = crc_input_finding::as_sent;
  } else if (fits_default) {
    result.crc = crc_input_finding::least_significant_first;
    result.layout.crc = ring::crc_input::least_significant_first;
  } else {
    result.crc = crc_input_finding::none_fits;
  }
  return result;
}

}  // namespace trionet::learn

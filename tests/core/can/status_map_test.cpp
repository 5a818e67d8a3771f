// A CAN send's and receive's statuses take the codec's, the port's and the VR store's outcomes by name
// (detail/status_map.hpp): the names line up, a run that does not line up is told apart, and each outcome
// converts to the enumerator of its name.
#include <gtest/gtest.h>

#include <cstring>

#include <trionet/can.hpp>
#include <trionet/detail/status_map.hpp>
#include <trionet/vr.hpp>

namespace {

using namespace trionet::can;
namespace detail = trionet::detail;

TEST(CanStatusMap, TheSendAndReceiveStatusesRepeatTheirSourcesNames) {
  static_assert(detail::names_agree<encode_status::vr_out_of_range, encode_status::fraction_out_of_range,
                                    send_status::vr_out_of_range>());
  static_assert(detail::names_agree<transmit_status::busy, transmit_status::failed, send_status::port_busy>());
  static_assert(detail::names_agree<decode_status::bad_dlc, decode_status::bad_fraction, receive_status::bad_dlc>());
  static_assert(detail::names_agree<trionet::vr_write_status::ok, trionet::vr_write_status::value_out_of_range,
                                    receive_status::ok>());
  SUCCEED();
}

TEST(CanStatusMap, ARunThatDoesNotLineUpIsToldApart) {
  // One place off, and a run longer than its names in the other enum.
  static_assert(!detail::names_agree<encode_status::vr_out_of_range, encode_status::fraction_out_of_range,
                                     send_status::no_such_channel>());
  static_assert(!detail::names_agree<decode_status::ok, decode_status::bad_fraction, receive_status::foreign>());
  static_assert(!detail::names_agree<transmit_status::ok, transmit_status::failed, send_status::port_busy>());
  EXPECT_TRUE(detail::ends_with("port_busy", "busy"));
  EXPECT_TRUE(detail::ends_with("busy", "busy"));
  EXPECT_FALSE(detail::ends_with("busy", "port_busy"));
  EXPECT_FALSE(detail::ends_with("port_failed", "busy"));
  EXPECT_TRUE(detail::ends_with("x", ""));
}

TEST(CanStatusMap, EachOutcomeBecomesTheEnumeratorOfItsName) {
  using failure = detail::status_map<encode_status::vr_out_of_range, encode_status::fraction_out_of_range,
                                     send_status::vr_out_of_range>;
  for (encode_status e : {encode_status::vr_out_of_range, encode_status::not_a_number, encode_status::too_large,
                          encode_status::fraction_out_of_range}) {
    EXPECT_STREQ(to_string(failure::of(e)), to_string(e));
  }
  using outcome = detail::status_map<trionet::vr_write_status::ok, trionet::vr_write_status::value_out_of_range,
                                     receive_status::ok>;
  for (trionet::vr_write_status w : {trionet::vr_write_status::ok, trionet::vr_write_status::refused,
                                     trionet::vr_write_status::out_of_range,
                                     trionet::vr_write_status::value_out_of_range}) {
    EXPECT_STREQ(to_string(outcome::of(w)), trionet::to_string(w));
  }
}

}  // namespace

// Profiles (src/learn/profile.hpp, docs/profile.md): the default is the protocol reference's decisions; a
// profile reads back what was written; every malformed file is an error naming the key (never undefined
// behaviour); and the generated C++ header compiles with the firmware flags and runs.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "learn/json.hpp"
#include "learn/profile.hpp"
#include "learn/ring_capture.hpp"
#include "trionet/genius/crc6.hpp"
#include "trionet/ring.hpp"

namespace ring = trionet::ring;
namespace genius = trionet::genius;
namespace learn = trionet::learn;

namespace {

// A profile that differs from the default in every key.
learn::profile custom_profile() {
  learn::profile p;
  p.name = "plant 7 \"north\" ring\nsecond line";
  p.ring.crc = {0x8005, 0xFFFF, true, true, 0x0000};  // CRC-16/MODBUS
  p.ring.layout = {ring::group_order::most_significant_first, ring::group_order::most_significant_first,
                   ring::crc_input::least_significant_first};
  p.ring.max_characters = 80;
  p.ring.receive_buffer = 512;
  for (std::size_t k = 0; k < ring::key_count; ++k)
    p.keypad.codes.raw[k] = static_cast<std::uint8_t>(0x60 + k);
  p.keypad.codes.raw[17] = 3;  // a control character: written as a number
  p.keypad.defkey = ring::make_default_defkey(p.keypad.codes);
  p.keypad.defkey.value[5] = 200;  // not derived from the codes: written as an array
  p.keypad.key_off = learn::key_off_rule::same;
  p.keypad.display = {ring::carriage_return_rule::line_start, ring::line_feed_rule::next_line, 32};
  p.can.node_count = 11;
  p.can.byte_order = trionet::can::byte_order::little_endian;
  p.genius.crc = {0x19, 0x00, true, true, 0x00};  // CRC-6/DARC
  p.genius.control = {3, 2, 1, 0, genius::tag_position::low};
  return p;
}

// Reads `json` and expects the error `status` at `key`.
void expect_error(const std::string& json, learn::profile_status status, const std::string& key) {
  const auto r = learn::read_profile(json);
  EXPECT_EQ(r.status, status) << json << "\n" << r.message;
  EXPECT_EQ(r.key, key) << json << "\n" << r.message;
  EXPECT_FALSE(r.message.empty());
}

std::string with_ring(const std::string& ring_members) {
  return "{\"trionet_profile\": 1, \"ring\": {" + ring_members + "}}";
}

}  // namespace

TEST(LearnProfile, TheDefaultIsTheProtocolReferencesDecisions) {
  const learn::profile p;
  EXPECT_EQ(p.ring.crc, (ring::crc16_parameters{0x1021, 0xFFFF, false, false, 0x0000}));  // CCITT-FALSE
  EXPECT_EQ(p.ring.layout.vr, ring::group_order::least_significant_first);
  EXPECT_EQ(p.ring.layout.value, ring::group_order::least_significant_first);
  EXPECT_EQ(p.ring.layout.crc, ring::crc_input::as_sent);
  EXPECT_EQ(p.ring.max_characters, ring::default_max_characters);
  EXPECT_EQ(p.ring.receive_buffer, 256u);
  EXPECT_EQ(0, std::memcmp(p.keypad.codes.raw, ring::default_keypad_codes.raw, ring::key_count));
  EXPECT_EQ(0, std::memcmp(p.keypad.defkey.value, ring::default_defkey.value, 128));
  EXPECT_EQ(p.keypad.key_off, learn::key_off_rule::plus_64);
  EXPECT_EQ(learn::key_off_function(p.keypad.key_off)('5'), '5' + 64);
  EXPECT_EQ(p.can.node_count, 5);
  EXPECT_EQ(p.genius.crc, (genius::crc6_parameters{0x03, 0x00, true, true, 0x00}));  // CRC-6/G-704
  EXPECT_EQ(p.keypad.display.carriage_return, ring::carriage_return_rule::other_line_unless_at_line_start);
  EXPECT_EQ(p.keypad.display.line_feed, ring::line_feed_rule::ignored);
  EXPECT_EQ(p.keypad.display.position_base, 0);
  EXPECT_EQ(p.can.byte_order, trionet::can::byte_order::big_endian);
  EXPECT_EQ(p.genius.control.start, 0);
  EXPECT_EQ(p.genius.control.stop, 1);
  EXPECT_EQ(p.genius.control.start_of_block, 2);
  EXPECT_EQ(p.genius.control.end_of_block, 3);
  EXPECT_EQ(p.genius.control.position, genius::tag_position::high);
  // The smallest profile file is the default profile.
  const auto minimal = learn::read_profile("{\"trionet_profile\": 1}");
  ASSERT_TRUE(minimal) << minimal.message;
  EXPECT_EQ(minimal.value, p);
}

TEST(LearnProfile, WhatIsWrittenReadsBack) {
  for (const learn::profile& p : {learn::profile{}, custom_profile()}) {
    const std::string text = learn::write_profile(p);
    const auto back = learn::read_profile(text);
    ASSERT_TRUE(back) << back.key << ": " << back.message << "\n" << text;
    EXPECT_EQ(back.value, p);
    EXPECT_EQ(learn::write_profile(back.value), text);  // canonical
  }
  const std::string text = learn::write_profile(learn::profile{});
  EXPECT_NE(text.find("\"polynomial\": \"0x1021\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"defkey\": \"from_codes\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"up\": \"U\""), std::string::npos) << text;
  const std::string custom = learn::write_profile(custom_profile());
  EXPECT_NE(custom.find("\"stop\": 3"), std::string::npos) << custom;
  EXPECT_NE(custom.find("\"defkey\": ["), std::string::npos) << custom;
  EXPECT_NE(custom.find("\"display\": {\"carriage_return\": \"line_start\", \"line_feed\": \"next_line\", "
                        "\"position_base\": 32}"),
            std::string::npos)
      << custom;
  EXPECT_NE(custom.find("\"byte_order\": \"little_endian\""), std::string::npos) << custom;
  EXPECT_NE(custom.find("\"control\": {\"start\": 3, \"stop\": 2, \"start_of_block\": 1, \"end_of_block\": 0, "
                        "\"tag_position\": \"low\"}"),
            std::string::npos)
      << custom;
  // Each new key on its own differs from the default, so == looks at it.
  learn::profile one;
  one.keypad.display.position_base = 1;
  EXPECT_NE(one, learn::profile{});
  one = {};
  one.can.byte_order = trionet::can::byte_order::little_endian;
  EXPECT_NE(one, learn::profile{});
  one = {};
  one.genius.control.position = genius::tag_position::low;
  EXPECT_NE(one, learn::profile{});
}

TEST(LearnProfile, AcceptsIntegersOrHexStringsAndOneCharacterStrings) {
  const auto r = learn::read_profile(
      "{\"trionet_profile\": 1, \"ring\": {\"crc\": {\"polynomial\": 32773, \"initial\": \"0XFFFF\"}},"
      " \"keypad\": {\"codes\": {\"up\": 117, \"down\": \"d\"}, \"key_off\": \"same\"},"
      " \"genius\": {\"crc6\": {\"polynomial\": \"0x2F\", \"xor_out\": 63, \"reflect_in\": false}}}");
  ASSERT_TRUE(r) << r.key << ": " << r.message;
  EXPECT_EQ(r.value.ring.crc.polynomial, 0x8005);
  EXPECT_EQ(r.value.ring.crc.initial, 0xFFFF);
  EXPECT_EQ(r.value.keypad.codes[ring::key::up], 'u');
  EXPECT_EQ(r.value.keypad.codes[ring::key::down], 'd');
  EXPECT_EQ(r.value.keypad.defkey['u'], 10);  // derived from the codes it has
  EXPECT_EQ(r.value.keypad.defkey['U'], 'U');
  EXPECT_EQ(r.value.genius.crc, (genius::crc6_parameters{0x2f, 0x00, false, true, 0x3f}));
}

TEST(LearnProfile, EveryErrorNamesTheKey) {
  using s = learn::profile_status;
  expect_error("{}", s::missing_key, "trionet_profile");
  expect_error("{\"trionet_profile\": 2}", s::unsupported_version, "trionet_profile");
  expect_error("{\"trionet_profile\": \"1\"}", s::wrong_type, "trionet_profile");
  expect_error("{\"trionet_profile\": 1.0}", s::unsupported_version, "trionet_profile");
  expect_error("[1]", s::wrong_type, "");
  expect_error("{\"trionet_profile\": 1, \"rings\": {}}", s::unknown_key, "rings");
  expect_error("{\"trionet_profile\": 1, \"name\": 5}", s::wrong_type, "name");
  expect_error(with_ring("\"crc\": {\"poly\": \"0x1021\"}"), s::unknown_key, "ring.crc.poly");
  expect_error(with_ring("\"crc\": {\"polynomial\": \"0x10210\"}"), s::out_of_range, "ring.crc.polynomial");
  expect_error(with_ring("\"crc\": {\"polynomial\": 65536}"), s::out_of_range, "ring.crc.polynomial");
  expect_error(with_ring("\"crc\": {\"polynomial\": -1}"), s::out_of_range, "ring.crc.polynomial");
  expect_error(with_ring("\"crc\": {\"polynomial\": \"1021\"}"), s::wrong_type, "ring.crc.polynomial");
  expect_error(with_ring("\"crc\": {\"polynomial\": \"0x12g4\"}"), s::wrong_type, "ring.crc.polynomial");
  expect_error(with_ring("\"crc\": {\"polynomial\": \"0x\"}"), s::wrong_type, "ring.crc.polynomial");
  expect_error(with_ring("\"crc\": {\"initial\": 1.5}"), s::wrong_type, "ring.crc.initial");
  expect_error(with_ring("\"crc\": {\"initial\": 1e3}"), s::wrong_type, "ring.crc.initial");
  expect_error(with_ring("\"crc\": {\"reflect_in\": \"yes\"}"), s::wrong_type, "ring.crc.reflect_in");
  expect_error(with_ring("\"crc\": {\"reflect_out\": 1}"), s::wrong_type, "ring.crc.reflect_out");
  expect_error(with_ring("\"crc\": [1]"), s::wrong_type, "ring.crc");
  expect_error(with_ring("\"vr_group_order\": \"msb_first\""), s::out_of_range, "ring.vr_group_order");
  expect_error(with_ring("\"value_group_order\": 1"), s::wrong_type, "ring.value_group_order");
  expect_error(with_ring("\"crc_input\": \"default\""), s::out_of_range, "ring.crc_input");
  expect_error(with_ring("\"max_characters\": 0"), s::out_of_range, "ring.max_characters");
  expect_error(with_ring("\"receive_buffer\": 65535"), s::out_of_range, "ring.receive_buffer");
  expect_error(with_ring("\"max_characters\": 99999999999999999999999"), s::out_of_range,
               "ring.max_characters");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"codes\": {\"enter\": 13}}}", s::unknown_key,
               "keypad.codes.enter");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"codes\": {\"up\": 128}}}", s::out_of_range,
               "keypad.codes.up");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"codes\": {\"up\": \"UP\"}}}", s::out_of_range,
               "keypad.codes.up");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"codes\": {\"up\": \"\\u00e9\"}}}", s::out_of_range,
               "keypad.codes.up");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"codes\": {\"up\": null}}}", s::wrong_type,
               "keypad.codes.up");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"codes\": {\"stop\": \"S\"}}}", s::duplicate_code,
               "keypad.codes.stop");  // 'S' is start's default code
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"defkey\": \"identity\"}}", s::out_of_range,
               "keypad.defkey");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"defkey\": [1, 2, 3]}}", s::out_of_range,
               "keypad.defkey");
  std::string defkey = "[";
  for (int c = 0; c < 128; ++c)
    defkey += std::string(c == 0 ? "" : ",") + (c == 70 ? "256" : std::to_string(c));
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"defkey\": " + defkey + "]}}", s::out_of_range,
               "keypad.defkey[70]");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"defkey\": {}}}", s::wrong_type, "keypad.defkey");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"key_off\": \"plus64\"}}", s::out_of_range,
               "keypad.key_off");
  expect_error("{\"trionet_profile\": 1, \"can\": {\"node_count\": 12}}", s::out_of_range, "can.node_count");
  expect_error("{\"trionet_profile\": 1, \"can\": {\"node_count\": 1}}", s::out_of_range, "can.node_count");
  expect_error("{\"trionet_profile\": 1, \"can\": {\"byte_order\": \"little\"}}", s::out_of_range,
               "can.byte_order");
  expect_error("{\"trionet_profile\": 1, \"can\": {\"byte_order\": true}}", s::wrong_type, "can.byte_order");
  expect_error("{\"trionet_profile\": 1, \"can\": {\"endian\": \"big_endian\"}}", s::unknown_key, "can.endian");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"display\": {\"carriage_return\": \"newline\"}}}",
               s::out_of_range, "keypad.display.carriage_return");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"display\": {\"line_feed\": 10}}}", s::wrong_type,
               "keypad.display.line_feed");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"display\": {\"position_base\": 89}}}", s::out_of_range,
               "keypad.display.position_base");
  expect_error("{\"trionet_profile\": 1, \"keypad\": {\"display\": {\"rows\": 4}}}", s::unknown_key,
               "keypad.display.rows");
  expect_error("{\"trionet_profile\": 1, \"genius\": {\"control\": {\"stop\": 0}}}", s::duplicate_code,
               "genius.control.stop");  // 0 is Start's default tag
  expect_error("{\"trionet_profile\": 1, \"genius\": {\"control\": {\"start\": 4}}}", s::out_of_range,
               "genius.control.start");
  expect_error("{\"trionet_profile\": 1, \"genius\": {\"control\": {\"tag_position\": \"middle\"}}}",
               s::out_of_range, "genius.control.tag_position");
  expect_error("{\"trionet_profile\": 1, \"genius\": {\"crc6\": {\"polynomial\": \"0x40\"}}}",
               s::out_of_range, "genius.crc6.polynomial");
  expect_error("{\"trionet_profile\": 1, \"genius\": {\"crc6\": {\"xor_out\": 64}}}", s::out_of_range,
               "genius.crc6.xor_out");
  expect_error("{\"trionet_profile\": 1, \"genius\": {\"crc\": {}}}", s::unknown_key, "genius.crc");
}

TEST(LearnProfile, ErrorsSayWhere) {
  const auto r = learn::read_profile("{\n  \"trionet_profile\": 1,\n  \"can\": {\"node_count\": 40}\n}");
  EXPECT_EQ(r.status, learn::profile_status::out_of_range);
  EXPECT_EQ(r.line, 3u);
  EXPECT_EQ(r.column, 25u);  // the value 40
}

TEST(LearnProfile, TextThatIsNotJsonIsRejectedWithItsReason) {
  using j = learn::json_status;
  const auto expect_json = [](const std::string& text, j status) {
    const auto r = learn::read_profile(text);
    EXPECT_EQ(r.status, learn::profile_status::not_json) << text;
    EXPECT_EQ(r.json, status) << text << ": " << r.message;
    EXPECT_GT(r.line, 0u);
  };
  expect_json("", j::syntax);
  expect_json("{\"trionet_profile\": 1,}", j::syntax);   // trailing comma
  expect_json("{\"trionet_profile\": 1} x", j::syntax);  // text after the value
  expect_json("{\"trionet_profile\": 01}", j::syntax);   // leading zero
  expect_json("// comment\n{\"trionet_profile\": 1}", j::syntax);
  expect_json("{\"trionet_profile\": 1, \"name\": \"a\nb\"}", j::syntax);  // raw newline in a string
  expect_json("{\"trionet_profile\": 1, \"name\": \"\\x\"}", j::syntax);
  expect_json("{\"trionet_profile\": 1, \"name\": \"\\ud800\"}", j::syntax);       // lone surrogate
  expect_json("{\"trionet_profile\": 1, \"name\": \"\xC3\x28\"}", j::syntax);      // invalid UTF-8
  expect_json("{\"trionet_profile\": 1, \"name\": \"\xED\xA0\x80\"}", j::syntax);  // UTF-8 surrogate
  expect_json("{\"trionet_profile\": 1, \"name\": \"\xC0\xAF\"}", j::syntax);      // overlong
  expect_json("{\"trionet_profile\": 1, \"name\": \"abc", j::syntax);
  expect_json("{\"trionet_profile\": 1, \"trionet_profile\": 1}", j::duplicate_key);
  expect_json(std::string(40, '[') + std::string(40, ']'), j::too_deep);
  expect_json("{\"name\": \"" + std::string(learn::max_json_bytes, 'a') + "\"}", j::too_large);
  // What is fine: escapes, a surrogate pair, UTF-8, a byte order mark, blanks.
  const auto fine = learn::read_profile(
      "\xEF\xBB\xBF { \"trionet_profile\" : 1 , \"name\" : \"\\u00e9\\ud83d\\ude00 \xC3\xA9 \\\"q\\\" \\/\" "
      "}\r\n");
  ASSERT_TRUE(fine) << fine.message;
  EXPECT_EQ(fine.value.name, "\xC3\xA9\xF0\x9F\x98\x80 \xC3\xA9 \"q\" /");
}

TEST(LearnProfile, RandomDamageIsAlwaysAnErrorOrAProfileThatRoundTrips) {
  const std::string base = learn::write_profile(custom_profile());
  std::mt19937_64 rng(60);
  const char alphabet[] = "{}[]\":,0123456789-+.eExabcdefnulltrue \\\n\x80\xff";
  int errors = 0;
  for (int round = 0; round < 20000; ++round) {
    std::string text = base;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = rng() % text.size();
      switch (rng() % 3) {
        case 0:
          text[at] = alphabet[rng() % (sizeof alphabet - 1)];
          break;
        case 1:
          text.erase(at, 1 + rng() % 8);
          break;
        default:
          text.insert(at, 1, alphabet[rng() % (sizeof alphabet - 1)]);
          break;
      }
      if (text.empty()) text = "{";
    }
    const auto r = learn::read_profile(text);
    if (!r) {
      ++errors;
      EXPECT_FALSE(r.message.empty());
      continue;
    }
    const auto again = learn::read_profile(learn::write_profile(r.value));
    ASSERT_TRUE(again) << text;
    EXPECT_EQ(again.value, r.value);
    EXPECT_TRUE(learn::profile_header(r.value));
  }
  EXPECT_GT(errors, 10000);
}

TEST(LearnProfile, HeaderNamespaceMustBeACppName) {
  EXPECT_TRUE(learn::profile_header(learn::profile{}, "plant::ring_7"));
  EXPECT_EQ(learn::profile_header(learn::profile{}, "7ring").status, learn::header_status::bad_namespace);
  EXPECT_EQ(learn::profile_header(learn::profile{}, "a::").status, learn::header_status::bad_namespace);
  EXPECT_EQ(learn::profile_header(learn::profile{}, "").status, learn::header_status::bad_namespace);
  EXPECT_EQ(learn::profile_header(learn::profile{}, "a b").status, learn::header_status::bad_namespace);
  EXPECT_EQ(learn::profile_header(learn::profile{}, "a b").reason,
            "it is not a C++ namespace name (identifiers joined by ::)");
}

// Regression: the library wrote a header that does not compile for a keyword or trionet namespace (only the
// tool refused them); every caller, the Python package too, now gets the refusal and its reason.
TEST(LearnProfile, HeaderNamespaceMustNotBeAKeywordOrTrionet) {
  const auto refused = [](const char* name) { return learn::profile_header(learn::profile{}, name); };
  EXPECT_EQ(refused("int").status, learn::header_status::bad_namespace);
  EXPECT_EQ(refused("int").reason, "'int' is a C++ keyword");
  EXPECT_EQ(refused("plant::and").reason, "'and' is a C++ keyword");
  EXPECT_EQ(refused("trionet::ring").status, learn::header_status::bad_namespace);
  EXPECT_EQ(refused("plant::trionet").status, learn::header_status::bad_namespace);
  EXPECT_EQ(refused("plant::trionet").text, "");
  EXPECT_TRUE(learn::profile_header(learn::profile{}, "plant::trionet_x::integer"));
  EXPECT_EQ(learn::profile_header(learn::profile{}, "plant").reason, "");
}

// The generated headers of the default and of a custom profile, compiled with the firmware's flags and run:
// their policies must give what the run-time CRCs and the host encoder give.
TEST(LearnProfile, TheGeneratedHeaderCompilesAndItsPoliciesWork) {
  const std::string dir = std::string(TRIONET_TEST_WORK_DIR) + "/learn_profile_header";
  ASSERT_EQ(std::system(("mkdir -p '" + dir + "'").c_str()), 0);
  const learn::profile custom = custom_profile();
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
  };
  const auto plain_header = learn::profile_header(learn::profile{}, "plain");
  const auto custom_header = learn::profile_header(custom, "custom::net");
  ASSERT_TRUE(plain_header);
  ASSERT_TRUE(custom_header);
  write("plain_profile.hpp", plain_header.text);
  write("custom_profile.hpp", custom_header.text);

  const std::uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  const auto ring_check = ring::crc16_runtime(custom.ring.crc).compute(check, 9);
  const auto genius_check = genius::crc6_runtime(custom.genius.crc).compute(check);
  const auto frame =
      learn::encode_capture({{200, trionet::q32_from_integer(99)}}, custom.ring.crc, custom.ring.layout);
  std::string expected_frame;
  for (std::uint8_t b : frame[0]) expected_frame += std::to_string(b) + ", ";

  std::string program = R"(#include "plain_profile.hpp"
#include "custom_profile.hpp"

#include <cstdint>
#include <type_traits>

#include "trionet/ring/encode.hpp"
#include "trionet/vr.hpp"

namespace ring = trionet::ring;
static_assert(std::is_same_v<plain::ring_crc, ring::crc16_ccitt_false>, "default CRC");
static_assert(std::is_same_v<plain::ring_crc_with<ring::crc_table::lookup>, ring::crc16_ccitt_false_table>, "");
static_assert(std::is_same_v<plain::ring_crc_with<ring::crc_table::sliced>, ring::crc16_ccitt_false_sliced>, "");
static_assert(std::is_same_v<plain::ring_layout, ring::default_variable_layout>, "default layout");
static_assert(std::is_same_v<plain::genius_crc, trionet::genius::crc6_g704>, "default Genius CRC");
static_assert(std::is_same_v<plain::motion_coordinator<>, ring::motion_coordinator<>>, "default MC");
static_assert(std::is_same_v<plain::keypad<>, ring::keypad<>>, "default keypad");
static_assert(plain::ring_max_characters == 256 && plain::ring_receive_buffer == 256, "");
static_assert(plain::can_node_count == 5 && custom::net::can_node_count == 11, "");
static_assert(custom::net::ring_max_characters == 80 && custom::net::ring_receive_buffer == 512, "");
static_assert(custom::net::keypad_config.key_off_code == ring::same_key_off_code, "");
static_assert(plain::keypad_config.key_off_code == ring::default_key_off_code, "");
static_assert(plain::can_byte_order == trionet::can::byte_order::big_endian, "");
static_assert(custom::net::can_byte_order == trionet::can::byte_order::little_endian, "");
static_assert(std::is_same_v<custom::net::can_node, trionet::can::basic_vr_exchange_node<
                                                         trionet::can::fixed_byte_order<trionet::can::byte_order::little_endian>>>,
              "");
static_assert(plain::keypad_config.display.carriage_return ==
                  ring::carriage_return_rule::other_line_unless_at_line_start, "");
static_assert(custom::net::keypad_config.display.carriage_return == ring::carriage_return_rule::line_start &&
                  custom::net::keypad_config.display.line_feed == ring::line_feed_rule::next_line &&
                  custom::net::keypad_config.display.position_base == 32, "");
static_assert(plain::genius_control.start == 0 && plain::genius_control.end_of_block == 3 &&
                  plain::genius_control.position == trionet::genius::tag_position::high, "");
static_assert(custom::net::genius_control.start == 3 && custom::net::genius_control.stop == 2 &&
                  custom::net::genius_control.start_of_block == 1 && custom::net::genius_control.end_of_block == 0 &&
                  custom::net::genius_control.position == trionet::genius::tag_position::low, "");

int main() {
  int failures = 0;
  for (unsigned c = 0; c < 128; ++c) failures += plain::defkey.value[c] != ring::default_defkey.value[c];
  for (unsigned k = 0; k < ring::key_count; ++k) failures += plain::keypad_codes.raw[k] != ring::default_keypad_codes.raw[k];
  failures += custom::net::defkey.value[5] != 200;
  failures += custom::net::keypad_codes.raw[17] != 3;
  const std::uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  failures += custom::net::ring_crc::compute(check, 9) != )" +
                        std::to_string(ring_check) + R"(;
  failures += custom::net::ring_crc_with<ring::crc_table::none>::compute(check, 9) != )" +
                        std::to_string(ring_check) + R"(;
  failures += custom::net::genius_crc::compute(check) != )" +
                        std::to_string(genius_check) + R"(;
  const std::uint8_t expected[14] = {)" +
                        expected_frame + R"(};
  std::uint8_t frame[16] = {};
  const auto encoded = ring::encode_variable<custom::net::ring_crc, custom::net::ring_layout>(
      frame, 1, 200, std::int64_t{99} << 32);
  failures += !encoded;
  for (unsigned i = 0; i < 14; ++i) failures += frame[1 + i] != expected[i];
  custom::net::ring_decoder decoder;
  ring::decode_result last;
  for (std::uint8_t b : frame) last = decoder.push(b);
  failures += last.status != ring::decode_status::ok || last.msg.vr != 200;
  trionet::vr_table<256> vr;
  custom::net::motion_coordinator<> mc(vr, custom::net::defkey);
  custom::net::keypad<> keypad(custom::net::keypad_config);
  (void)mc;
  failures += keypad.display().model().position_base != 32;
  const trionet::genius::character stop = trionet::genius::stop_character(5, custom::net::genius_control);
  failures += stop.byte != (5 << 2 | 2);  // Stop's tag 2, in bits 1..0
  std::uint8_t can_data[8] = {};
  failures += trionet::can::encode_vr(1, 2.345, can_data, custom::net::can_byte_order) != trionet::can::encode_status::ok;
  failures += can_data[2] != 2 || can_data[6] != 0x7A;
  struct recording_port final : trionet::can::port {
    trionet::can::frame sent{};
    trionet::can::transmit_status send(const trionet::can::frame& f) noexcept override {
      sent = f;
      return trionet::can::transmit_status::ok;
    }
  } port;
  trionet::vr_table<16> can_vr;
  custom::net::can_node node(trionet::can::make_node_address(custom::net::can_node_count, 1).address, port, can_vr);
  failures += node.order() != trionet::can::byte_order::little_endian;
  failures += node.send_to_node(2, 1, 2.345) != trionet::can::send_status::ok;
  failures += port.sent.data[2] != 2 || port.sent.data[6] != 0x7A;
  return failures;
}
)";
  write("check.cpp", program);
  const std::string compile =
      std::string("'") + TRIONET_CXX_COMPILER + "' -std=c++17 -O1 -fno-exceptions -fno-rtti " +
      "-Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wshadow -Wold-style-cast " + "-Werror -I '" +
      TRIONET_INCLUDE_DIR + "' -I '" + dir + "' '" + dir + "/check.cpp' -o '" + dir + "/check' 2> '" + dir +
      "/compile.log'";
  const int compiled = std::system(compile.c_str());
  if (compiled != 0) {
    std::ifstream log(dir + "/compile.log");
    const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    FAIL() << "the generated headers do not compile:\n" << text;
  }
  EXPECT_EQ(std::system(("'" + dir + "/check'").c_str()), 0);
}

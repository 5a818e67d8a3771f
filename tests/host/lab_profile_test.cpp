// The lab's board images (firmware/lab, scripts/lab) take their wire parameters from a profile header: for
// the default profile the one committed in firmware/lab/profile, which must be what `trionet profile header
// --namespace lab_profile` writes today; and the lab's other profile must be one the tool reads, differing
// from the default where the lab says it does (the CRC, the keypad codes, the cursor positions).
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "learn/profile.hpp"
#include "trionet/ring.hpp"

namespace {

namespace learn = trionet::learn;

std::string lab_file(const std::string& name) {
  std::ifstream in(std::string(TRIONET_INCLUDE_DIR) + "/../firmware/lab/profile/" + name, std::ios::binary);
  std::stringstream all;
  all << in.rdbuf();
  return all.str();
}

TEST(LabProfile, TheCommittedHeaderIsWhatTheToolWritesForTheDefaultProfile) {
  const learn::header_result header = learn::profile_header(learn::profile{}, "lab_profile");
  ASSERT_TRUE(header);
  const std::string committed = lab_file("lab_profile.hpp");
  ASSERT_FALSE(committed.empty());
  EXPECT_EQ(header.text, committed) << "regenerate: trionet profile header --namespace lab_profile -o "
                                       "firmware/lab/profile/lab_profile.hpp";
}

TEST(LabProfile, TheOtherProfileChangesTheCrcTheKeypadCodesAndTheCursorPositions) {
  const learn::profile_result r = learn::read_profile(lab_file("custom-profile.json"));
  ASSERT_TRUE(r) << r.message;
  const learn::profile standard;
  EXPECT_NE(r.value.ring.crc, standard.ring.crc);
  EXPECT_NE(std::string(std::begin(r.value.keypad.codes.raw), std::end(r.value.keypad.codes.raw)),
            std::string(std::begin(standard.keypad.codes.raw), std::end(standard.keypad.codes.raw)));
  EXPECT_EQ(r.value.keypad.display.position_base, 32);
  EXPECT_TRUE(learn::profile_header(r.value, "lab_profile"));
}

}  // namespace

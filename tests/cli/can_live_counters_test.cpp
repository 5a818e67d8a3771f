// The live CAN commands over candump text: every kind of frame kept in the capture (classic, CAN FD and error
// frames), one counter for each kind of frame, and candump's log lines as can-utils reads them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "support/run_cli.hpp"
#include "support/temp_files.hpp"

namespace {

using trionet::test::temp_path;
using trionet::test::cli_result;
using trionet::test::run_cli;

const std::string mixed_frames =
    "(1700000000.000001) can0 028#0100000000020D7A\n"                  // a VR message, node 1 to 4
    "(1700000000.000002) can0 123##1" + std::string(48, 'A') + "\n"    // CAN FD, 24 bytes, BRS
    "(1700000000.000003) can0 20000004#0000080000000000\n"              // an error frame (controller problem)
    "(1700000000.000004) can0 7FF#0102030405060708\n"                   // a foreign identifier
    "(1700000000.000005) can0 028#01\n"                                 // on an exchange identifier, bad DLC
    "not candump\n";

TEST(CanLiveCapture, FdAndErrorFramesAreKeptInTheCapture) {
  const std::string pcap = temp_path("mixed.pcapng");
  const cli_result monitor = run_cli("can monitor - --json --pcap " + pcap, mixed_frames);
  ASSERT_EQ(monitor.exit_code, 0) << monitor.err;
  const cli_result decoded = run_cli("can decode --pcap " + pcap);
  std::remove(pcap.c_str());
  ASSERT_EQ(decoded.exit_code, 0) << decoded.err;
  // Every frame read is a record: what `can decode` makes of it is what the monitor made of it.
  EXPECT_NE(decoded.out.find("\"record\":1,"), std::string::npos) << decoded.out;
  EXPECT_NE(decoded.out.find("\"record\":5,"), std::string::npos) << decoded.out;
  EXPECT_NE(decoded.out.find("\"kind\":\"fd\",\"id\":291,\"length\":24}"), std::string::npos) << decoded.out;
  EXPECT_NE(decoded.out.find("\"kind\":\"error_frame\",\"id\":4,\"length\":8}"), std::string::npos) << decoded.out;
  EXPECT_NE(monitor.out.find("\"kind\":\"fd\",\"id\":291,\"length\":24}"), std::string::npos) << monitor.out;
  EXPECT_NE(monitor.out.find("\"kind\":\"error_frame\",\"id\":4,\"length\":8}"), std::string::npos) << monitor.out;
}

TEST(CanLiveCapture, EachKindOfFrameHasOneCounter) {
  const cli_result r = run_cli("can monitor - --json", mixed_frames);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // frames = vr + vr_errors + other + error_frames; an error frame is not counted as anything else.
  EXPECT_NE(r.out.find("\"frames\":5,\"vr\":1,\"vr_errors\":1,\"other\":2,\"error_frames\":1,\"syntax\":1}"),
            std::string::npos)
      << r.out;
}

TEST(CanLiveCapture, ALogLineWithoutABlankAfterItsTimestampIsReadAsCanUtilsReadsIt) {
  // can-utils reads log lines with sscanf("(%llu.%llu) %s %s"), where the blank matches none too.
  const cli_result decoded = run_cli("can decode", "(1700000000.123456)can0 028#0100000000020D7A\n");
  EXPECT_EQ(decoded.out,
            "{\"event\":\"vr\",\"line\":1,\"time\":\"1700000000.123456\",\"interface\":\"can0\",\"id\":40,\"from\":1,"
            "\"to\":4,\"vr\":1,\"negative\":false,\"int\":2,\"frac\":3450,\"value\":2.345}\n");
  const cli_result monitored = run_cli("can monitor - --json", "(1700000000.123456)can0 028#0100000000020D7A\n");
  EXPECT_NE(monitored.out.find("\"event\":\"vr\",\"time\":\"1700000000.123456000\",\"line\":1,"), std::string::npos)
      << monitored.out;
  // Still not a frame: a timestamp with nothing after it.
  EXPECT_NE(run_cli("can decode", "(1700000000.123456)\n").out.find("\"detail\":\"interface_name\""),
            std::string::npos);
}

}  // namespace

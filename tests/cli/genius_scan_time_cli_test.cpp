// `trionet genius scan-time`: GE's published scan-time figures, exact output, and exit 2 on bad arguments.
#include <gtest/gtest.h>

#include <string>

#include "support/run_cli.hpp"

namespace {

using trionet::test::expect_usage_error;
using trionet::test::run_cli;

TEST(GeniusScanTimeCli, TableForThreeDevices) {
  const auto r = run_cli("genius scan-time --rate 153.6s --device 16 --device 8 --device 4");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out,
            "rate 153.6s (153.6 kbaud standard): 0.943 ms per device + 0.0715 ms per byte of inputs and outputs "
            "(GE GFK-0825F)\n"
            "  device  io_bytes  scan_time_ms\n"
            "       1        16         2.087\n"
            "       2         8         1.515\n"
            "       3         4         1.229\n"
            "bus: 3 devices, 28 bytes: sum 4.831 ms, scan time 4.831 ms (above the minimum of 3 ms)\n"
            "computed character time (11 bits at 153600 bit/s): 0.071615 ms, not used above\n");
  // A comma-separated list is the same as repeated --device options.
  EXPECT_EQ(run_cli("genius scan-time --rate 153.6s --device 16,8,4").out, r.out);
  EXPECT_EQ(run_cli("genius scan-time --device 16,8 --rate 153.6s --device 4").out, r.out);
}

TEST(GeniusScanTimeCli, JsonAtEveryRate) {
  EXPECT_EQ(run_cli("genius scan-time --rate 153.6s --device 16,8,4 --json").out,
            "{\"rate\":\"153.6s\",\"fixed_ms\":0.943,\"per_byte_ms\":0.0715,\"devices\":[{\"io_bytes\":16,"
            "\"scan_time_ms\":2.087},{\"io_bytes\":8,\"scan_time_ms\":1.515},{\"io_bytes\":4,\"scan_time_ms\":"
            "1.229}],\"io_bytes\":28,\"sum_ms\":4.831,\"minimum_ms\":3,\"scan_ms\":4.831,\"minimum_applies\":false,\"character_time_ms\":0.071615}\n");
  EXPECT_EQ(run_cli("genius scan-time --rate 153.6e --device 16,8,4 --json").out,
            "{\"rate\":\"153.6e\",\"fixed_ms\":1.015,\"per_byte_ms\":0.0715,\"devices\":[{\"io_bytes\":16,"
            "\"scan_time_ms\":2.159},{\"io_bytes\":8,\"scan_time_ms\":1.587},{\"io_bytes\":4,\"scan_time_ms\":"
            "1.301}],\"io_bytes\":28,\"sum_ms\":5.047,\"minimum_ms\":3,\"scan_ms\":5.047,\"minimum_applies\":false,\"character_time_ms\":0.071615}\n");
  EXPECT_EQ(run_cli("genius scan-time --rate 76.8 --device 16,8,4 --json").out,
            "{\"rate\":\"76.8\",\"fixed_ms\":1.538,\"per_byte_ms\":0.143,\"devices\":[{\"io_bytes\":16,"
            "\"scan_time_ms\":3.826},{\"io_bytes\":8,\"scan_time_ms\":2.682},{\"io_bytes\":4,\"scan_time_ms\":"
            "2.11}],\"io_bytes\":28,\"sum_ms\":8.618,\"minimum_ms\":3,\"scan_ms\":8.618,\"minimum_applies\":false,\"character_time_ms\":0.143229}\n");
  EXPECT_EQ(run_cli("genius scan-time --rate 38.4 --device 16,8,4 --json").out,
            "{\"rate\":\"38.4\",\"fixed_ms\":2.583,\"per_byte_ms\":0.286,\"devices\":[{\"io_bytes\":16,"
            "\"scan_time_ms\":7.159},{\"io_bytes\":8,\"scan_time_ms\":4.871},{\"io_bytes\":4,\"scan_time_ms\":"
            "3.727}],\"io_bytes\":28,\"sum_ms\":15.757,\"minimum_ms\":3,\"scan_ms\":15.757,\"minimum_applies\":false,\"character_time_ms\":0.286458}\n");
}

TEST(GeniusScanTimeCli, OneDeviceOfOneByte) {
  const auto r = run_cli("genius scan-time --rate 153.6s --device 1");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("       1         1        1.0145\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("bus: 1 device, 1 byte: sum 1.0145 ms, scan time 3 ms (the bus controller's minimum of 3 ms "
                       "applies)\n"),
            std::string::npos)
      << r.out;
}

TEST(GeniusScanTimeCli, TheMinimumScanTimeIsShownBesideTheSumAndCanBeChanged) {
  EXPECT_EQ(run_cli("genius scan-time --rate 153.6s --device 16 --json").out,
            "{\"rate\":\"153.6s\",\"fixed_ms\":0.943,\"per_byte_ms\":0.0715,\"devices\":[{\"io_bytes\":16,"
            "\"scan_time_ms\":2.087}],\"io_bytes\":16,\"sum_ms\":2.087,\"minimum_ms\":3,\"scan_ms\":3,"
            "\"minimum_applies\":true,\"character_time_ms\":0.071615}\n");
  EXPECT_NE(run_cli("genius scan-time --rate 153.6s --device 16 --minimum-ms 0").out.find(
                "bus: 1 device, 16 bytes: sum 2.087 ms, scan time 2.087 ms (no minimum)\n"),
            std::string::npos);
  EXPECT_NE(run_cli("genius scan-time --rate 153.6s --device 16,16 --minimum-ms 4.5").out.find(
                "sum 4.174 ms, scan time 4.5 ms (the bus controller's minimum of 4.5 ms applies)\n"),
            std::string::npos);
  expect_usage_error("genius scan-time --rate 153.6s --device 16 --minimum-ms -1", "--minimum-ms");
  expect_usage_error("genius scan-time --rate 153.6s --device 16 --minimum-ms 1.0001", "--minimum-ms");
}

TEST(GeniusScanTimeCli, TableMarksGesPrintedCellsThatAreNotTheFormula) {
  const auto r = run_cli("genius scan-time --table");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out,
            "GE's printed scan-time table (GFK-0825F) beside GE's formula, one device, ms\n"
            "  bytes  153.6s           153.6e           76.8             38.4\n"
            "     16   2.09   2.087     2.16   2.159     3.83   3.826     7.16   7.159\n"
            "     32   3.24   3.231 *   3.31   3.303 *   6.12   6.114 *  11.74  11.735\n"
            "     64   5.52   5.519     5.60   5.591 *  10.69   10.69    20.89  20.887\n"
            "    128  10.10  10.095    10.17  10.167    19.85  19.842 *  39.20  39.191 *\n"
            "    256  19.25  19.247    19.32  19.319    38.15  38.146    75.80  75.799\n"
            "* the printed cell is not the formula rounded to 0.01 ms: 6 cells, by up to 0.009 ms\n");
  expect_usage_error("genius scan-time --table --rate 38.4", "--table");
}

TEST(GeniusScanTimeCli, Help) {
  const auto r = run_cli("genius scan-time --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out.rfind("usage: trionet genius scan-time --rate", 0), 0u) << r.out;
  EXPECT_NE(run_cli("genius --help").out.find("  scan-time   the bus scan time"), std::string::npos);
}

TEST(GeniusScanTimeCli, BadArgumentsExit2WithAMessage) {
  expect_usage_error("genius scan-time --device 4", "--rate");
  expect_usage_error("genius scan-time --rate 153.6 --device 4", "153.6");
  expect_usage_error("genius scan-time --rate 76.8", "--device");
  expect_usage_error("genius scan-time --rate 76.8 --device x", "--device 'x'");
  expect_usage_error("genius scan-time --rate 76.8 --device 4,,5", "--device '4,,5'");
  expect_usage_error("genius scan-time --rate 76.8 --device 4,", "--device '4,'");
  expect_usage_error("genius scan-time --rate 76.8 --device -1", "--device '-1'");
  expect_usage_error("genius scan-time --rate 76.8 --device 4294967296", "4294967296");
  expect_usage_error("genius scan-time --rate 76.8 --device 4 extra", "extra");
  expect_usage_error("genius scan-time --rate 76.8 --rate 38.4 --device 4", "--rate");
  expect_usage_error("genius scan-time --rate 76.8 --device 4 --skip-us 3", "--skip-us");
  expect_usage_error("genius scan-time --rate 38.4 --device 1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1", "38.4 allows 16");
  EXPECT_EQ(run_cli("genius scan-time --rate 38.4 --device 1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1").exit_code, 0);
}

}  // namespace

namespace {

// A sum equal to the minimum is not "above" it (s37 item 11).
TEST(GeniusScanTimeCliMessages, ASumEqualToTheMinimumIsSaidToBeEqual) {
  const auto r = trionet::test::run_cli("genius scan-time --rate 153.6s --device 16 --minimum-ms 2.087");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("scan time 2.087 ms (equal to the minimum of 2.087 ms)\n"), std::string::npos) << r.out;
  const auto above = trionet::test::run_cli("genius scan-time --rate 153.6s --device 16 --minimum-ms 2.086");
  EXPECT_NE(above.out.find("(above the minimum of 2.086 ms)\n"), std::string::npos) << above.out;
}

}  // namespace

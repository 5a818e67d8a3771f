// `trionet can encode | decode | table`: exact output bytes, exit codes, and errors on stderr.
#include <gtest/gtest.h>

#include "support/run_cli.hpp"

namespace {

using trionet::test::run_cli;

TEST(CanCli, EncodeProtocolExample) {
  const auto r = run_cli("can encode --nodes 5 --from 1 --to 4 --vr 1 --value 2.345");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, "028#0100000000020D7A\n");
  EXPECT_EQ(r.err, "");
}

TEST(CanCli, EncodeRoundsCarriesAndDefaultsToFiveNodes) {
  EXPECT_EQ(run_cli("can encode --from 1 --to 4 --vr 1 --value 2.34565").out, "028#0100000000020D81\n");
  EXPECT_EQ(run_cli("can encode --from 5 --to 2 --vr 255 --value -0.99995").out, "017#FF01000000010000\n");
  EXPECT_EQ(run_cli("can encode --from 2 --to 1 --vr 0 --value -0").out, "00A#0000000000000000\n");
  EXPECT_EQ(run_cli("can encode --nodes 11 --from 11 --to 10 --vr 3 --value 4294967295.9999").out,
            "06D#0300FFFFFFFF270F\n");
}

TEST(CanCli, EncodeBadArgumentsExitTwoWithAMessageAndNoOutput) {
  const char* bad[] = {
      "can encode --from 1 --to 4 --vr 1",                           // no value
      "can encode --from 1 --to 1 --vr 1 --value 1",                 // same node
      "can encode --from 0 --to 4 --vr 1 --value 1",                 // node 0
      "can encode --from 1 --to 6 --vr 1 --value 1",                 // no node 6 of 5
      "can encode --nodes 12 --from 1 --to 4 --vr 1 --value 1",      // too many nodes
      "can encode --nodes 1 --from 1 --to 4 --vr 1 --value 1",       // too few nodes
      "can encode --from 1 --to 4 --vr 256 --value 1",               // vr
      "can encode --from 1 --to 4 --vr 1 --value 4294967295.99995",  // rounds to 2^32
      "can encode --from 1 --to 4 --vr 1 --value 4294967296",        // 2^32
      "can encode --from 1 --to 4 --vr 1 --value nan",               // not a number
      "can encode --from 1 --to 4 --vr 1 --value 2,5",               // not a number
      "can encode --from 1 --to 4 --vr 1 --value 1 --colour red",    // unknown option
      "can encode --from 1 --to 4 --vr 1 --value 1 extra",           // stray word
      "can frobnicate",                                              // unknown command
  };
  for (const char* args : bad) trionet::test::expect_usage_error(args);
  const auto no_command = run_cli("can");  // prints the usage text on stderr
  EXPECT_EQ(no_command.exit_code, 2);
  EXPECT_EQ(no_command.out, "");
  EXPECT_NE(no_command.err.find("usage"), std::string::npos);
  EXPECT_NE(run_cli("can encode --from 1 --to 4 --vr 256 --value 1").err.find("--vr"), std::string::npos);
  EXPECT_NE(run_cli("can encode --from 1 --to 4 --vr 1").err.find("--value"), std::string::npos);
}

TEST(CanCli, DecodeBothFormsAndEveryErrorReason) {
  const std::string input =
      "(1700000000.123456) can0 028#0100000000020D7A\n"
      "017#FF01000000010000\n"
      "\n"
      "not candump\n"
      "028#01000000000200\n"
      "028#0102000000000000\n"
      "028#0100000000002710\n"
      "03C#0100000000000000\n"
      "   \n"
      "00A#0000000000000000";  // no final newline
  const auto r = run_cli("can decode", input);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(
      r.out,
      "{\"event\":\"vr\",\"line\":1,\"time\":\"1700000000.123456\",\"interface\":\"can0\",\"id\":40,\"from\":1,"
      "\"to\":4,\"vr\":1,\"negative\":false,\"int\":2,\"frac\":3450,\"value\":2.345}\n"
      "{\"event\":\"vr\",\"line\":2,\"id\":23,\"from\":5,\"to\":2,\"vr\":255,\"negative\":true,\"int\":1,\"frac\":0,"
      "\"value\":-1}\n"
      "{\"event\":\"error\",\"line\":4,\"reason\":\"syntax\",\"detail\":\"identifier\"}\n"
      "{\"event\":\"error\",\"line\":5,\"reason\":\"bad_dlc\",\"id\":40}\n"
      "{\"event\":\"error\",\"line\":6,\"reason\":\"bad_sign\",\"id\":40}\n"
      "{\"event\":\"error\",\"line\":7,\"reason\":\"bad_fraction\",\"id\":40}\n"
      "{\"event\":\"frame\",\"line\":8,\"kind\":\"foreign_id\",\"id\":60,\"length\":8}\n"
      "{\"event\":\"vr\",\"line\":10,\"id\":10,\"from\":2,\"to\":1,\"vr\":0,\"negative\":false,\"int\":0,"
      "\"frac\":0,\"value\":0}\n");
}

TEST(CanCli, DecodeNodeCountChangesWhichIdentifiersAreKnown) {
  const std::string input = "03C#0100000000000000\n(1.000001) can1 06D#0300FFFFFFFF270F\n";
  const auto five = run_cli("can decode --nodes 5", input);
  EXPECT_EQ(five.out,
            "{\"event\":\"frame\",\"line\":1,\"kind\":\"foreign_id\",\"id\":60,\"length\":8}\n"
            "{\"event\":\"frame\",\"line\":2,\"time\":\"1.000001\",\"interface\":\"can1\",\"kind\":\"foreign_id\","
            "\"id\":109,\"length\":8}\n");
  const auto eleven = run_cli("can decode --nodes 11", input);
  EXPECT_EQ(
      eleven.out,
      "{\"event\":\"vr\",\"line\":1,\"id\":60,\"from\":1,\"to\":6,\"vr\":1,\"negative\":false,\"int\":0,"
      "\"frac\":0,\"value\":0}\n"
      "{\"event\":\"vr\",\"line\":2,\"time\":\"1.000001\",\"interface\":\"can1\",\"id\":109,\"from\":11,\"to\":10,"
      "\"vr\":3,\"negative\":false,\"int\":4294967295,\"frac\":9999,\"value\":4294967295.9999}\n");
  const auto bad = run_cli("can decode --nodes 0", input);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.out, "");
  EXPECT_NE(bad.err, "");
}

TEST(CanCli, EncodeThenDecodeEveryPairOfFiveNodes) {
  std::string lines;
  for (int from = 1; from <= 5; ++from) {
    for (int to = 1; to <= 5; ++to) {
      if (from == to) continue;
      const auto r = run_cli("can encode --from " + std::to_string(from) + " --to " + std::to_string(to) +
                             " --vr " + std::to_string(from * 10 + to) + " --value -" + std::to_string(from) +
                             "." + std::to_string(to));
      ASSERT_EQ(r.exit_code, 0);
      lines += r.out;
    }
  }
  const auto decoded = run_cli("can decode", lines);
  std::string expected;
  int line = 0;
  for (int from = 1; from <= 5; ++from) {
    for (int to = 1; to <= 5; ++to) {
      if (from == to) continue;
      const int id = 10 * to + (from < to ? from : from - 1) - 1;
      expected += "{\"event\":\"vr\",\"line\":" + std::to_string(++line) + ",\"id\":" + std::to_string(id) +
                  ",\"from\":" + std::to_string(from) +
                  ",\"to\":" + std::to_string(to) + ",\"vr\":" + std::to_string(from * 10 + to) +
                  ",\"negative\":true,\"int\":" + std::to_string(from) +
                  ",\"frac\":" + std::to_string(to * 1000) + ",\"value\":-" + std::to_string(from) + "." +
                  std::to_string(to) + "}\n";
    }
  }
  EXPECT_EQ(decoded.out, expected);
}

// The note's two tables, one after the other, in columns aligned with blanks.
TEST(CanCli, TableReproducesTheNotesTwoTablesForFiveNodes) {
  const auto r = run_cli("can table --nodes 5");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out,
            "Node Base address  Rx #1  Rx #2  Rx #3  Rx #4\n"
            "10                 10     11     12     13\n"
            "20                 20     21     22     23\n"
            "30                 30     31     32     33\n"
            "40                 40     41     42     43\n"
            "50                 50     51     52     53\n"
            "\n"
            "Node Base address  Tx #5  Tx #6  Tx #7  Tx #8\n"
            "10                 20     30     40     50\n"
            "20                 31     41     51     10\n"
            "30                 42     52     11     21\n"
            "40                 53     12     22     32\n"
            "50                 13     23     33     43\n");
  EXPECT_EQ(run_cli("can table").out, r.out) << "5 nodes is the default";
}

// Columns widen for three-digit identifiers and two-digit channels; no line ends in a blank.
TEST(CanCli, TableForTwoAndElevenNodes) {
  EXPECT_EQ(run_cli("can table --nodes 2").out,
            "Node Base address  Rx #1\n10                 10\n20                 20\n\n"
            "Node Base address  Tx #5\n10                 20\n20                 10\n");
  const auto eleven = run_cli("can table --nodes 11");
  EXPECT_EQ(eleven.exit_code, 0);
  EXPECT_NE(eleven.out.find("Node Base address  Rx #1  Rx #2  Rx #3  Rx #4  Rx #5  Rx #6  Rx #7  Rx #8  Rx #9  "
                            "Rx #10\n"),
            std::string::npos);
  EXPECT_NE(eleven.out.find("\n110                110    111    112    113    114    115    116    117    118    "
                            "119\n"),
            std::string::npos);
  EXPECT_NE(eleven.out.find("Tx #13  Tx #14\n"), std::string::npos);
  EXPECT_EQ(eleven.out.find(" \n"), std::string::npos);
  EXPECT_EQ(eleven.out.find('\t'), std::string::npos);
  const auto bad = run_cli("can table --nodes 12");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.out, "");
  EXPECT_NE(bad.err.find("--nodes"), std::string::npos);
}

TEST(CanCli, HelpGoesToStdout) {
  const auto r = run_cli("can --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("encode"), std::string::npos);
  EXPECT_EQ(r.err, "");
}

}  // namespace

#include <fstream>

#include "trionet/host/capture.hpp"
#include "trionet/host/pcapng.hpp"

namespace {

TEST(CanCli, DecodeACaptureRecordByRecord) {
  using namespace trionet::host;
  const std::string capture = "/tmp/trionet-can-" + std::to_string(::getpid()) + ".pcapng";
  {
    std::ofstream file(capture, std::ios::binary);
    pcapng_writer writer(file);
    const std::uint32_t bus = writer.add_interface("can0", capture_network::can).id;
    trionet::can::frame vr;
    vr.id = 0x028;
    vr.dlc = 8;
    const std::uint8_t data[8] = {0x01, 0x00, 0x00, 0x00, 0x00, 0x02, 0x0D, 0x7A};
    for (int i = 0; i < 8; ++i) vr.data[i] = data[i];
    trionet::can::frame remote;
    remote.id = 0x123 | trionet::can::frame::remote_flag;
    for (const trionet::can::frame& f : {vr, remote}) {
      const auto record = socketcan_record(f);
      ASSERT_EQ(writer.write(bus, 1700000000123456789ull, trionet::byte_view(record.data(), record.size())),
                pcapng_write_status::ok);
    }
  }
  const auto r = run_cli("can decode --pcap " + capture);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out,
            "{\"event\":\"vr\",\"record\":1,\"interface_id\":0,\"interface\":\"can0\",\"time\":\"1700000000.123456789\","
            "\"id\":40,\"from\":1,\"to\":4,\"vr\":1,\"negative\":false,\"int\":2,\"frac\":3450,\"value\":2.345}\n"
            "{\"event\":\"frame\",\"record\":2,\"interface_id\":0,\"interface\":\"can0\",\"time\":\"1700000000.123456789\","
            "\"kind\":\"remote\",\"id\":291,\"length\":0}\n");
  const auto fields = run_cli("can decode --pcap " + capture + " --json");
  // The shortest decimal that reads back as the same double (tshark shows 2.345 too).
  EXPECT_NE(fields.out.find("\"trionet_can.value\":2.345}"), std::string::npos) << fields.out;
  const auto ring = run_cli("ring decode --pcap " + capture);
  EXPECT_EQ(ring.out.find("{\"event\":\"other_network\",\"record\":1"), 0u) << ring.out;
  std::remove(capture.c_str());
}

// A CAN FD record whose identifier has the error flag is an error frame, as candump text `20000080##0` is;
// without the flag it is a CAN FD frame.
TEST(CanCli, DecodeACaptureCanFdRecordWithTheErrorFlagAsAnErrorFrame) {
  using namespace trionet::host;
  const std::string capture = "/tmp/trionet-can-fd-" + std::to_string(::getpid()) + ".pcapng";
  {
    std::ofstream file(capture, std::ios::binary);
    pcapng_writer writer(file);
    const std::uint32_t bus = writer.add_interface("can0", capture_network::can).id;
    for (const std::uint32_t id : {0x20000080U, 0x00000080U}) {
      std::uint8_t record[72] = {};  // struct canfd_frame: id, len 0, flags CANFD_FDF
      for (std::size_t i = 0; i < 4; ++i) record[i] = static_cast<std::uint8_t>(id >> (24 - 8 * i));
      record[5] = 0x04;
      ASSERT_EQ(writer.write(bus, 1700000000000000000ull, trionet::byte_view(record, sizeof record)),
                pcapng_write_status::ok);
    }
  }
  const auto r = run_cli("can decode --pcap " + capture);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out,
            "{\"event\":\"frame\",\"record\":1,\"interface_id\":0,\"interface\":\"can0\",\"time\":\"1700000000.000000000\","
            "\"kind\":\"error_frame\",\"id\":128,\"length\":0}\n"
            "{\"event\":\"frame\",\"record\":2,\"interface_id\":0,\"interface\":\"can0\",\"time\":\"1700000000.000000000\","
            "\"kind\":\"fd\",\"id\":128,\"length\":0}\n");
  std::remove(capture.c_str());
}

// A remote request gives the same event from candump text and from a capture of it (s38: the capture gave
// length 0 where the record holds 8), an extended one says that it is remote (it read as 8 data bytes), and a
// 3-digit identifier above 7FF is bad_identifier in a CAN FD frame too (it was kind fd with id 2339).
TEST(CanCli, RemoteFramesAndIdentifiersAboveTheStandardRangeAreNamed) {
  const std::string lines = "028#R8\n12345678#R8\n40000028#0100000000020D7A\n923##1AA\n923#01\n";
  const auto text = run_cli("can decode", lines);
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_EQ(text.out,
            "{\"event\":\"frame\",\"line\":1,\"kind\":\"remote\",\"id\":40,\"length\":8}\n"
            "{\"event\":\"frame\",\"line\":2,\"kind\":\"extended\",\"id\":305419896,\"length\":8,\"remote\":true}\n"
            "{\"event\":\"frame\",\"line\":3,\"kind\":\"extended\",\"id\":40,\"length\":8,\"remote\":true}\n"
            "{\"event\":\"frame\",\"line\":4,\"kind\":\"bad_identifier\",\"id\":2339,\"length\":1}\n"
            "{\"event\":\"frame\",\"line\":5,\"kind\":\"bad_identifier\",\"id\":2339,\"length\":1}\n");
  const std::string capture = "/tmp/trionet-can-remote-" + std::to_string(::getpid()) + ".pcapng";
  const auto written = run_cli("can monitor - --json --pcap " + capture, "028#R8\n12345678#R8\n");
  ASSERT_EQ(written.exit_code, 0) << written.err;
  const auto read = run_cli("can decode --pcap " + capture);
  EXPECT_EQ(read.exit_code, 0) << read.err;
  EXPECT_NE(read.out.find("\"kind\":\"remote\",\"id\":40,\"length\":8}\n"), std::string::npos) << read.out;
  EXPECT_NE(read.out.find("\"kind\":\"extended\",\"id\":305419896,\"length\":8,\"remote\":true}\n"),
            std::string::npos)
      << read.out;
  std::remove(capture.c_str());
}

// `decode --pcap --json` gives a CAN FD frame's and an error frame's fields as Wireshark's SocketCAN dissector
// shows them (s38: no field at all; wireshark_dissect_random checks their values against tshark).
TEST(CanCli, CaptureFieldsOfCanFdAndErrorFrames) {
  const std::string capture = "/tmp/trionet-can-fd-fields-" + std::to_string(::getpid()) + ".pcapng";
  const auto written = run_cli("can monitor - --json --pcap " + capture, "028##1AA\n12345678##3112233\n20000080#0000000000000000\n");
  ASSERT_EQ(written.exit_code, 0) << written.err;
  const auto fields = run_cli("can decode --pcap " + capture + " --json");
  EXPECT_EQ(fields.exit_code, 0) << fields.err;
  EXPECT_NE(fields.out.find("\"can.id\":40,\"can.flags.xtd\":false,\"can.len\":1,\"canfd.flags.brs\":true,"
                            "\"canfd.flags.esi\":false}"),
            std::string::npos)
      << fields.out;
  EXPECT_NE(fields.out.find("\"can.id\":305419896,\"can.flags.xtd\":true,\"can.len\":3,\"canfd.flags.brs\":true,"
                            "\"canfd.flags.esi\":true}"),
            std::string::npos)
      << fields.out;
  EXPECT_NE(fields.out.find("\"can.flags.err\":true,\"can.len\":8}"), std::string::npos) << fields.out;
  std::remove(capture.c_str());
}

// A file that is not pcapng is named in a sentence, not a status name (s38: "FILE: not_pcapng").
TEST(CanCli, AFileThatIsNotPcapngIsSaidInWords) {
  const std::string path = "/tmp/trionet-not-pcapng-" + std::to_string(::getpid()) + ".txt";
  {
    std::ofstream file(path);
    file << "028#0100000000020D7A\n";
  }
  const auto r = run_cli("can decode --pcap " + path);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "trionet: " + path +
                       ": not a pcapng capture (it does not start with a section header block; a libpcap .pcap file "
                       "converts with editcap -F pcapng)\n");
  std::remove(path.c_str());
}

// A capture that cannot be written names the system's cause (s38: "writing the capture failed" alone).
TEST(CanCli, ACaptureThatCannotBeWrittenNamesTheCause) {
  for (const char* command : {"can monitor - --pcap /dev/full", "can node - --node 4 --pcap /dev/full",
                              "ring monitor - --pcap /dev/full"}) {
    const auto r = run_cli(command, "028#0100000000020D7A\n");
    EXPECT_EQ(r.exit_code, 1) << command;
    EXPECT_NE(r.err.find("writing the capture"), std::string::npos) << command << ": " << r.err;
    EXPECT_NE(r.err.find("failed: No space left on device\n"), std::string::npos) << command << ": " << r.err;
  }
}

TEST(CanCli, HelpOnEveryCommand) {
  for (const char* command : {"can encode --help", "can decode -h", "can table --help", "can --help"}) {
    const auto r = run_cli(command);
    EXPECT_EQ(r.exit_code, 0) << command;
    EXPECT_EQ(r.out.rfind("usage: trionet can", 0), 0u) << command << ": " << r.out;
    EXPECT_EQ(r.err, "") << command;
  }
}

}  // namespace

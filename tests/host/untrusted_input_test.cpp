// The host helpers every reader of untrusted input goes through: bounded file reading
// (trionet/host/files.hpp), the one function that echoes untrusted text in messages (host::printable), and
// the progress line for long work (trionet/host/progress.hpp).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <future>
#include <iterator>
#include <string>
#include <thread>

#include "support/temp_files.hpp"
#include "trionet/host/files.hpp"
#include "trionet/host/progress.hpp"
#include "trionet/host/q32_text.hpp"
#include "trionet/host/text.hpp"

namespace {

using trionet::test::temp_file;
using trionet::test::temp_path;
using trionet::host::file_result;
using trionet::host::file_status;
using trionet::host::parse_q32;
using trionet::host::printable;
using trionet::host::progress;
using trionet::host::read_bounded_fd;
using trionet::host::read_bounded_file;

// ---- parse_q32: decimal text to Q32.32, exactly (docs/protocol.md 1.3) ----

using trionet::host::q32_text_status;

// The raw Q32.32 of `text`, or the status when there is none (as a negative number below any raw value
// a test expects, so that a wrong status shows in the failure).
std::int64_t q32_of(const std::string& text) {
  const trionet::host::q32_text_result r = parse_q32(text);
  EXPECT_EQ(r.status, q32_text_status::ok) << text;
  return r.raw;
}
q32_text_status q32_status_of(const std::string& text) { return parse_q32(text).status; }

constexpr std::int64_t q32_max = INT64_MAX;  // 2^31 - 2^-32
constexpr std::int64_t q32_min = INT64_MIN;  // -2^31

// The top of the range as docs/protocol.md 1.3 writes it, and as the tool's message wrote it, is in range:
// a double holds neither (both read as 2^31).
TEST(ParseQ32, TheDocumentedTopOfTheRangeIsAccepted) {
  EXPECT_EQ(q32_of("2147483647.99999999977"), q32_max);
  EXPECT_EQ(q32_of("2147483647.9999999998"), q32_max);
  EXPECT_EQ(q32_of("2147483647.9999999"), std::int64_t{0x7ffffffffffffe53});
  EXPECT_EQ(q32_of("2147483647.99999999976716935634613037109375"), q32_max);  // 2^31 - 2^-32 exactly
  EXPECT_EQ(q32_of("-2147483648"), q32_min);
}

// The range a message prints is the one docs/protocol.md 1.3 gives, and both of its ends are in range.
TEST(ParseQ32, TheRangeInMessagesIsTheDocumentedOneAndInRange) {
  const std::string range = trionet::host::q32_range_text;  // "[-2147483648, 2147483647.99999999977]"
  const std::size_t comma = range.find(", ");
  ASSERT_NE(comma, std::string::npos);
  const std::string bottom = range.substr(1, comma - 1);
  const std::string top = range.substr(comma + 2, range.size() - comma - 3);
  EXPECT_EQ(q32_of(bottom), q32_min);
  EXPECT_EQ(q32_of(top), q32_max);
  std::ifstream doc(std::string(TRIONET_SOURCE_DIR) + "/docs/protocol.md");
  const std::string text((std::istreambuf_iterator<char>(doc)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(text.empty());
  // The document writes the minus sign as U+2212.
  EXPECT_NE(text.find("(\xe2\x88\x92" + bottom.substr(1) + " to " + top + ")"), std::string::npos) << range;
}

TEST(ParseQ32, ExactRoundingWhereADoubleLosesDigits) {
  EXPECT_EQ(q32_of("2147483647.5000001"), std::int64_t{0x7fffffff800001ad});  // via a double: ...80000000
  EXPECT_EQ(q32_of("123456789.123456789"), std::int64_t{0x075bcd151f9add37});  // via a double: ...1f9add40
  EXPECT_EQ(q32_of("-123456789.123456789"), -std::int64_t{0x075bcd151f9add37});
  EXPECT_EQ(q32_of("0.3"), std::int64_t{0x4ccccccd});  // docs/protocol.md's example
  EXPECT_EQ(q32_of("99"), std::int64_t{99} << 32);
}

// Ties (an odd multiple of 2^-33) go away from zero; a hair below a tie goes toward zero.
TEST(ParseQ32, TiesGoAwayFromZero) {
  EXPECT_EQ(q32_of("0.000000000116415321826934814453125"), 1);  // 2^-33
  EXPECT_EQ(q32_of("-0.000000000116415321826934814453125"), -1);
  EXPECT_EQ(q32_of("0.000000000116415321826934814453124999"), 0);
  EXPECT_EQ(q32_of("-0.000000000116415321826934814453124999"), 0);
  EXPECT_EQ(q32_of("0.000000000349245965480804443359375"), 2);  // 3 * 2^-33
  EXPECT_EQ(q32_of("1.000000000116415321826934814453125"), (std::int64_t{1} << 32) + 1);
  EXPECT_EQ(q32_of("1e-10"), 0);   // below 2^-33
  EXPECT_EQ(q32_of("-1e-10"), 0);  // no negative zero
  EXPECT_EQ(q32_of("2e-10"), 1);
}

TEST(ParseQ32, NegativeValuesAndTheBottomOfTheRange) {
  EXPECT_EQ(q32_of("-0.5"), -(std::int64_t{1} << 31));
  EXPECT_EQ(q32_of("-2.5"), -(std::int64_t{5} << 31));
  EXPECT_EQ(q32_of("-0"), 0);
  EXPECT_EQ(q32_of("-2147483648.0000000001"), q32_min);  // rounds to -2^31, in range
  EXPECT_EQ(q32_of("-2147483648.000000000116415321826934814453124"), q32_min);
  EXPECT_EQ(q32_status_of("-2147483648.000000000116415321826934814453125"), q32_text_status::out_of_range);  // a tie
  EXPECT_EQ(q32_status_of("-2147483648.0000000002"), q32_text_status::out_of_range);
  EXPECT_EQ(q32_status_of("-2147483649"), q32_text_status::out_of_range);
}

TEST(ParseQ32, AboveTheTopIsOutOfRangeNeverWrapped) {
  EXPECT_EQ(q32_of("2147483647.999999999883584678173065185546874"), q32_max);  // just below the tie
  EXPECT_EQ(q32_status_of("2147483647.999999999883584678173065185546875"), q32_text_status::out_of_range);
  EXPECT_EQ(q32_status_of("2147483647.9999999999"), q32_text_status::out_of_range);
  EXPECT_EQ(q32_status_of("2147483648"), q32_text_status::out_of_range);
  EXPECT_EQ(q32_status_of("4294967296"), q32_text_status::out_of_range);  // would wrap to 0
  EXPECT_EQ(q32_status_of("18446744073709551616"), q32_text_status::out_of_range);
  EXPECT_EQ(q32_status_of("1e400"), q32_text_status::out_of_range);
  EXPECT_EQ(q32_status_of("-1e400"), q32_text_status::out_of_range);
}

TEST(ParseQ32, ExponentForms) {
  EXPECT_EQ(q32_of("1e3"), std::int64_t{1000} << 32);
  EXPECT_EQ(q32_of("1E+3"), std::int64_t{1000} << 32);
  EXPECT_EQ(q32_of("2.5E-4"), std::int64_t{1073742});  // 0.00025 * 2^32 = 1073741.8
  EXPECT_EQ(q32_of("+25e-5"), std::int64_t{1073742});
  EXPECT_EQ(q32_of("0.0000025e2"), std::int64_t{1073742});
  EXPECT_EQ(q32_of("21474836475e-1"), std::int64_t{0x7fffffff80000000});
  EXPECT_EQ(q32_of("-2.147483648e9"), q32_min);
  EXPECT_EQ(q32_of("1e-400"), 0);
  EXPECT_EQ(q32_of("0e999999999999999999999"), 0);
  EXPECT_EQ(q32_of("1e-999999999999999999999"), 0);
  EXPECT_EQ(q32_status_of("1e999999999999999999999"), q32_text_status::out_of_range);
  EXPECT_EQ(q32_of("100000000000000000000e-20"), std::int64_t{1} << 32);
}

TEST(ParseQ32, LongInputsAreExactAndBounded) {
  EXPECT_EQ(q32_of("0." + std::string(60, '3')), std::int64_t{0x55555555});
  EXPECT_EQ(q32_of("0." + std::string(60, '9')), std::int64_t{1} << 32);
  EXPECT_EQ(q32_of("1." + std::string(60, '0') + "1"), std::int64_t{1} << 32);
  EXPECT_EQ(q32_of(std::string(900, '0') + "7." + std::string(90, '0')), std::int64_t{7} << 32);
  const std::string longest = "0." + std::string(trionet::host::max_q32_text - 3, '0') + "1";
  ASSERT_EQ(longest.size(), trionet::host::max_q32_text);
  EXPECT_EQ(q32_of(longest), 0);
  EXPECT_EQ(q32_status_of(longest + "0"), q32_text_status::too_long);
  EXPECT_EQ(q32_status_of(std::string(1 << 20, '9')), q32_text_status::too_long);
}

// The syntax is parse_real's, word for word: the same texts are numbers (here, all within a double's
// range) and the same are not.
TEST(ParseQ32, AcceptsWhatParseRealAccepts) {
  const char* const texts[] = {"99",  "-2.345", "+1e3", ".5",   "-.5",  "1.",    "+-5",   "0",     "-0",    "2.5E-4",
                               "1e+2", "1E-2", "",     ".",    "-",    "+",     "++5",   "-+5",   "--5",   "1e",
                               "1e+",  "e5",   "1.2.3", "1,5",  " 1",   "1 ",    "0x10",  "0x1p3", "nan",   "NaN",
                               "inf",  "-inf", "infinity", "1e5.5", "1e--2", "12abc", "1d3", "\xd9\xa3", "1_000", "1e3 "};
  for (const char* text : texts) {
    double ignored = 0;
    const bool real = trionet::host::parse_real(text, -1.7976931348623157e308, 1.7976931348623157e308, ignored);
    EXPECT_EQ(parse_q32(text).status != q32_text_status::not_a_number, real) << '"' << text << '"';
  }
  EXPECT_EQ(q32_status_of("+-5"), q32_text_status::not_a_number);  // one sign at most
}

// Regression: "+-5" was read as -5 (the '+' skipped, then from_chars took the '-'). One sign at most, for
// the integer and real readers of every option.
TEST(ParseNumbers, TwoSignsAreNotANumber) {
  long long whole = 1;
  double real = 1;
  for (const char* text : {"+-5", "-+5", "++5", "--5", "+-0"}) {
    EXPECT_FALSE(trionet::host::parse_integer(text, -100, 100, whole)) << text;
    EXPECT_FALSE(trionet::host::parse_real(text, -100, 100, real)) << text;
  }
  EXPECT_EQ(whole, 1);
  EXPECT_EQ(real, 1);
  ASSERT_TRUE(trionet::host::parse_integer("+5", -100, 100, whole));
  EXPECT_EQ(whole, 5);
  ASSERT_TRUE(trionet::host::parse_integer("-5", -100, 100, whole));
  EXPECT_EQ(whole, -5);
  ASSERT_TRUE(trionet::host::parse_real("-5.5", -100, 100, real));
  EXPECT_EQ(real, -5.5);
  ASSERT_TRUE(trionet::host::parse_real("+5.5", -100, 100, real));
  EXPECT_EQ(real, 5.5);
}

// ---- printable ----

TEST(Printable, PlainTextIsShownAsItIs) {
  EXPECT_EQ(printable("prog.bas"), "prog.bas");
  EXPECT_EQ(printable(""), "");
  EXPECT_EQ(printable("caf\xc3\xa9 \xe2\x82\xac"), "caf\xc3\xa9 \xe2\x82\xac");  // well-formed UTF-8
}

TEST(Printable, ControlCharactersAreShownEscapedNeverRaw) {
  EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\x00b");
  EXPECT_EQ(printable("\x1b[31mred"), "\\x1b[31mred");
  EXPECT_EQ(printable("bell\x07"), "bell\\x07");
  EXPECT_EQ(printable("del\x7f"), "del\\x7f");
  EXPECT_EQ(printable("a\r\n\tb"), "a\\r\\n\\tb");
  EXPECT_EQ(printable("back\\slash"), "back\\\\slash");
}

TEST(Printable, BytesThatAreNotWellFormedUtf8AreShownAsHex) {
  EXPECT_EQ(printable("\xff"), "\\xff");
  EXPECT_EQ(printable("\xc3"), "\\xc3");                  // cut sequence
  EXPECT_EQ(printable("\xc0\x80"), "\\xc0\\x80");         // overlong NUL
  EXPECT_EQ(printable("\xe0\x80\x9b"), "\\xe0\\x80\\x9b");  // overlong CSI
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a surrogate
  EXPECT_EQ(printable("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");  // above U+10FFFF
}

TEST(Printable, C1ControlsAndDirectionControlsAreEscaped) {
  EXPECT_EQ(printable("\xc2\x9b" "2J"), "\\xc2\\x9b2J");  // U+009B, a CSI to some terminals
  EXPECT_EQ(printable("ab\xe2\x80\xae" "cd"), "ab\\u202ecd");  // U+202E right-to-left override
  EXPECT_EQ(printable("\xe2\x81\xa6"), "\\u2066");
}

TEST(Printable, CutTo40CharactersWithAMark) {
  const std::string forty(40, 'x');
  EXPECT_EQ(printable(forty), forty);
  EXPECT_EQ(printable(forty + "y"), forty + "...");
  // Characters, not bytes: 41 two-byte characters are cut after 40 of them.
  std::string accents;
  for (int i = 0; i < 41; ++i) accents += "\xc3\xa9";
  EXPECT_EQ(printable(accents), accents.substr(0, 80) + "...");
  EXPECT_EQ(printable("abcdef", 3), "abc...");
}

TEST(Printable, AMegabyteOfHostileBytesGivesAShortLine) {
  std::string hostile;
  for (int i = 0; i < (1 << 20); ++i) hostile += static_cast<char>(i % 256);
  const std::string shown = printable(hostile);
  EXPECT_LE(shown.size(), 40U * 8U + 3U);
  for (const char c : shown) {
    const auto byte = static_cast<unsigned char>(c);
    EXPECT_TRUE(byte >= 0x20 && byte != 0x7f) << static_cast<int>(byte);
  }
}

// ---- read_bounded_file ----

TEST(ReadBoundedFile, ReadsAWholeFile) {
  const std::string path = temp_file("whole", "PRINT 1\n");
  std::string text = "old";
  const file_result r = read_bounded_file(path, 100, text);
  EXPECT_TRUE(r);
  EXPECT_EQ(text, "PRINT 1\n");
  std::remove(path.c_str());
}

TEST(ReadBoundedFile, AFileOfExactlyTheBoundIsRead_OneByteMoreIsRefused) {
  const std::string exact = temp_file("exact", std::string(64, 'a'));
  const std::string over = temp_file("over", std::string(65, 'a'));
  std::string text;
  EXPECT_TRUE(read_bounded_file(exact, 64, text));
  EXPECT_EQ(text.size(), 64U);
  const file_result r = read_bounded_file(over, 64, text);
  EXPECT_EQ(r.status, file_status::too_large);
  EXPECT_TRUE(text.empty());
  EXPECT_EQ(r.message("big.json", "profile"), "profile big.json is larger than 64 bytes");
  std::remove(exact.c_str());
  std::remove(over.c_str());
}

TEST(ReadBoundedFile, AMissingFileNamesTheCause) {
  std::string text;
  const file_result r = read_bounded_file("/nonexistent/x.bas", 100, text);
  EXPECT_EQ(r.status, file_status::cannot_open);
  EXPECT_EQ(r.system_error, ENOENT);
  EXPECT_EQ(r.message("/nonexistent/x.bas", "program"),
            "cannot open program /nonexistent/x.bas: No such file or directory");
}

TEST(ReadBoundedFile, AnUnreadableFileNamesTheCause) {
  if (::geteuid() == 0) GTEST_SKIP() << "root reads a file whatever its mode";
  const std::string path = temp_file("unreadable", "x");
  ::chmod(path.c_str(), 0);
  std::string text;
  const file_result r = read_bounded_file(path, 100, text);
  EXPECT_EQ(r.status, file_status::cannot_open);
  EXPECT_NE(r.message(path).find("Permission denied"), std::string::npos);
  std::remove(path.c_str());
}

TEST(ReadBoundedFile, ADirectoryIsRefused) {
  std::string text;
  const file_result r = read_bounded_file(".", 100, text);
  EXPECT_EQ(r.status, file_status::directory);
  EXPECT_EQ(r.message("."), ". is a directory, not a file");
}

TEST(ReadBoundedFile, ADeviceIsRefusedBeforeAByteIsRead) {
  std::string text;
  const file_result zero = read_bounded_file("/dev/zero", 100, text);
  EXPECT_EQ(zero.status, file_status::device);
  EXPECT_EQ(zero.message("/dev/zero"), "/dev/zero is a device, not a file");
  EXPECT_EQ(read_bounded_file("/dev/null", 100, text).status, file_status::device);
}

TEST(ReadBoundedFile, AnEndlessPipeIsCutAtTheBound) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  // The writer learns that the reader has gone from EPIPE, not from a signal that would end the test.
  void (*const old_handler)(int) = std::signal(SIGPIPE, SIG_IGN);
  std::thread writer([&] {
    const std::string block(4096, 'x');
    while (::write(fds[1], block.data(), block.size()) > 0) {
    }
  });
  std::string text;
  const file_result r = read_bounded_fd(fds[0], 100000, text);
  ::close(fds[0]);  // the writer's next write fails (EPIPE) and it ends
  writer.join();
  ::close(fds[1]);
  std::signal(SIGPIPE, old_handler);
  EXPECT_EQ(r.status, file_status::too_large);
  EXPECT_TRUE(text.empty());
}

// A writer that opens the FIFO at `path` (waiting for its reader), writes `text` and closes it at once.
std::thread fifo_writer(const std::string& path, const std::string& text) {
  return std::thread([path, text] {
    const int fd = ::open(path.c_str(), O_WRONLY);
    (void)!::write(fd, text.data(), text.size());
    ::close(fd);
  });
}

TEST(ReadBoundedFile, ANamedFifoIsReadToItsEnd) {
  const std::string path = temp_path("fifo");
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  std::thread writer = fifo_writer(path, "12 34\n");
  std::string text;
  const file_result r = read_bounded_file(path, 100, text);
  writer.join();
  ::unlink(path.c_str());
  EXPECT_TRUE(r) << r.message(path);
  EXPECT_EQ(text, "12 34\n");
}

// Writers that open the FIFO, write and close at once, round after round. A reader that opened the FIFO twice
// (a first look without waiting, then again to wait for the writer) lost what a writer wrote between its two
// opens and then waited for a writer for ever: the test above hung so in CI now and then. A read that hangs
// here is released by a writer that comes and goes, and fails the test.
TEST(ReadBoundedFile, AFifoWhoseWriterIsGoneAtOnceIsReadWhole) {
  const std::string path = temp_path("quick-fifo");
  for (int round = 0; round < 300; ++round) {
    ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
    std::thread writer = fifo_writer(path, "56 78\n");
    std::string text;
    std::future<file_result> reading =
        std::async(std::launch::async, [&] { return read_bounded_file(path, 100, text); });
    writer.join();
    const bool hung = reading.wait_for(std::chrono::seconds(5)) != std::future_status::ready;
    if (hung) {
      const int release = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
      if (release >= 0) ::close(release);
    }
    const file_result r = reading.get();
    ::unlink(path.c_str());
    ASSERT_FALSE(hung) << "round " << round << ": the reader waited for a writer that had come and gone";
    ASSERT_TRUE(r) << r.message(path);
    ASSERT_EQ(text, "56 78\n") << "round " << round;
  }
}

TEST(ReadBoundedFile, TheNameInAMessageIsShownEscaped) {
  std::string text;
  const std::string name = std::string("/nonexistent/\x1b[2J\0x", 19);
  const file_result r = read_bounded_file(name, 100, text);
  EXPECT_EQ(r.message(name), "cannot open /nonexistent/\\x1b[2J\\x00x: No such file or directory");
}

// ---- progress ----

TEST(Progress, TheLineSaysWhatIsDoneTheRateAndTheTimeLeft) {
  EXPECT_EQ(progress::line("ring simulate", "s of ring time", 12.5, 60, 3.2),
            "ring simulate: 12.5 of 60 s of ring time (21%), 3.91 s of ring time/s, 3.20 s elapsed, about 12.2 s "
            "left");
  EXPECT_EQ(progress::line("ring learn crc", "candidates", 1.5e6, 4e9, 100),
            "ring learn crc: 1.50 M of 4 G candidates (0%), 15 k candidates/s, 1 min 40 s elapsed, about 74 h 02 "
            "min left");
  // Without a total: no percentage and no estimate.
  EXPECT_EQ(progress::line("soak", "runs", 400, 0, 2), "soak: 400 runs, 200 runs/s, 2.00 s elapsed");
  // Nothing done yet: no rate.
  EXPECT_EQ(progress::line("soak", "runs", 0, 10, 2), "soak: 0 of 10 runs (0%)");
}

TEST(Progress, SilentWhenTheOutputIsNotATerminal) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  {
    progress shown("work", "items", 10, fds[1]);
    EXPECT_FALSE(shown.active());
    std::this_thread::sleep_for(std::chrono::milliseconds(600));
    shown.update(5);
  }
  ::close(fds[1]);
  char c = 0;
  EXPECT_EQ(::read(fds[0], &c, 1), 0);  // nothing was written
  ::close(fds[0]);
}

TEST(Progress, DrawnInPlaceOnATerminalAndClearedAtTheEnd) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  const int terminal = ::open(::ptsname(master), O_RDWR | O_NOCTTY);
  ASSERT_GE(terminal, 0);
  {
    progress shown("work", "items", 10, terminal);
    EXPECT_TRUE(shown.active());
    shown.update(1);  // too early: nothing is drawn in the first half second
    std::this_thread::sleep_for(std::chrono::milliseconds(600));
    shown.update(5);
  }
  ::close(terminal);
  std::string got;
  char chunk[512];
  ::fcntl(master, F_SETFL, O_NONBLOCK);
  for (ssize_t n = 0; (n = ::read(master, chunk, sizeof chunk)) > 0;) got.append(chunk, static_cast<std::size_t>(n));
  ::close(master);
  EXPECT_EQ(got.rfind("\rwork: 5 of 10 items (50%), ", 0), 0U) << got;
  EXPECT_EQ(got.substr(got.size() - 4), "\r\x1b[K") << got;
  EXPECT_EQ(got.find("work: 1 "), std::string::npos) << got;
}

}  // namespace

// The BASIC interpreter's grammar and semantics, one construct at a time (docs/basic.md), against a fake
// controller.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "basic/number_format.hpp"
#include "basic/program.hpp"
#include "basic/task.hpp"
#include "support/fake_controller.hpp"

namespace basic = trionet::basic;
using basic::task_state;
using basic::wait_reason;

namespace {

// A program compiled and ready to run on a fake controller.
class running {
 public:
  explicit running(const std::string& text, const basic::task_config& config = {}) {
    basic::compile_result r = basic::compile("test.bas", text);
    EXPECT_TRUE(r) << r.located_message();
    program_ = std::move(r.compiled);
    task = std::make_unique<basic::task>(program_, io, config);
  }
  running(const running&) = delete;
  running& operator=(const running&) = delete;

  /// Runs at clock `now` until the program ends, fails or waits (or `budget` statements).
  task_state go(std::uint32_t budget = 1000000) {
    task->run(budget);
    return task->state();
  }
  double var(const std::string& name) const {
    const double* v = task->find_variable(name);
    EXPECT_NE(v, nullptr) << "no variable " << name;
    return v != nullptr ? *v : std::nan("");
  }
  std::string printed(int channel) { return io.printed[channel]; }

  trionet::test::fake_controller io;
  std::unique_ptr<basic::task> task;

 private:
  basic::program program_;
};

}  // namespace

// ---- numbers as PRINT writes them ----

TEST(BasicNumbers, PrintWritesFourDecimalPlacesAsTheManualShows) {
  EXPECT_EQ(basic::format_print_number(1), "1.0000");  // the manual: PRINT INT(1.79) writes 1.0000
  EXPECT_EQ(basic::format_print_number(47104), "47104.0000");
  EXPECT_EQ(basic::format_print_number(0.1 + 0.2), "0.3000");  // 0.30000000000000004
  EXPECT_EQ(basic::format_print_number(1.0 / 3), "0.3333");
  EXPECT_EQ(basic::format_print_number(2.0 / 3), "0.6667");
  EXPECT_EQ(basic::format_print_number(-2.5), "-2.5000");
  EXPECT_EQ(basic::format_print_number(-0.00001), "0.0000");  // no sign on a value that rounds to zero
  EXPECT_EQ(basic::format_print_number(-0.0), "0.0000");
}

TEST(BasicNumbers, ReportsRoundToFourDecimalsAndDropTrailingZeros) {
  EXPECT_EQ(basic::format_value(0.1 + 0.2), "0.3");  // 0.30000000000000004
  EXPECT_EQ(basic::format_value(125), "125");
  EXPECT_EQ(basic::format_value(1.0 / 3), "0.3333");
  EXPECT_EQ(basic::format_value(2.0 / 3), "0.6667");
  EXPECT_EQ(basic::format_value(-2.5), "-2.5");
  EXPECT_EQ(basic::format_value(-0.00001), "0");
  EXPECT_EQ(basic::format_value(-0.0), "0");
  EXPECT_EQ(basic::format_value(0.02), "0.02");
  EXPECT_EQ(basic::format_value(1e6), "1000000");
  EXPECT_EQ(basic::format_value(99.99996), "100");
}

TEST(BasicNumbers, FormattedWidthAndDecimals) {
  EXPECT_EQ(basic::format_print_number(125, 6, 0), "   125");
  EXPECT_EQ(basic::format_print_number(0.2 + 1e-16, 8, 1), "     0.2");
  EXPECT_EQ(basic::format_print_number(0.02, 0, 2), "0.02");
  EXPECT_EQ(basic::format_print_number(-0.01, 4, 1), " 0.0");
  EXPECT_EQ(basic::format_print_number(-1.25, 6, 1), "  -1.2");   // the double below -1.25 rounds away
  EXPECT_EQ(basic::format_print_number(123456, 3, 0), "123456");  // a wider number takes the room it needs
}

// ---- text as Trio writes it ----

TEST(BasicText, LabelsCommentsAndSeveralStatementsOnALine) {
  running r(
      "' a comment line\n"
      "start: a=1 : b=2' a comment right after a statement\n"
      "REM a REM line, \"with quotes\n"
      "  c=a+b: REM the rest is a comment: d=9\n"
      "only_a_label:\n"
      "e=4\r\n"
      "f=5\r"
      "g=6");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("a"), 1);
  EXPECT_EQ(r.var("b"), 2);
  EXPECT_EQ(r.var("c"), 3);
  EXPECT_EQ(r.task->find_variable("d"), nullptr);  // inside the REM
  EXPECT_EQ(r.var("e"), 4);
  EXPECT_EQ(r.var("f"), 5);
  EXPECT_EQ(r.var("g"), 6);
  EXPECT_EQ(r.task->line(), 8u);  // CR LF and a lone CR each end a line
}

TEST(BasicText, AUtf8ByteOrderMarkAtTheStartIsNotProgramText) {
  running r("\xEF\xBB\xBF" "a=1\r\nb=a+1\r\n");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("a"), 1);
  EXPECT_EQ(r.var("b"), 2);
}

TEST(BasicText, NamesAndKeywordsIgnoreCase) {
  running r("Length=2: LENGTH=LENGTH+1\nif length=3 then Goto Done\nlength=0\ndone: x=Vr(0)");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("length"), 3);
  EXPECT_EQ(r.task->variable_name(0), "length");
}

// ---- expressions ----

TEST(BasicExpressions, ArithmeticAndPrecedence) {
  running r("a=2+3*4\nb=(2+3)*4\nc=-2*-3\nd=10/4\ne=7 MOD 3\nf=-7 MOD 3\ng=7.9 MOD 2\nh=2-3-4\ni=.5+$1F\nj=-(1+1)");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("a"), 14);
  EXPECT_EQ(r.var("b"), 20);
  EXPECT_EQ(r.var("c"), 6);
  EXPECT_EQ(r.var("d"), 2.5);
  EXPECT_EQ(r.var("e"), 1);
  EXPECT_EQ(r.var("f"), -1);  // MOD on the integer parts; the sign follows the left side
  EXPECT_EQ(r.var("g"), 1);
  EXPECT_EQ(r.var("h"), -5);
  EXPECT_EQ(r.var("i"), 31.5);
  EXPECT_EQ(r.var("j"), -2);
}

TEST(BasicExpressions, NumbersAreDoubles) {
  running r("a=0.1+0.2\nb=1/3");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("a"), 0.1 + 0.2);
  EXPECT_EQ(r.var("b"), 1.0 / 3);
}

TEST(BasicExpressions, ComparisonsGiveTrueMinusOneAndFalseZero) {
  running r("a=1=1\nb=1<>1\nc=1<2\nd=2>1\ne=2<=2\nf=3>=4\ng=TRUE\nh=FALSE\ni=1+1=2");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("a"), -1);
  EXPECT_EQ(r.var("b"), 0);
  EXPECT_EQ(r.var("c"), -1);
  EXPECT_EQ(r.var("d"), -1);
  EXPECT_EQ(r.var("e"), -1);
  EXPECT_EQ(r.var("f"), 0);
  EXPECT_EQ(r.var("g"), -1);
  EXPECT_EQ(r.var("h"), 0);
  EXPECT_EQ(r.var("i"), -1);  // arithmetic before comparison
}

TEST(BasicExpressions, AndOrXorNotWorkOnTheIntegerParts) {
  running r(
      "a=12 AND 10\nb=12 OR 3\nc=12 XOR 10\nd=NOT 0\ne=NOT TRUE\nf=NOT(5)\ng=(1=1)&(2=2)\nh=(1=1)&(2=3)\n"
      "i=NOT 1=2\nj=1=1 OR 1=2 AND 1=2\nk=2.9 AND 3");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("a"), 8);
  EXPECT_EQ(r.var("b"), 15);
  EXPECT_EQ(r.var("c"), 6);
  EXPECT_EQ(r.var("d"), -1);
  EXPECT_EQ(r.var("e"), 0);
  EXPECT_EQ(r.var("f"), -6);
  EXPECT_EQ(r.var("g"), -1);  // '&' is AND, as the manual's Example 1 writes it
  EXPECT_EQ(r.var("h"), 0);
  EXPECT_EQ(r.var("i"), -1);  // NOT binds looser than '='
  EXPECT_EQ(r.var("j"), -1);  // AND binds tighter than OR
  EXPECT_EQ(r.var("k"), 2);
}

TEST(BasicExpressions, AbsAndInt) {
  running r("a=ABS(-2.5)\nb=INT(2.7)\nc=INT(-2.7)");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("a"), 2.5);
  EXPECT_EQ(r.var("b"), 2);
  EXPECT_EQ(r.var("c"), -2);  // the integer part: toward zero
}

TEST(BasicExpressions, VrReadAndWrite) {
  running r("length=2\nVR(length)=VR(length)+0.1\nVR(length*10)=7\nx=VR(20)+VR(2.9)");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.io.vrs[2], 0.1);
  EXPECT_EQ(r.io.vrs[20], 7);
  EXPECT_EQ(r.var("x"), 7.1);  // VR(2.9) is VR(2)
}

TEST(BasicExpressions, AxisParametersBelongToTheBaseAxisOrTheAxisNamed) {
  running r("SPEED=VR(1)\nAccel=SPEED*2\nx=ACCEL\nSPEED AXIS(2)=7\nBASE(2)\ny=SPEED\nz=SPEED AXIS(0)");
  r.io.vrs[1] = 0.02;
  EXPECT_EQ(r.go(), task_state::ended);
  const basic::machine& hw = r.io.hardware_state;
  EXPECT_EQ(hw.axis_value(0, basic::axis_parameter::speed), 0.02);
  EXPECT_EQ(hw.axis_value(0, basic::axis_parameter::accel), 0.04);
  EXPECT_EQ(hw.axis_value(2, basic::axis_parameter::speed), 7);
  EXPECT_EQ(r.var("x"), 0.04);
  EXPECT_EQ(r.var("y"), 7);
  EXPECT_EQ(r.var("z"), 0.02);
  EXPECT_EQ(r.task->variable_count(), 3u);  // SPEED and ACCEL are not variables
}

TEST(BasicMotion, AVeryLongMoveRunsToItsLimitAndDoesNotStall) {
  // The path length of MOVE(1e155) squared overflows a double: the move used to get no direction and stall.
  running r("FS_LIMIT=100\nSPEED=1000\nACCEL=100000\nDECEL=100000\nMOVE(1e155)");
  EXPECT_EQ(r.go(), task_state::ended);
  basic::machine& hw = r.io.hardware_state;
  for (int tick = 0; tick < 50; ++tick) hw.servo_tick();
  EXPECT_GT(hw.axis_value(0, basic::axis_parameter::dpos), 30);
  for (int tick = 0; tick < 200 && hw.any_motion(); ++tick) hw.servo_tick();
  EXPECT_FALSE(hw.any_motion());
  EXPECT_EQ(hw.axis_value(0, basic::axis_parameter::dpos), 100);  // stopped at FS_LIMIT
  // Two axes, one distance near the largest double: the path is as long as it.
  running two("FS_LIMIT=100\nSPEED=1000\nACCEL=100000\nDECEL=100000\nBASE(0,1)\nMOVE(1e300,-3e299)");
  EXPECT_EQ(two.go(), task_state::ended);
  basic::machine& hw2 = two.io.hardware_state;
  for (int tick = 0; tick < 50; ++tick) hw2.servo_tick();
  EXPECT_GT(hw2.axis_value(0, basic::axis_parameter::dpos), 30);
  EXPECT_LT(hw2.axis_value(1, basic::axis_parameter::dpos), -9);
}

TEST(BasicExpressions, NetstatReadsAndNetstatZeroClears) {
  running r("a=NETSTAT\nNETSTAT=0\nb=NETSTAT");
  r.io.netstat_value = 8;
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("a"), 8);
  EXPECT_EQ(r.var("b"), 0);
  EXPECT_EQ(r.io.netstat_value, 0u);
}

// ---- control flow ----

TEST(BasicControl, OneLineIfThenElse) {
  running r(
      "a=5\n"
      "IF a>3 THEN b=1 ELSE b=2\n"
      "IF a>9 THEN c=1 ELSE c=2\n"
      "IF a=5 THEN d=1: e=1\n"  // every statement after THEN belongs to it
      "IF a=6 THEN f=1: g=1\n"
      "IF a=5 THEN IF a>9 THEN h=1 ELSE h=2\n"  // ELSE belongs to the nearest IF
      "IF a=5 THEN GOTO skip\n"
      "i=1\n"
      "skip: j=1");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("b"), 1);
  EXPECT_EQ(r.var("c"), 2);
  EXPECT_EQ(r.var("d"), 1);
  EXPECT_EQ(r.var("e"), 1);
  EXPECT_EQ(r.var("f"), 0);
  EXPECT_EQ(r.var("g"), 0);
  EXPECT_EQ(r.var("h"), 2);
  EXPECT_EQ(r.var("i"), 0);
  EXPECT_EQ(r.var("j"), 1);
}

TEST(BasicControl, BlockIfElseEndif) {
  running r(
      "FOR i=1 TO 3\n"
      "  IF i=1 THEN\n"
      "    one=one+1\n"
      "  ELSE\n"
      "    IF i=2 THEN\n"
      "      two=two+1\n"
      "    ELSE\n"
      "      other=other+1\n"
      "    ENDIF\n"
      "  ENDIF\n"
      "  IF i=3 THEN\n"
      "    three=1\n"
      "  ENDIF\n"
      "NEXT i");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("one"), 1);
  EXPECT_EQ(r.var("two"), 1);
  EXPECT_EQ(r.var("other"), 1);
  EXPECT_EQ(r.var("three"), 1);
}

TEST(BasicControl, GotoGosubReturn) {
  running r(
      "GOSUB add\n"
      "GOSUB add\n"
      "GOTO finish\n"
      "add: n=n+1\n"
      "  GOSUB twice\n"
      "  RETURN\n"
      "twice: m=m+2: RETURN\n"
      "finish: STOP\n"
      "never=1");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("n"), 2);
  EXPECT_EQ(r.var("m"), 4);
  EXPECT_EQ(r.var("never"), 0);
  EXPECT_EQ(r.task->line(), 8u);  // the STOP
}

TEST(BasicControl, RepeatUntilAndWhileWend) {
  running r(
      "REPEAT\n  a=a+1\nUNTIL a>=3\n"
      "REPEAT: b=b+1: UNTIL TRUE\n"  // the body runs once at least
      "WHILE c<4\n  c=c+1\nWEND\n"
      "WHILE FALSE\n  d=1\nWEND\n");  // and here not at all
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("a"), 3);
  EXPECT_EQ(r.var("b"), 1);
  EXPECT_EQ(r.var("c"), 4);
  EXPECT_EQ(r.var("d"), 0);
}

TEST(BasicControl, ForNextWithStep) {
  running r(
      "FOR i=1 TO 5: s=s+i: NEXT i\n"
      "FOR j=10 TO 1 STEP -3: t=t*10+j: NEXT\n"
      "FOR k=0 TO 1 STEP 0.25: u=u+1: NEXT k\n"
      "FOR m=5 TO 1: never=1: NEXT m\n"
      "last=10: FOR n=1 TO last: last=2: count=count+1: NEXT n\n");  // the end is taken once, at FOR
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("s"), 15);
  EXPECT_EQ(r.var("i"), 6);
  EXPECT_EQ(r.var("t"), 10741);  // 10, 7, 4, 1
  EXPECT_EQ(r.var("j"), -2);
  EXPECT_EQ(r.var("u"), 5);
  EXPECT_EQ(r.var("never"), 0);
  EXPECT_EQ(r.var("m"), 5);
  EXPECT_EQ(r.var("count"), 10);
}

TEST(BasicControl, StatementsAreCountedAndTheBudgetIsKept) {
  running r("a=1\nIF a=1 THEN b=1 ELSE b=2\nc=3");  // 1 + (IF, b=1) + 1 = 4; the jump over ELSE is free
  EXPECT_EQ(r.task->run(2), 2u);
  EXPECT_EQ(r.task->state(), task_state::running);
  EXPECT_EQ(r.var("b"), 0);
  EXPECT_EQ(r.task->run(100), 2u);
  EXPECT_EQ(r.task->state(), task_state::ended);
  EXPECT_EQ(r.task->statements(), 4u);
}

// ---- waiting ----

TEST(BasicWaiting, WaitUntilRechecksEachTurn) {
  running r("WAIT UNTIL VR(5)=1\nx=1");
  EXPECT_EQ(r.go(), task_state::waiting);
  EXPECT_EQ(r.task->waiting_for(), wait_reason::wait_until);
  EXPECT_EQ(r.go(), task_state::waiting);
  r.io.vrs[5] = 1;
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("x"), 1);
}

TEST(BasicWaiting, WaCountsServoTicks) {
  running r("WA(2)\nx=1\nWA(0)\ny=1");  // the default servo period: 1 ms a tick
  EXPECT_EQ(r.go(), task_state::waiting);
  EXPECT_EQ(r.task->waiting_for(), wait_reason::wa);
  r.io.hardware_state.servo_tick();
  EXPECT_EQ(r.go(), task_state::waiting);
  r.io.hardware_state.servo_tick();
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("y"), 1);
}

TEST(BasicWaiting, GetWaitsForACharacterAndKeyDoesNot) {
  running r("a=KEY#4\nGET #4,c\nb=KEY#3\nGET#3, VR(7)\n");
  EXPECT_EQ(r.go(), task_state::waiting);
  EXPECT_EQ(r.task->waiting_for(), wait_reason::get);
  EXPECT_EQ(r.var("a"), 0);
  r.io.received = {'I', 13};
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.var("c"), 'I');
  EXPECT_EQ(r.var("b"), -1);
  EXPECT_EQ(r.io.vrs[7], 13);
}

TEST(BasicWaiting, PrintWaitsUntilEverythingIsQueued) {
  running r("PRINT #10,\"HELLO\"\nx=1");
  r.io.room = 3;
  EXPECT_EQ(r.go(), task_state::waiting);
  EXPECT_EQ(r.task->waiting_for(), wait_reason::print);
  EXPECT_EQ(r.printed(10), "HEL");
  EXPECT_EQ(r.go(), task_state::waiting);  // still no room
  r.io.room = 100;
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.printed(10), "HELLO\r\n");  // the rest, not the whole text again
}

TEST(BasicWaiting, SendWaitsForRoomAndEvaluatesOnce) {
  running r("VR(3)=5\nSEND(10,1,200,VR(3))\nSEND(11,2,10)\n");
  r.io.send_room = false;
  EXPECT_EQ(r.go(), task_state::waiting);
  EXPECT_EQ(r.task->waiting_for(), wait_reason::send);
  r.io.vrs[3] = 6;  // changed while waiting: the value was taken when SEND started
  r.io.send_room = true;
  EXPECT_EQ(r.go(), task_state::ended);
  ASSERT_EQ(r.io.variables_sent.size(), 1u);
  EXPECT_EQ(r.io.variables_sent[0], std::make_tuple(10, 200, 5.0));
  ASSERT_EQ(r.io.offsets_sent.size(), 1u);
  EXPECT_EQ(r.io.offsets_sent[0], std::make_pair(11, 10));
}

// ---- PRINT ----

TEST(BasicPrint, ItemsSeparatorsAndTheEndOfLine) {
  running r(
      "PRINT #10,\"A\";\"B\"\n"
      "PRINT #10,\"C\";\n"
      "PRINT #10,\"D\",\"E\"\n"
      "PRINT #10,\"F\",\n"
      "PRINT #10\n"
      "PRINT #9+2,CHR(12);CHR(65);CURSOR(28);\"X\";\n"
      "PRINT \"to the terminal\"\n"
      "PRINT #0,1/3;\n");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.printed(10), "AB\r\nCD\tE\r\nF\t\r\n");
  EXPECT_EQ(r.printed(11), "\x0c" "A\x1bH\x1cX");
  EXPECT_EQ(r.printed(0), "to the terminal\r\n0.3333");
}

TEST(BasicPrint, NumbersAndTheirFormats) {
  running r(
      "a=125: v=0.1+0.1+0.1-0.1\n"
      "PRINT #10,a;\" \";v;\" \";-0.5\n"
      "PRINT #10,a[6,0];v[8,1]\n"
      "PRINT #10,v[6.1];\"|\";v[2]\n"
      "PRINT #10,VR(0)[6.1]\n");
  EXPECT_EQ(r.go(), task_state::ended);
  EXPECT_EQ(r.printed(10),
            "125.0000 0.2000 -0.5000\r\n"
            "   125     0.2\r\n"
            "   0.2|0.20\r\n"
            "   0.0\r\n");
}

// ---- idle loops ----

TEST(BasicIdle, APollingLoopThatChangesNothingIsIdle) {
  running r("loop: IF KEY#3 THEN GOSUB got\nGOTO loop\ngot: GET #3,k: n=n+1: RETURN");
  EXPECT_EQ(r.go(100), task_state::running);
  EXPECT_TRUE(r.task->idle());
  r.io.received = {5};
  r.task->world_changed();  // a character arrived
  EXPECT_FALSE(r.task->idle());
  EXPECT_EQ(r.go(100), task_state::running);
  EXPECT_EQ(r.var("n"), 1);
  EXPECT_TRUE(r.task->idle());  // polling again
}

TEST(BasicIdle, ALoopThatChangesSomethingIsNotIdle) {
  running r("loop: i=i+1: GOTO loop");
  EXPECT_EQ(r.go(1000), task_state::running);
  EXPECT_FALSE(r.task->idle());
  running same("loop: i=5: GOTO loop");  // stores the same value again: no change
  EXPECT_EQ(same.go(1000), task_state::running);
  EXPECT_TRUE(same.task->idle());
}

TEST(BasicIdle, TheSameSubroutineFromAnotherPlaceIsNotTheSameState) {
  // Both calls of `s` look alike (same statement, same depth) but return to different places; after the
  // second one the program changes `x`, so it must not be taken for idle before that.
  running r("a: GOSUB s\nb: GOSUB s\nx=1\nhold: GOTO hold\ns: RETURN");
  EXPECT_EQ(r.go(3), task_state::running);  // GOSUB s, RETURN, GOSUB s: at s again, returning elsewhere
  EXPECT_FALSE(r.task->idle());
  EXPECT_EQ(r.go(100), task_state::running);
  EXPECT_EQ(r.var("x"), 1);
  EXPECT_TRUE(r.task->idle());
}

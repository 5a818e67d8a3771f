// The words of Trio BASIC (src/basic/reserved_words.hpp): every one, walked through every place a user
// variable or label could stand, is compiled as modelled or refused naming it; none is ever taken as a user
// variable. And the manual's examples of the modelled words print what the manual prints.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "basic/program.hpp"
#include "basic/reserved_words.hpp"
#include "basic/task.hpp"
#include "support/fake_controller.hpp"

namespace basic = trionet::basic;

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return s;
}

// The places a word could be taken for a user variable or a label.
std::vector<std::string> places(const std::string& w) {
  return {"x=" + w + "\n",
          w + "=1\n",
          "x=" + w + "+1\n",
          "x=1+" + w + "\n",
          "PRINT " + w + "\n",
          "IF " + w + " THEN x=1\n",
          "FOR " + w + "=1 TO 2: NEXT " + w + "\n",
          "GET #3," + w + "\n",
          w + ": x=1\n",
          "GOTO " + w + "\n" + w + ":\n",
          "GOSUB " + w + "\nSTOP\n" + w + ": RETURN\n",
          "x=" + lower(w) + "\n",
          lower(w) + "=1\n"};
}

std::string printed(const std::string& program) {
  trionet::test::fake_controller io;
  basic::compile_result r = basic::compile("manual.bas", program);
  EXPECT_TRUE(r) << program << r.located_message();
  if (!r) return "";
  basic::task task(r.compiled, io);
  task.run(100000);
  EXPECT_EQ(task.state(), basic::task_state::ended) << program << task.error();
  return io.printed[0];
}

}  // namespace

TEST(BasicWords, TheTableIsSortedAndHasNoDuplicates) {
  const basic::reserved_word* first = basic::reserved_words_begin();
  const basic::reserved_word* last = basic::reserved_words_end();
  ASSERT_GT(last - first, 250);
  for (const basic::reserved_word* w = first + 1; w != last; ++w) {
    EXPECT_LT(std::strcmp(w[-1].name, w->name), 0) << w[-1].name << " " << w->name;
  }
  for (const basic::reserved_word* w = first; w != last; ++w) {
    EXPECT_EQ(basic::find_reserved_word(w->name), w) << w->name;
  }
  EXPECT_EQ(basic::find_reserved_word("SPEEDY"), nullptr);
  EXPECT_EQ(basic::find_reserved_word("speed"), nullptr);  // the table is upper case; the compiler folds case
}

// The figure: 0 reserved words read as user variables.
TEST(BasicWords, NoReservedWordIsEverAUserVariableOrLabel) {
  std::size_t modelled = 0;
  std::size_t refused = 0;
  std::size_t taken_as_variable = 0;
  for (const basic::reserved_word* w = basic::reserved_words_begin(); w != basic::reserved_words_end(); ++w) {
    (w->modelled ? modelled : refused) += 1;
    const std::string word = w->name;
    for (const std::string& program : places(word)) {
      const basic::compile_result r = basic::compile("walk.bas", program);
      if (r) {
        // It compiled: as the modelled word, never as a variable of that name.
        EXPECT_TRUE(w->modelled) << "refused word compiled: " << program;
        const auto& names = r.compiled.variable_names;
        if (std::find(names.begin(), names.end(), lower(word)) != names.end()) {
          ++taken_as_variable;
          ADD_FAILURE() << word << " taken as a user variable in: " << program;
        }
        continue;
      }
      if (word == "REM") continue;  // REM starts a comment: what follows is never read
      if (!w->modelled) {
        // Refused, with the message that names it, wherever it stands.
        EXPECT_NE(r.message.find(basic::refusal_message(*w)), std::string::npos) << program << r.message;
        EXPECT_EQ(r.status, basic::compile_status::not_modelled) << program << r.message;
      } else {
        // A modelled word where it cannot stand: the error names it, or (an operator without its operand) what
        // was found instead of the operand.
        const bool named = r.message.find(word) != std::string::npos;
        const bool operator_word = word == "AND" || word == "OR" || word == "XOR" || word == "NOT" || word == "MOD";
        EXPECT_TRUE(named || (operator_word && r.message.find("expected") != std::string::npos))
            << program << r.located_message();
      }
    }
  }
  EXPECT_EQ(taken_as_variable, 0u);
  EXPECT_GT(modelled, 90u);
  EXPECT_GT(refused, 150u);
  std::printf("[          ] %zu reserved words: %zu modelled, %zu refused; %zu taken as a user variable\n",
              modelled + refused, modelled, refused, taken_as_variable);
  // docs/basic.md gives the counts (regression: it said 107 and 191 after OFFPOS became modelled).
  std::ifstream page(std::string(TRIONET_SOURCE_DIR) + "/docs/basic.md");
  const std::string text((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  std::string flat;
  for (char c : text) flat += c == '\n' ? ' ' : c;
  EXPECT_NE(flat.find(std::to_string(modelled + refused) + " of them"), std::string::npos);
  EXPECT_NE(flat.find(std::to_string(modelled) + " are modelled, " + std::to_string(refused) + " refused"),
            std::string::npos);
}

TEST(BasicWords, EveryWordTheCompilerKnowsIsInTheTableAsModelled) {
  const char* known[] = {"ABS",    "ACCEL", "ACOS",   "AND",     "ASIN",     "ATAN",    "ATAN2",   "AXIS",
                         "BASE",   "BASICERROR", "CANCEL", "CHR", "CONSTANT", "CONTROL", "COS",     "CREEP",
                         "CURSOR", "DATUM", "DECEL",  "DEFPOS",  "DPOS",     "ELSE",    "ELSEIF",  "ENDIF",
                         "ENDMOVE", "ERROR_LINE", "EXP", "FALSE", "FE",      "FOR",     "FORWARD", "FRAC",
                         "GET",    "GLOBAL", "GOSUB", "GOTO",    "HALT",     "HEX",     "IDLE",    "IF",
                         "IN",     "INT",   "KEY",    "LN",      "LOADED",   "MOD",     "MOTION_ERROR",
                         "MOVE",   "MOVEABS", "MPOS", "MTYPE",   "NETSTAT",  "NEXT",    "NOT",     "NTYPE",
                         "OFF",    "OFFPOS", "ON",    "OP",     "OR",      "PI",       "PRINT",   "RAPIDSTOP", "READ_OP",
                         "REMAIN", "REPEAT", "RETURN", "REVERSE", "SEND",    "SERVO",   "SERVO_PERIOD",
                         "SGN",    "SIN",   "SPEED",  "SQR",     "STEP",     "STOP",    "SYSTEM_ERROR",
                         "TABLE",  "TAN",   "THEN",   "TICKS",   "TO",       "TRUE",    "UNITS",   "UNTIL",
                         "VR",     "WA",    "WAIT",   "WDOG",    "WEND",     "WHILE",   "XOR"};
  for (const char* word : known) {
    const basic::reserved_word* w = basic::find_reserved_word(word);
    ASSERT_NE(w, nullptr) << word;
    EXPECT_TRUE(w->modelled) << word;
  }
}

TEST(BasicWords, ARefusalNamesTheWordItsKindAndThePlace) {
  const basic::compile_result r = basic::compile("m.bas", "WDOG=ON\nx=ENCODER AXIS(1)\n");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.located_message(),
            "m.bas:2:3: `ENCODER` is a Trio BASIC axis parameter that the simulator does not model");
  const basic::compile_result dollar = basic::compile("m.bas", "PRINT TIME$\n");
  EXPECT_EQ(dollar.located_message(), "m.bas:1:7: `TIME$` is a Trio BASIC system parameter that the simulator does "
                                      "not model");
  const basic::compile_result text = basic::compile("m.bas", "a$=1\n");
  EXPECT_EQ(text.located_message(), "m.bas:1:1: 'a$': Trio BASIC has no string variables (strings are only items of "
                                    "PRINT)");
}

// The reference's examples of the modelled words, with what the manual prints: numbers with 4 decimal places.
TEST(BasicWords, TheManualsExamplesPrintWhatTheManualPrints) {
  EXPECT_EQ(printed("PRINT INT(1.79)\n"), "1.0000\r\n");  // INT
  EXPECT_EQ(printed("maybe=1<=0\nPRINT maybe\n"), "0.0000\r\n");  // <=: 1 is not <= 0, so FALSE
  EXPECT_EQ(printed("PRINT 1<2\n"), "-1.0000\r\n");  // TRUE is -1
  EXPECT_EQ(printed("PRINT TRUE;\" \";FALSE;\" \";ON;\" \";OFF\n"), "-1.0000 0.0000 1.0000 0.0000\r\n");
  EXPECT_EQ(printed("PRINT DPOS AXIS(1)\n"), "0.0000\r\n");  // an axis at rest after power-up
}

TEST(BasicWords, MathematicalFunctionsFollowTheirDefinitions) {
  EXPECT_EQ(printed("PRINT SGN(-1.2);\" \";SGN(0);\" \";SGN(3)\n"), "-1.0000 0.0000 1.0000\r\n");
  EXPECT_EQ(printed("PRINT FRAC(1.25);\" \";FRAC(-1.25)\n"), "0.2500 -0.2500\r\n");
  EXPECT_EQ(printed("PRINT 2^10;\" \";2^0.5;\" \";-2^2;\" \";2^3^2\n"), "1024.0000 1.4142 -4.0000 64.0000\r\n");
  EXPECT_EQ(printed("PRINT SQR(16);\" \";EXP(0);\" \";LN(1)\n"), "4.0000 1.0000 0.0000\r\n");
  EXPECT_EQ(printed("PRINT SIN(PI/2);\" \";COS(PI);\" \";TAN(0)\n"), "1.0000 -1.0000 0.0000\r\n");
  EXPECT_EQ(printed("PRINT ASIN(1)*2=PI;\" \";ACOS(1);\" \";ATAN(1)*4;\" \";ATAN2(0,-1)\n"),
            "-1.0000 0.0000 3.1416 3.1416\r\n");
  EXPECT_EQ(printed("PRINT HEX(255);\" \";HEX($1F);\" \";HEX(0)\n"), "FF 1F 0\r\n");
  EXPECT_EQ(printed("PRINT 1e3;\" \";2.5E-1;\" \";.5;\" \";$FF\n"), "1000.0000 0.2500 0.5000 255.0000\r\n");
}

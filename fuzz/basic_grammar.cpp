// Fuzz harness: BASIC programs built from the grammar, so that the fuzzer spends its time in the interpreter
// and the motion model rather than in the lexer's refusals.
//
// The input is read as choices (trionet_fuzz::input_reader): each byte picks the next production. The program
// is made of at most 40 lines of statements: assignments to variables, VR(), TABLE() and axis parameters
// (writable and read-only), block IF/ELSEIF/ELSE/ENDIF, one-line IF, FOR/NEXT, REPEAT/UNTIL, WHILE/WEND,
// GOSUB and ON ... GOSUB/GOTO to labels that exist, ON BASICERROR, PRINT with [w,d] and HEX, motion commands
// with AXIS(n), WAIT IDLE/LOADED/UNTIL, WA, OP, TICKS, CONSTANT and GLOBAL, and now and then any reserved word
// (modelled or not) or a stray token. Expressions nest up to 70 deep (past the compiler's limit of 64) and use
// every number syntax ($1F, .5, 1e3). The text then goes through the same checks as basic_program.cpp
// (basic_checks.hpp): compile, well-formedness, 300 bounded turns. Time and memory per input are bounded by
// the 40 lines, 12 statements a line and the 300 turns. TRIONET_FUZZ_PRINT=1 in the environment prints each
// program on standard error.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "basic/reserved_words.hpp"
#include "basic_checks.hpp"

namespace {

using trionet_fuzz::input_reader;

constexpr const char* variables[] = {"a", "b", "speed1", "i", "k", "n"};
constexpr const char* labels[] = {"first", "second", "third"};
constexpr const char* axis_parameters[] = {"SPEED", "ACCEL", "DECEL", "UNITS", "CREEP", "MPOS", "DPOS", "IDLE",
                                           "MTYPE", "NTYPE", "REMAIN", "REP_DIST", "REP_OPTION", "FS_LIMIT",
                                           "RS_LIMIT", "SERVO", "VP_SPEED", "ENDMOVE"};
constexpr const char* writable_parameters[] = {"SPEED", "ACCEL", "DECEL", "UNITS", "CREEP", "REP_DIST",
                                               "REP_OPTION", "FS_LIMIT", "RS_LIMIT", "SERVO"};
constexpr const char* functions[] = {"ABS", "INT", "FRAC", "SGN", "SQR", "SIN", "COS", "TAN",
                                     "ASIN", "ACOS", "ATAN", "EXP", "LN", "READ_OP", "VR", "TABLE", "IN"};
constexpr const char* operators[] = {"+", "-", "*", "/", "^", " MOD ", " AND ", " OR ", " XOR ", "=", "<>",
                                     "<", ">", "<=", ">=", "&"};

template <std::size_t n>
const char* pick(input_reader& in, const char* const (&words)[n]) {
  return words[in.byte() % n];
}

class generator {
 public:
  explicit generator(input_reader& in) : in_(in) {}

  std::string program() {
    std::string text;
    const int lines = 1 + in_.byte() % 40;
    bool defined[3] = {};
    for (int line = 0; line < lines && !in_.done(); ++line) {
      const std::size_t label = in_.byte() % 16;
      if (label < 3 && !defined[label]) {
        text += std::string(labels[label]) + ":";
        defined[label] = true;
      }
      const int count = 1 + in_.byte() % 3;
      end_line_ = false;
      for (int i = 0; i < count && !end_line_; ++i) {
        if (i > 0) text += ": ";
        text += statement(0);
      }
      text += line % 5 == 4 ? "\r\n" : "\n";
    }
    while (depth_ > 0) {  // close what is open, most of the time
      --depth_;
      if (in_.byte() % 16 != 0) text += blocks_[depth_].closer + "\n";
    }
    text += "STOP\n";
    for (std::size_t i = 0; i < 3; ++i) {
      if (!defined[i] || in_.byte() % 32 == 0) text += std::string(labels[i]) + ": RETURN\n";
    }
    return text;
  }

 private:
  struct block {
    std::string closer;
    bool is_if = false;
    bool has_else = false;
  };

  std::string number() {
    switch (in_.byte() % 7) {
      case 0:
        return std::to_string(in_.byte());
      case 1:
        return "." + std::to_string(in_.byte() % 10);
      case 2:
        return "$" + std::string(1, "0123456789ABCDEF"[in_.byte() % 16]) + "F";
      case 3:
        return std::to_string(in_.byte() % 10) + "e" + std::to_string(in_.byte() % 5);
      case 4:
        return std::to_string(in_.u16()) + "." + std::to_string(in_.byte());
      case 5:
        return "1E-" + std::to_string(in_.byte() % 9);
      default:
        return std::to_string(in_.byte() % 8);
    }
  }

  std::string axis_modifier() { return in_.byte() % 3 == 0 ? " AXIS(" + std::to_string(in_.byte() % 5) + ")" : ""; }

  std::string value(int depth) {
    const std::uint8_t choice = in_.byte() % 32;
    if (choice < 8) return number();
    if (choice < 13) return pick(in_, variables);
    if (choice < 16) return std::string(pick(in_, axis_parameters)) + axis_modifier();
    if (choice < 19) {
      const char* f = pick(in_, functions);
      if (std::string(f) == "IN" && in_.byte() % 2 == 0) return "IN";
      return std::string(f) + "(" + expression(depth + 1) + ")";
    }
    switch (choice) {
      case 19:
        return "ATAN2(" + expression(depth + 1) + "," + expression(depth + 1) + ")";
      case 20:
      case 21:
        return "(" + expression(depth + 1) + ")";
      case 22:
        return in_.byte() % 2 ? "TICKS" : "KEY#" + std::to_string(3 + in_.byte() % 2);
      case 23:
      case 24:
        return constants_[in_.byte() % (sizeof constants_ / sizeof constants_[0])];
      case 25:
        return "-" + value(depth + 1);
      case 26:
        return "(NOT " + value(depth + 1) + ")";
      case 27:
        return in_.byte() % 16 == 0 ? any_word() : number();  // now and then a word that is no value
      default:
        return pick(in_, variables);
    }
  }

  std::string expression(int depth) {
    if (depth > 70 || in_.done()) return number();
    std::string text = value(depth);
    const int more = in_.byte() % 4 == 0 ? 1 + in_.byte() % 2 : 0;
    for (int i = 0; i < more; ++i) text += std::string(pick(in_, operators)) + value(depth + 1);
    return text;
  }

  std::string any_word() {
    const std::size_t count = trionet::basic::reserved_word_count();
    return trionet::basic::reserved_words_begin()[in_.u16() % count].name;
  }

  std::string format() {
    switch (in_.byte() % 4) {
      case 0:
        return "[" + std::to_string(in_.byte() % 12) + "," + std::to_string(in_.byte() % 6) + "]";
      case 1:
        return "[" + std::to_string(in_.byte() % 9) + "." + std::to_string(in_.byte() % 4) + "]";
      case 2:
        return "[" + std::to_string(in_.byte() % 6) + "]";
      default:
        return "";
    }
  }

  // A statement that opens a block: at the top of a line's statements only; a block IF ends its line.
  std::string open(int depth, const std::string& text, const std::string& closer, bool is_if = false) {
    if (depth > 0 || depth_ >= 70) return std::string(pick(in_, variables)) + "=1";
    blocks_[depth_++] = {closer, is_if, false};
    if (is_if) end_line_ = true;
    return text;
  }

  std::string close(int depth) {
    if (depth > 0) return "n=n+1";
    if (depth_ == 0) return in_.byte() % 16 == 0 ? "ENDIF" : "k=0";  // now and then unmatched on purpose
    return blocks_[--depth_].closer;
  }

  std::string else_part(int depth) {
    if (depth > 0 || depth_ == 0 || !blocks_[depth_ - 1].is_if || blocks_[depth_ - 1].has_else) return "b=2";
    end_line_ = true;
    if (in_.byte() % 2 == 0) return "ELSEIF " + expression(0) + " THEN";
    blocks_[depth_ - 1].has_else = true;
    return "ELSE";
  }

  std::string statement(int depth) {
    const auto e = [&] { return expression(depth); };
    switch (in_.byte() % 32) {
      case 0:
      case 1:
        return std::string(pick(in_, variables)) + "=" + e();
      case 2:
        return "VR(" + std::to_string(in_.byte() % 70) + ")=" + e();
      case 3:
        return in_.byte() % 2 ? "TABLE(" + e() + ")=" + e() : "TABLE(" + e() + "," + e() + "," + e() + ")";
      case 4:
        if (in_.byte() % 32 == 0) return "MPOS=" + e();  // read-only: refused
        return std::string(pick(in_, writable_parameters)) + axis_modifier() + "=" + e();
      case 5:
        return open(depth, "IF " + e() + " THEN", "ENDIF", true);
      case 6:
        return else_part(depth);
      case 7: {  // a one-line IF takes the rest of its line
        std::string text = "IF " + e() + " THEN " + statement(depth + 1);
        if (in_.byte() % 2) text += " ELSE " + statement(depth + 1);
        end_line_ = true;
        return text;
      }
      case 8:
        return open(depth, "FOR i=" + e() + " TO " + e() + (in_.byte() % 2 ? " STEP " + e() : ""), "NEXT i");
      case 9:
        return open(depth, "REPEAT", "UNTIL " + e());
      case 10:
        return open(depth, "WHILE " + e(), "WEND");
      case 11:
        return close(depth);
      case 12:
        return std::string(in_.byte() % 2 ? "GOSUB " : "GOTO ") + pick(in_, labels);
      case 13:
        return "ON " + e() + (in_.byte() % 2 ? " GOSUB " : " GOTO ") + pick(in_, labels) + "," + pick(in_, labels);
      case 14:
        return std::string("ON BASICERROR GOTO ") + pick(in_, labels);
      case 15:
        return "PRINT " + std::string(in_.byte() % 2 ? "#" + std::to_string(in_.byte() % 26) + "," : "") + "\"t\";" +
               e() + format() + (in_.byte() % 2 ? ";" : ",") + "HEX(" + e() + ")" + (in_.byte() % 2 ? ";" : "");
      case 16:
        return "MOVE(" + e() + (in_.byte() % 2 ? "," + e() : "") + ")" + axis_modifier();
      case 17:
        return "MOVEABS(" + e() + ")" + axis_modifier();
      case 18:
        return std::string(in_.byte() % 2 ? "FORWARD" : "REVERSE") + axis_modifier();
      case 19:
        return std::string(in_.byte() % 2 ? "CANCEL" : "CANCEL(1)") + axis_modifier();
      case 20:
        return in_.byte() % 2 ? "RAPIDSTOP" : "DATUM(" + std::to_string(in_.byte() % 8) + ")" + axis_modifier();
      case 21:
        return "DEFPOS(" + e() + ")" + axis_modifier();
      case 22:
        return std::string(in_.byte() % 2 ? "WAIT IDLE" : "WAIT LOADED") + axis_modifier();
      case 23:
        return "WAIT UNTIL " + e();
      case 24:
        return "WA(" + std::to_string(in_.byte() % 20) + ")";
      case 25:
        return in_.byte() % 2 ? "OP(" + e() + "," + e() + ")" : "OP(" + e() + ")";
      case 26:
        return in_.byte() % 2 ? "TICKS=" + e() : "WDOG=" + e();
      case 27:
        return "BASE(" + std::to_string(in_.byte() % 5) + (in_.byte() % 2 ? "," + std::to_string(in_.byte() % 5) : "") + ")";
      case 28:
        return std::string(in_.byte() % 2 ? "CONSTANT \"c" : "GLOBAL \"g") +
               std::to_string(in_.byte() % 16 == 0 ? 0 : ++declared_) + "\"," + std::to_string(in_.byte() % 70);
      case 29:
        if (in_.byte() % 8 != 0) return std::string(pick(in_, variables)) + "=" + e();
        return any_word() + (in_.byte() % 2 ? "=" + e() : "");
      case 30:
        return "SEND(" + std::to_string(9 + in_.byte() % 17) + "," + std::to_string(in_.byte() % 3) + "," + e() +
               (in_.byte() % 2 ? "," + e() : "") + ")";
      default:
        return in_.byte() % 4 == 0 ? "STOP" : "GET #" + std::to_string(3 + in_.byte() % 2) + "," + pick(in_, variables);
    }
  }

  static constexpr const char* constants_[] = {"TRUE", "FALSE", "ON", "OFF", "PI", "SERVO_PERIOD", "CONTROL",
                                               "NETSTAT", "ERROR_LINE"};
  input_reader& in_;
  block blocks_[72];
  int depth_ = 0;
  int declared_ = 0;
  bool end_line_ = false;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  input_reader in(data, size);
  const std::string text = generator(in).program();
  if (std::getenv("TRIONET_FUZZ_PRINT") != nullptr) {  // to read a finding
    const trionet::basic::compile_result r = trionet::basic::compile("fuzz.bas", text);
    std::fprintf(stderr, "%s---- %s\n", text.c_str(), r ? "compiles" : r.located_message().c_str());
  }
  trionet_fuzz::compile_and_run(text, trionet_fuzz::hash(data, size));
  return 0;
}

// Trio BASIC text -> program (program.hpp): a lexer, then one recursive-descent pass that emits statements
// and reverse-Polish expressions, resolving block ends as they close and labels at the end. Every name is
// looked up in the reserved-word table (reserved_words.hpp) first: a word Trio BASIC reserves is either
// compiled as modelled or refused with a message that names it, never taken as a user variable.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "basic/program.hpp"
#include "basic/reserved_words.hpp"
#include "trionet/host/text.hpp"

namespace trionet::basic {
namespace {

// ---- lexer ----

enum class token_kind : std::uint8_t { number, string, name, symbol, end_of_line, end_of_file };

struct token {
  token_kind kind = token_kind::end_of_file;
  std::string text;  // name: upper case; string: its characters; symbol: itself; number: as written
  std::string raw;   // name: as written
  double value = 0;
  source_position at;
};

bool is_letter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
int hex_value(char c) {
  return host::hex_digit(c);
}
char upper(char c) {
  return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}
char lower(char c) {
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}
std::string to_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = lower(c);
  return out;
}

// Untrusted text echoed in a message: at most `limit` characters, control characters escaped.
std::string shown(std::string_view text, std::size_t limit = 40) {
  return host::printable(text, limit);
}

std::string shown_character(char c) {
  const auto byte = static_cast<unsigned char>(c);
  if (byte >= 32 && byte < 127) return std::string("'") + c + "'";
  char text[16];
  std::snprintf(text, sizeof text, "byte 0x%02x", byte);
  return text;
}

struct lex_error {
  source_position at;
  std::string message;
};

class lexer {
 public:
  explicit lexer(std::string_view text) : s_(text) {}

  bool run(std::vector<token>& out, lex_error& error) {
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == '\n' || c == '\r') {
        emit(out, token_kind::end_of_line, "", i_);
        i_ += (c == '\r' && i_ + 1 < s_.size() && s_[i_ + 1] == '\n') ? 2u : 1u;
        ++line_;
        line_start_ = i_;
      } else if (c == ' ' || c == '\t') {
        ++i_;
      } else if (c == '\'') {
        skip_to_end_of_line();
      } else if (is_letter(c)) {
        name(out);
      } else if (is_digit(c) || (c == '.' && i_ + 1 < s_.size() && is_digit(s_[i_ + 1]))) {
        if (!number(out, error)) return false;
      } else if (c == '$') {
        if (!hex_number(out, error)) return false;
      } else if (c == '"') {
        if (!string(out, error)) return false;
      } else if (!symbol(out)) {
        error = {here(i_), "unexpected character " + shown_character(c) + unexpected_hint(c)};
        return false;
      }
    }
    if (out.empty() || out.back().kind != token_kind::end_of_line) emit(out, token_kind::end_of_line, "", i_);
    emit(out, token_kind::end_of_file, "", i_);
    return true;
  }

 private:
  static std::string unexpected_hint(char c) {
    switch (c) {
      case '|':
        return " (Trio BASIC writes OR)";
      case '!':
        return " (Trio BASIC writes NOT, and <> for not equal)";
      case '%':
        return " (Trio BASIC writes MOD)";
      case '{':
      case '}':
        return " (Trio BASIC has no braces)";
      default:
        return "";
    }
  }
  source_position here(std::size_t at) const {
    return {line_, static_cast<std::uint32_t>(at - line_start_ + 1)};
  }
  void emit(std::vector<token>& out, token_kind kind, std::string text, std::size_t at, double value = 0) {
    token t;
    t.kind = kind;
    t.text = std::move(text);
    t.value = value;
    t.at = here(at);
    out.push_back(std::move(t));
  }
  void skip_to_end_of_line() {
    while (i_ < s_.size() && s_[i_] != '\n' && s_[i_] != '\r') ++i_;
  }

  void name(std::vector<token>& out) {
    const std::size_t start = i_;
    while (i_ < s_.size() && (is_letter(s_[i_]) || is_digit(s_[i_]) || s_[i_] == '_')) ++i_;
    if (i_ < s_.size() && s_[i_] == '$') ++i_;  // DATE$ ... or a string variable, which the compiler refuses
    std::string text(s_.substr(start, i_ - start));
    std::string raw = text;
    for (char& c : text) c = upper(c);
    if (text == "REM") {  // a comment to the end of the line
      skip_to_end_of_line();
      return;
    }
    emit(out, token_kind::name, std::move(text), start);
    out.back().raw = std::move(raw);
  }

  // Digits, an optional fraction, an optional exponent (1e3, 2.5E-2).
  bool number(std::vector<token>& out, lex_error& error) {
    const std::size_t start = i_;
    while (i_ < s_.size() && is_digit(s_[i_])) ++i_;
    if (i_ < s_.size() && s_[i_] == '.') {
      ++i_;
      while (i_ < s_.size() && is_digit(s_[i_])) ++i_;
    }
    if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
      std::size_t j = i_ + 1;
      if (j < s_.size() && (s_[j] == '+' || s_[j] == '-')) ++j;
      if (j < s_.size() && is_digit(s_[j])) {
        i_ = j;
        while (i_ < s_.size() && is_digit(s_[i_])) ++i_;
      }
    }
    const std::string_view text = s_.substr(start, i_ - start);
    double value = 0;
    const auto parsed = std::from_chars(text.data(), text.data() + text.size(), value, std::chars_format::general);
    if (parsed.ec != std::errc() || parsed.ptr != text.data() + text.size() || !std::isfinite(value)) {
      error = {here(start), "the number " + shown(text) + " is out of range"};
      return false;
    }
    emit(out, token_kind::number, std::string(text), start, value);
    return true;
  }

  bool hex_number(std::vector<token>& out, lex_error& error) {
    const std::size_t start = i_++;
    double value = 0;
    int digits = 0;
    while (i_ < s_.size() && hex_value(s_[i_]) >= 0) {
      value = value * 16 + static_cast<double>(hex_value(s_[i_++]));
      ++digits;
    }
    if (digits == 0) {
      error = {here(start), "expected hex digits after '$' (a hex number is written $1F)"};
      return false;
    }
    if (digits > 13) {  // 13 hex digits are exact in a double
      error = {here(start), "the hex number " + shown(s_.substr(start, i_ - start)) + " is out of range"};
      return false;
    }
    emit(out, token_kind::number, std::string(s_.substr(start, i_ - start)), start, value);
    return true;
  }

  bool string(std::vector<token>& out, lex_error& error) {
    const std::size_t start = i_++;
    std::string text;
    while (i_ < s_.size() && s_[i_] != '"' && s_[i_] != '\n' && s_[i_] != '\r') {
      if (static_cast<unsigned char>(s_[i_]) > 127) {
        error = {here(i_), shown_character(s_[i_]) + " in a string: a string holds characters 0..127, what the ring carries"};
        return false;
      }
      text += s_[i_++];
    }
    if (i_ == s_.size() || s_[i_] != '"') {
      error = {here(i_), "expected '\"' to close the string that starts at column " +
                             std::to_string(here(start).column)};
      return false;
    }
    ++i_;
    emit(out, token_kind::string, std::move(text), start);
    return true;
  }

  bool symbol(std::vector<token>& out) {
    static constexpr const char* two[] = {"<>", "<=", ">="};
    for (const char* s : two) {
      if (s_.compare(i_, 2, s) == 0) {
        emit(out, token_kind::symbol, s, i_);
        i_ += 2;
        return true;
      }
    }
    static constexpr std::string_view one = "(),;:#[]=<>+-*/&^?";
    if (one.find(s_[i_]) == std::string_view::npos) return false;
    emit(out, token_kind::symbol, std::string(1, s_[i_]), i_);
    ++i_;
    return true;
  }

  std::string_view s_;
  std::size_t i_ = 0;
  std::size_t line_start_ = 0;
  std::uint32_t line_ = 1;
};

// ---- words ----

std::string found(const token& t) {
  switch (t.kind) {
    case token_kind::end_of_line:
      return "the end of the line";
    case token_kind::end_of_file:
      return "the end of the file";
    case token_kind::name: {
      const reserved_word* w = find_reserved_word(t.text);
      if (w != nullptr) return std::string("the ") + to_string(w->kind) + " " + w->name;
      return "'" + shown(t.raw) + "'";
    }
    case token_kind::number:
      return "the number " + shown(t.text);
    case token_kind::string:
      return "the string \"" + shown(t.text) + "\"";
    case token_kind::symbol:
      return "'" + t.text + "'";
  }
  return "?";
}

// The one-argument functions and what they compile to.
struct function_word {
  const char* name;
  expr_op op;
};
constexpr function_word functions[] = {
    {"ABS", expr_op::absolute},     {"INT", expr_op::integer_part}, {"FRAC", expr_op::fraction},
    {"SGN", expr_op::sign},         {"SQR", expr_op::square_root},  {"SIN", expr_op::sine},
    {"COS", expr_op::cosine},       {"TAN", expr_op::tangent},      {"ASIN", expr_op::arc_sine},
    {"ACOS", expr_op::arc_cosine},  {"ATAN", expr_op::arc_tangent}, {"EXP", expr_op::exponential},
    {"LN", expr_op::logarithm},     {"READ_OP", expr_op::read_op},
};

struct system_word {
  const char* name;
  system_value value;
};
constexpr system_word system_words[] = {
    {"NETSTAT", system_value::netstat},           {"WDOG", system_value::wdog},
    {"SERVO_PERIOD", system_value::servo_period}, {"CONTROL", system_value::control},
    {"MOTION_ERROR", system_value::motion_error}, {"SYSTEM_ERROR", system_value::system_error},
    {"ERROR_LINE", system_value::error_line},
};

struct motion_word {
  const char* name;
  motion_command command;
};
constexpr motion_word motion_words[] = {
    {"MOVE", motion_command::move},       {"MOVEABS", motion_command::moveabs},
    {"FORWARD", motion_command::forward}, {"REVERSE", motion_command::reverse},
    {"CANCEL", motion_command::cancel},   {"RAPIDSTOP", motion_command::rapidstop},
    {"DATUM", motion_command::datum},     {"DEFPOS", motion_command::defpos},
    {"DP", motion_command::defpos},  // the manual's alternate format of DEFPOS
};

// ---- parser and code generator ----

struct block {
  enum class kind : std::uint8_t { if_block, else_block, repeat, while_loop, for_loop } what;
  source_position at;
  std::uint32_t statement;  // if: its open branch; else: unused; repeat: the body's first; while, for: theirs
  std::uint32_t slot;       // for: the loop variable
  std::vector<std::uint32_t> ends;  // if: the jumps to ENDIF over each ELSEIF and ELSE part
};

const char* opening_word(block::kind k) {
  switch (k) {
    case block::kind::if_block:
    case block::kind::else_block:
      return "IF";
    case block::kind::repeat:
      return "REPEAT";
    case block::kind::while_loop:
      return "WHILE";
    case block::kind::for_loop:
      return "FOR";
  }
  return "?";
}
const char* closing_word(block::kind k) {
  switch (k) {
    case block::kind::if_block:
    case block::kind::else_block:
      return "ENDIF";
    case block::kind::repeat:
      return "UNTIL";
    case block::kind::while_loop:
      return "WEND";
    case block::kind::for_loop:
      return "NEXT";
  }
  return "?";
}

struct label_use {
  std::string name;
  std::uint32_t statement;
  std::uint32_t jump_index;  // index into jump_targets, or no_expression for the statement's own target
  source_position at;
};

struct label_definition {
  std::uint32_t statement;
  std::uint32_t line;
};

// A CONSTANT or GLOBAL name.
struct declared_name {
  bool global;  // GLOBAL: VR(number); CONSTANT: number
  double number;
  std::uint32_t line;
};

class compiler {
 public:
  compiler(const std::vector<token>& tokens, program& out) : t_(tokens), p_(out) {}

  bool run() {
    while (peek().kind != token_kind::end_of_file) {
      if (!line()) return false;
    }
    if (!blocks_.empty()) {
      const block& b = blocks_.back();
      return fail(compile_status::unmatched_block, b.at,
                  std::string(opening_word(b.what)) + " has no " + closing_word(b.what));
    }
    for (const label_use& use : label_uses_) {
      const auto found_label = labels_.find(use.name);
      if (found_label == labels_.end())
        return fail(compile_status::unknown_label, use.at, "no label '" + shown(use.name) + "' in the program");
      if (use.jump_index == no_expression) {
        p_.statements[use.statement].target = found_label->second.statement;
      } else {
        p_.jump_targets[use.jump_index] = found_label->second.statement;
      }
    }
    // FOR's hidden end and step values go after the named variables.
    const auto named = static_cast<std::uint32_t>(p_.variable_names.size());
    for (statement& s : p_.statements) {
      if (s.kind == statement_kind::for_start || s.kind == statement_kind::for_next) s.extra += named;
    }
    p_.slots = named + 2 * for_loops_;
    return true;
  }

  compile_status status = compile_status::ok;
  source_position at;
  std::string message;

 private:
  // ---- tokens ----
  const token& peek(std::size_t ahead = 0) const { return t_[std::min(pos_ + ahead, t_.size() - 1)]; }
  const token& next() {
    const token& t = t_[pos_];
    if (pos_ + 1 < t_.size()) ++pos_;
    return t;
  }
  bool is_symbol(const char* s, std::size_t ahead = 0) const {
    const token& t = peek(ahead);
    return t.kind == token_kind::symbol && t.text == s;
  }
  bool is_word(const char* w, std::size_t ahead = 0) const {
    const token& t = peek(ahead);
    return t.kind == token_kind::name && t.text == w;
  }
  bool at_end_of_line() const {
    return peek().kind == token_kind::end_of_line || peek().kind == token_kind::end_of_file;
  }
  bool at_end_of_statement() const { return at_end_of_line() || is_symbol(":") || is_word("ELSE"); }

  bool fail(compile_status s, source_position where, std::string text) {
    if (status == compile_status::ok) {
      status = s;
      at = where;
      message = std::move(text);
    }
    return false;
  }
  bool expected(const std::string& what) {
    return fail(compile_status::syntax_error, peek().at, "expected " + what + ", found " + found(peek()));
  }
  bool expect_symbol(const char* s, const std::string& what) {
    if (!is_symbol(s)) return expected(what);
    next();
    return true;
  }
  bool expect_word(const char* w, const std::string& what) {
    if (!is_word(w)) return expected(what);
    next();
    return true;
  }
  bool refuse(const reserved_word& w, source_position where) {
    return fail(compile_status::not_modelled, where, refusal_message(w));
  }
  // A reserved word where the program needs a name of its own (a variable, a label, a FOR variable): true,
  // with the error recorded, when `t` is one.
  bool reserved_here(const token& t, const char* as) {
    const reserved_word* w = find_reserved_word(t.text);
    if (w == nullptr) return false;
    if (!w->modelled) {
      refuse(*w, t.at);
    } else {
      fail(compile_status::syntax_error, t.at,
           std::string("`") + w->name + "` is a Trio BASIC " + to_string(w->kind) + " and cannot be " + as);
    }
    return true;
  }
  // A name with '$': a reserved word (DATE$ ...) or a string variable, which Trio BASIC does not have. True,
  // with the error recorded, when `t` is one.
  bool dollar_name(const token& t) {
    if (t.text.empty() || t.text.back() != '$') return false;
    if (const reserved_word* w = find_reserved_word(t.text)) {
      refuse(*w, t.at);
    } else {
      fail(compile_status::syntax_error, t.at,
           "'" + shown(t.raw) + "': Trio BASIC has no string variables (strings are only items of PRINT)");
    }
    return true;
  }

  // ---- lines and statements ----

  // Statement words that are a whole statement alone, so that `WORD:` is that statement and then ':'.
  static bool complete_alone(const std::string& word) {
    static constexpr const char* words[] = {"RETURN", "STOP",    "HALT",    "REPEAT", "ELSE",     "ENDIF", "WEND",
                                            "NEXT",   "PRINT",   "FORWARD", "REVERSE", "CANCEL", "RAPIDSTOP"};
    return std::any_of(std::begin(words), std::end(words), [&](const char* w) { return word == w; });
  }

  bool line() {
    if (peek().kind == token_kind::name && is_symbol(":", 1) && !complete_alone(peek().text)) {
      const token& label = peek();
      if (dollar_name(label) || reserved_here(label, "a label")) return false;
      next();
      const std::string name = to_lower(label.raw);
      const auto [where, added] = labels_.emplace(name, label_definition{here(), label.at.line});
      if (!added) {
        return fail(compile_status::duplicate_label, label.at,
                    "label '" + shown(name) + "' is already defined at line " + std::to_string(where->second.line));
      }
      next();  // ':'
    }
    if (!statements(false)) return false;
    if (peek().kind == token_kind::end_of_line) next();
    return true;
  }

  // Statements separated by ':' up to the end of the line (and, in a one-line IF, up to its ELSE).
  bool statements(bool one_line_if) {
    for (;;) {
      if (at_end_of_line() || (one_line_if && is_word("ELSE"))) return true;
      if (is_symbol(":")) {
        next();
        continue;
      }
      if (!one_statement(one_line_if)) return false;
      if (is_symbol(":")) {
        next();
      } else if (!at_end_of_line() && !(one_line_if && is_word("ELSE"))) {
        return expected("':' or the end of the line after the statement");
      }
    }
  }

  std::uint32_t here() const { return static_cast<std::uint32_t>(p_.statements.size()); }
  std::uint32_t emit(statement_kind kind, source_position where) {
    statement s;
    s.kind = kind;
    s.line = where.line;
    p_.statements.push_back(s);
    return here() - 1;
  }
  statement& at_index(std::uint32_t i) { return p_.statements[i]; }

  std::uint32_t slot_of(const std::string& raw_name) {
    const std::string name = to_lower(raw_name);
    const auto found_slot = slots_.find(name);
    if (found_slot != slots_.end()) return found_slot->second;
    const auto slot = static_cast<std::uint32_t>(p_.variable_names.size());
    p_.variable_names.push_back(name);
    slots_.emplace(name, slot);
    return slot;
  }

  // A user variable where one is needed (FOR, NEXT, GET): not reserved, not declared CONSTANT or GLOBAL.
  bool variable_name(const token& t, const std::string& what) {
    if (t.kind != token_kind::name) return expected(what);
    if (dollar_name(t) || reserved_here(t, "a variable")) return false;
    if (const auto d = declared_.find(to_lower(t.raw)); d != declared_.end()) {
      return fail(compile_status::syntax_error, t.at,
                  "'" + shown(t.raw) + "' is declared " + (d->second.global ? "GLOBAL" : "CONSTANT") + " at line " +
                      std::to_string(d->second.line) + " and cannot be " + what);
    }
    return true;
  }

  bool one_statement(bool one_line_if) {
    const token& first = peek();
    const source_position where = first.at;
    if (first.kind == token_kind::symbol && first.text == "?") return print_statement(where);
    if (first.kind != token_kind::name) return expected("a statement");
    const std::string word = first.text;
    const reserved_word* reserved = find_reserved_word(word);
    if (reserved != nullptr && !reserved->modelled) return refuse(*reserved, where);
    if (reserved != nullptr && is_symbol("=", 1) && !assignable(word)) {
      return fail(compile_status::syntax_error, where,
                  std::string("`") + reserved->name + "` is a Trio BASIC " + to_string(reserved->kind) +
                      " and cannot be assigned");
    }
    if (one_line_if && (word == "ELSEIF" || word == "ENDIF" || word == "REPEAT" || word == "UNTIL" ||
                        word == "WHILE" || word == "WEND" || word == "FOR" || word == "NEXT")) {
      return fail(compile_status::syntax_error, where,
                  word + " cannot be part of a one-line IF (write IF ... THEN at the end of a line, then ENDIF)");
    }
    if (word == "PRINT") return print_statement(where);
    if (word == "GET") return get_statement(where);
    if (word == "SEND") return send_statement(where);
    if (word == "IF") return if_statement(where, one_line_if);
    if (word == "ELSE") return else_statement(where);
    if (word == "ELSEIF") return elseif_statement(where);
    if (word == "ENDIF") return endif_statement(where);
    if (word == "GOTO" || word == "GOSUB") {
      next();
      const std::uint32_t s = emit(word == "GOTO" ? statement_kind::jump : statement_kind::gosub, where);
      return label_reference(s, no_expression, "a label after " + word);
    }
    if (word == "RETURN" || word == "STOP" || word == "HALT") {
      next();
      if (word == "STOP" && peek().kind == token_kind::string) {
        return fail(compile_status::syntax_error, where,
                    "STOP with a program name stops another program, which the simulator does not model (one "
                    "program runs on each controller: STOP alone ends it)");
      }
      emit(word == "RETURN" ? statement_kind::return_from_gosub : statement_kind::stop, where);
      return true;
    }
    if (word == "REPEAT") {
      next();
      return open_block({block::kind::repeat, where, here(), 0, {}});
    }
    if (word == "UNTIL") return until_statement(where);
    if (word == "WHILE") {
      next();
      std::uint32_t condition = 0;
      if (!expression(condition)) return false;
      const std::uint32_t s = emit(statement_kind::branch_unless, where);
      at_index(s).expr[0] = condition;
      return open_block({block::kind::while_loop, where, s, 0, {}});
    }
    if (word == "WEND") return wend_statement(where);
    if (word == "FOR") return for_statement(where);
    if (word == "NEXT") return next_statement(where);
    if (word == "WAIT") return wait_statement(where);
    if (word == "WA") {
      next();
      std::uint32_t ms = 0;
      if (!expect_symbol("(", "'(' after WA (WA(milliseconds))") || !expression(ms) ||
          !expect_symbol(")", "')' to close WA(")) {
        return false;
      }
      at_index(emit(statement_kind::wait_ms, where)).expr[0] = ms;
      return true;
    }
    if (word == "ON") return on_statement(where);
    if (word == "OP") return op_statement(where);
    if (word == "BASE") return base_statement(where);
    if (word == "CONSTANT" || word == "GLOBAL") return declaration(where, word == "GLOBAL");
    if (word == "TABLE" && is_symbol("(", 1)) return table_statement(where);
    for (const motion_word& m : motion_words) {
      if (word == m.name) return motion_statement(where, m.command);
    }
    if (word == "DIM" && peek(1).kind == token_kind::name) {
      return fail(compile_status::syntax_error, where,
                  "DIM is not part of Trio BASIC on the MC206/MC224 (use VR() or TABLE() for arrays)");
    }
    return assignment(where);
  }

  // Reserved words a program may assign: `WORD = value`.
  static bool assignable(const std::string& word) {
    if (word == "NETSTAT" || word == "WDOG" || word == "TICKS") return true;
    axis_parameter p{};
    return find_axis_parameter(word, p);  // a read-only one gets its own message in assignment()
  }

  // A label name after GOTO, GOSUB or in an ON list: resolved at the end.
  bool label_reference(std::uint32_t statement_index, std::uint32_t jump_index, const std::string& what) {
    const token& label = peek();
    if (label.kind != token_kind::name) return expected(what);
    if (dollar_name(label) || reserved_here(label, "a label")) return false;
    label_uses_.push_back({to_lower(label.raw), statement_index, jump_index, label.at});
    next();
    return true;
  }

  // `AXIS(n)` after a command or parameter, or nothing: the expression id, or no_expression.
  bool axis_modifier(std::uint32_t& axis) {
    axis = no_expression;
    if (!is_word("AXIS")) return true;
    next();
    return expect_symbol("(", "'(' after AXIS (AXIS(n))") && expression(axis) &&
           expect_symbol(")", "')' to close AXIS(");
  }

  bool assignment(source_position where) {
    const token& target = peek();
    const std::string word = target.text;
    statement s;
    s.line = where.line;
    std::uint32_t value_slot = 0;
    if (word == "VR" || word == "TABLE") {
      next();
      s.kind = word == "VR" ? statement_kind::assign_vr : statement_kind::assign_table;
      if (!expect_symbol("(", "'(' after " + word) || !expression(s.expr[0]) ||
          !expect_symbol(")", "')' to close " + word + "(")) {
        return false;
      }
      value_slot = 1;
    } else if (word == "NETSTAT" || word == "WDOG" || word == "TICKS") {
      next();
      s.kind = word == "NETSTAT" ? statement_kind::assign_netstat
               : word == "WDOG"  ? statement_kind::assign_wdog
                                 : statement_kind::assign_ticks;
    } else if (axis_parameter p{}; find_axis_parameter(word, p)) {
      next();
      if (info(p).read_only) {
        return fail(compile_status::syntax_error, where,
                    std::string("`") + info(p).name + "` is a read-only axis parameter: the axis sets it" +
                        (p == axis_parameter::dpos || p == axis_parameter::mpos ? " (DEFPOS sets the position)" : ""));
      }
      s.kind = statement_kind::assign_axis;
      s.slot = static_cast<std::uint32_t>(p);
      if (!axis_modifier(s.expr[1])) return false;
    } else if (const reserved_word* w = find_reserved_word(word)) {
      return fail(compile_status::syntax_error, where,
                  std::string("expected a statement, found ") + found(target) +
                      (w->kind == word_kind::constant || w->kind == word_kind::system_parameter ||
                               w->kind == word_kind::mathematical
                           ? " (it cannot be assigned)"
                           : ""));
    } else {
      if (dollar_name(target)) return false;
      next();
      if (const auto d = declared_.find(to_lower(target.raw)); d != declared_.end()) {
        if (!d->second.global) {
          return fail(compile_status::syntax_error, where,
                      "'" + shown(target.raw) + "' is a CONSTANT (line " + std::to_string(d->second.line) +
                          ") and cannot be assigned");
        }
        s.kind = statement_kind::assign_vr;
        s.expr[0] = constant_expression(d->second.number);
        value_slot = 1;
      } else {
        if (is_symbol("(")) {
          return fail(compile_status::syntax_error, where,
                      "'" + shown(target.raw) + "' is not a Trio BASIC command (docs/basic.md lists the words)");
        }
        if (is_symbol(":")) {
          return fail(compile_status::syntax_error, where,
                      "a label must start its line ('" + shown(target.raw) + ":' follows another statement)");
        }
        if (target.text == "END" && is_word("IF")) {
          return fail(compile_status::syntax_error, where, "Trio BASIC ends a block IF with ENDIF, one word");
        }
        if (!is_symbol("=")) {  // LET x=1, END, INCLUDE "f": a word of another BASIC, or a typing error
          return fail(compile_status::syntax_error, peek().at,
                      "expected '=' after '" + shown(target.raw) + "', found " + found(peek()) +
                          " (it is not a Trio BASIC command: docs/basic.md lists the words)");
        }
        s.kind = statement_kind::assign_variable;
        s.slot = slot_of(target.raw);
      }
    }
    if (!expect_symbol("=", "'=' after " + found(target))) return false;
    if (!expression(s.expr[value_slot])) return false;
    p_.statements.push_back(s);
    return true;
  }

  std::uint32_t constant_expression(double value) {
    const auto begin = static_cast<std::uint32_t>(p_.code.size());
    p_.code.push_back({expr_op::constant, 0, value});
    p_.expressions.push_back({begin, begin + 1, 0});
    return static_cast<std::uint32_t>(p_.expressions.size() - 1);
  }

  // CONSTANT "name", value / GLOBAL "name", vr: a name for a number or for VR(vr) from here on.
  bool declaration(source_position where, bool global) {
    const char* word = global ? "GLOBAL" : "CONSTANT";
    next();
    const token& name = peek();
    if (name.kind != token_kind::string)
      return expected(std::string("the name in quotes after ") + word + " (" + word + " \"name\", " +
                      (global ? "vr" : "value") + ")");
    std::string text = name.text;
    const source_position name_at = name.at;
    next();
    bool valid = !text.empty() && is_letter(text[0]);
    for (char c : text) valid = valid && (is_letter(c) || is_digit(c) || c == '_');
    if (!valid)
      return fail(compile_status::syntax_error, name_at,
                  "'" + shown(text) + "' is not a name (a letter, then letters, digits and '_')");
    std::string upper_name = text;
    for (char& c : upper_name) c = upper(c);
    if (const reserved_word* w = find_reserved_word(upper_name)) {
      return fail(compile_status::syntax_error, name_at,
                  std::string("`") + w->name + "` is a Trio BASIC " + to_string(w->kind) + " and cannot be declared");
    }
    const std::string key = to_lower(text);
    if (slots_.count(key) != 0)
      return fail(compile_status::syntax_error, name_at,
                  "'" + shown(text) + "' is already used as a variable before this " + word);
    if (!expect_symbol(",", std::string("',' and the ") + (global ? "VR number" : "value") + " after " + word +
                                " \"name\"")) {
      return false;
    }
    double value = 0;
    if (!constant_value(value)) return false;
    if (!at_end_of_statement()) {
      return fail(compile_status::syntax_error, peek().at,
                  std::string(word) + " takes a number (or TRUE, PI, a CONSTANT ...), not an expression: found " +
                      found(peek()));
    }
    if (global && !(value >= 0 && value == std::floor(value) && value < 65536))
      return fail(compile_status::syntax_error, where, "GLOBAL takes a VR number (0, 1, 2 ...)");
    const auto [existing, added] = declared_.emplace(key, declared_name{global, value, where.line});
    if (!added) {
      return fail(compile_status::syntax_error, name_at,
                  "'" + shown(text) + "' is already declared at line " + std::to_string(existing->second.line));
    }
    return true;
  }

  // A number, a declared CONSTANT or a constant (TRUE, PI ...), with an optional sign.
  bool constant_value(double& out) {
    double sign = 1;
    while (is_symbol("-") || is_symbol("+")) {
      if (next().text == "-") sign = -sign;
    }
    const token& t = peek();
    if (t.kind == token_kind::number) {
      out = sign * next().value;
      return true;
    }
    if (t.kind == token_kind::name) {
      if (t.text == "TRUE" || t.text == "FALSE" || t.text == "ON" || t.text == "OFF" || t.text == "PI") {
        out = sign * named_constant(next().text);
        return true;
      }
      if (const auto d = declared_.find(to_lower(t.raw)); d != declared_.end() && !d->second.global) {
        next();
        out = sign * d->second.number;
        return true;
      }
    }
    return expected("a number");
  }

  static double named_constant(const std::string& word) {
    if (word == "TRUE") return -1;
    if (word == "ON") return 1;
    if (word == "PI") return 3.14159265358979323846;
    return 0;  // FALSE, OFF
  }

  // A list of expressions in parentheses (the '(' is next), at most max_arguments, into program::arguments.
  bool argument_list(const std::string& word, std::uint32_t& extra, std::uint32_t& count,
                     std::size_t at_least = 1) {
    if (!expect_symbol("(", "'(' after " + word)) return false;
    std::vector<std::uint32_t> ids;
    for (;;) {
      std::uint32_t id = 0;
      if (!expression(id)) return false;
      ids.push_back(id);
      if (ids.size() > max_arguments)
        return fail(compile_status::too_large, peek().at,
                    word + " takes at most " + std::to_string(max_arguments) + " values");
      if (!is_symbol(",")) break;
      next();
    }
    if (!expect_symbol(")", "')' to close " + word + "(")) return false;
    if (ids.size() < at_least)
      return expected(word + " with at least " + std::to_string(at_least) + " values");
    extra = static_cast<std::uint32_t>(p_.arguments.size());
    count = static_cast<std::uint32_t>(ids.size());
    p_.arguments.insert(p_.arguments.end(), ids.begin(), ids.end());
    return true;
  }

  bool motion_statement(source_position where, motion_command command) {
    const std::string word = next().text;
    statement s;
    s.kind = statement_kind::motion;
    s.line = where.line;
    s.slot = static_cast<std::uint32_t>(command);
    switch (command) {
      case motion_command::move:
      case motion_command::moveabs:
      case motion_command::defpos:
        if (!argument_list(word, s.extra, s.count)) return false;
        break;
      case motion_command::datum:
        if (!argument_list(word, s.extra, s.count)) return false;
        if (s.count != 1) return fail(compile_status::syntax_error, where, "DATUM takes one value: DATUM(mode)");
        break;
      case motion_command::cancel:
        if (is_symbol("(")) {
          if (!argument_list(word, s.extra, s.count)) return false;
          if (s.count != 1) return fail(compile_status::syntax_error, where, "CANCEL takes at most one value");
        }
        break;
      case motion_command::rapidstop:
        if (is_symbol("(")) {
          return fail(compile_status::syntax_error, where,
                      "RAPIDSTOP with a mode is not modelled (RAPIDSTOP alone cancels every axis's moves)");
        }
        break;
      case motion_command::forward:
      case motion_command::reverse:
        break;
    }
    if (command != motion_command::rapidstop && !axis_modifier(s.expr[3])) return false;
    p_.statements.push_back(s);
    return true;
  }

  bool base_statement(source_position where) {
    next();
    statement s;
    s.kind = statement_kind::base;
    s.line = where.line;
    if (!argument_list("BASE", s.extra, s.count)) return false;
    p_.statements.push_back(s);
    return true;
  }

  // TABLE(n, v1 [, v2 ...]) writes v1 to TABLE(n), v2 to TABLE(n+1) ...; TABLE(n) = v writes one.
  bool table_statement(source_position where) {
    const std::size_t start = pos_;
    next();
    next();  // '('
    int depth = 1;
    bool list = false;
    for (std::size_t i = pos_; i < t_.size() && depth > 0; ++i) {  // a ',' at the top level: the list form
      const token& t = t_[i];
      if (t.kind == token_kind::end_of_line || t.kind == token_kind::end_of_file) break;
      if (t.kind != token_kind::symbol) continue;
      if (t.text == "(") ++depth;
      if (t.text == ")") --depth;
      if (t.text == "," && depth == 1) list = true;
    }
    pos_ = start;
    if (!list) return assignment(where);
    next();
    statement s;
    s.kind = statement_kind::table_write;
    s.line = where.line;
    if (!argument_list("TABLE", s.extra, s.count, 2)) return false;
    p_.statements.push_back(s);
    return true;
  }

  bool op_statement(source_position where) {
    next();
    statement s;
    s.kind = statement_kind::output;
    s.line = where.line;
    if (!expect_symbol("(", "'(' after OP (OP(output, ON|OFF) or OP(bits))") || !expression(s.expr[0])) return false;
    if (is_symbol(",")) {
      next();
      if (!expression(s.expr[1])) return false;
    } else {
      s.flag = true;
    }
    if (!expect_symbol(")", "')' to close OP(")) return false;
    p_.statements.push_back(s);
    return true;
  }

  // ON n GOTO|GOSUB label1, label2 ... / ON BASICERROR GOTO label
  bool on_statement(source_position where) {
    next();
    if (is_word("BASICERROR")) {
      next();
      if (!expect_word("GOTO", "GOTO after ON BASICERROR (ON BASICERROR GOTO label)")) return false;
      const std::uint32_t s = emit(statement_kind::on_error, where);
      return label_reference(s, no_expression, "a label after ON BASICERROR GOTO");
    }
    std::uint32_t selector = 0;
    if (!expression(selector)) return false;
    if (!is_word("GOTO") && !is_word("GOSUB")) return expected("GOTO or GOSUB after ON expression");
    const bool gosub = next().text == "GOSUB";
    statement s;
    s.kind = statement_kind::on_jump;
    s.flag = gosub;
    s.line = where.line;
    s.expr[0] = selector;
    s.extra = static_cast<std::uint32_t>(p_.jump_targets.size());
    p_.statements.push_back(s);
    const std::uint32_t index = here() - 1;
    for (;;) {
      if (at_index(index).count >= max_arguments)
        return fail(compile_status::too_large, peek().at,
                    "ON ... GOTO takes at most " + std::to_string(max_arguments) + " labels");
      p_.jump_targets.push_back(0);
      ++at_index(index).count;
      if (!label_reference(index, static_cast<std::uint32_t>(p_.jump_targets.size() - 1),
                           std::string("a label after ON ... ") + (gosub ? "GOSUB" : "GOTO"))) {
        return false;
      }
      if (!is_symbol(",")) return true;
      next();
    }
  }

  bool wait_statement(source_position where) {
    next();
    if (is_word("UNTIL")) {
      next();
      std::uint32_t condition = 0;
      if (!expression(condition)) return false;
      at_index(emit(statement_kind::wait_until, where)).expr[0] = condition;
      return true;
    }
    if (is_word("IDLE") || is_word("LOADED")) {
      const bool idle = next().text == "IDLE";
      statement s;
      s.kind = idle ? statement_kind::wait_idle : statement_kind::wait_loaded;
      s.line = where.line;
      if (!axis_modifier(s.expr[3])) return false;
      p_.statements.push_back(s);
      return true;
    }
    return expected("UNTIL, IDLE or LOADED after WAIT");
  }

  bool print_statement(source_position where) {
    next();
    statement s;
    s.kind = statement_kind::print;
    s.line = where.line;
    if (is_symbol("#")) {
      next();
      if (!expression(s.expr[0])) return false;
      if (!at_end_of_statement() && !expect_symbol(",", "',' after the channel of PRINT #")) return false;
    }
    s.extra = static_cast<std::uint32_t>(p_.print_items.size());
    while (!at_end_of_statement()) {
      print_item item{};
      if (!print_item_of(item)) return false;
      if (is_symbol(";") || is_symbol(",")) {
        item.separator = next().text[0];
        p_.print_items.push_back(item);
      } else {
        p_.print_items.push_back(item);
        if (!at_end_of_statement()) return expected("';' or ',' between the items of PRINT");
      }
    }
    s.count = static_cast<std::uint32_t>(p_.print_items.size()) - s.extra;
    s.flag = s.count == 0 || p_.print_items.back().separator == '\0';  // CR LF at the end
    p_.statements.push_back(s);
    return true;
  }

  bool print_item_of(print_item& item) {
    item.separator = '\0';
    // A string, also in parentheses: PRINT("done") is a PRINT of "done".
    const bool in_parentheses =
        is_symbol("(") && peek(1).kind == token_kind::string && is_symbol(")", 2);
    if (peek().kind == token_kind::string || in_parentheses) {
      if (in_parentheses) next();
      item.what = print_item::kind::text;
      item.source = static_cast<std::uint32_t>(p_.texts.size());
      p_.texts.push_back(next().text);
      if (in_parentheses) next();
      return true;
    }
    if (is_word("CHR") || is_word("CURSOR") || is_word("HEX")) {
      const std::string word = next().text;
      item.what = word == "CHR"      ? print_item::kind::character
                  : word == "CURSOR" ? print_item::kind::cursor
                                     : print_item::kind::hex;
      return expect_symbol("(", "'(' after " + word) && expression(item.source) &&
             expect_symbol(")", "')' to close " + word + "(");
    }
    if (!expression(item.source)) return false;
    item.what = print_item::kind::number;
    if (!is_symbol("[")) return true;
    return number_format(item);
  }

  // x[w,d], x[w.d] (width w, d decimals) or x[d] (d decimals, no padding).
  bool number_format(print_item& item) {
    const source_position open = next().at;
    const token& first = peek();
    if (first.kind != token_kind::number || first.text[0] == '$')
      return expected("a width and decimals in the number format ([w,d], [w.d] or [d])");
    const std::string text = first.text;
    next();
    int width = 0;
    int decimals = 0;
    bool in_range = true;
    if (const std::size_t point = text.find('.'); point != std::string::npos) {
      if (point == 0 || point + 1 == text.size())
        return fail(compile_status::syntax_error, first.at, "expected [w.d] with digits on both sides of the point");
      in_range = small_number(text.substr(0, point), width) && small_number(text.substr(point + 1), decimals);
    } else if (is_symbol(",")) {
      next();
      const token& second = peek();
      if (second.kind != token_kind::number || second.text.find_first_not_of("0123456789") != std::string::npos)
        return expected("the number of decimals after ',' in [w,d]");
      in_range = small_number(text, width) && small_number(second.text, decimals);
      next();
    } else {
      in_range = small_number(text, decimals);
    }
    if (!in_range || width > 99 || decimals > 15) {
      return fail(compile_status::syntax_error, open,
                  "number format out of range: the width is 0..99 and the decimals 0..15");
    }
    item.what = print_item::kind::formatted_number;
    item.width = static_cast<std::int16_t>(width);
    item.decimals = static_cast<std::int16_t>(decimals);
    return expect_symbol("]", "']' to close the number format");
  }

  // Digits only, at most 3 of them.
  static bool small_number(const std::string& digits, int& out) {
    if (digits.empty() || digits.size() > 3 || digits.find_first_not_of("0123456789") != std::string::npos)
      return false;
    out = std::stoi(digits);
    return true;
  }

  bool get_statement(source_position where) {
    next();
    statement s;
    s.kind = statement_kind::get;
    s.line = where.line;
    if (!expect_symbol("#", "'#' and a channel after GET (GET #n,variable; GET alone, the controller's own "
                            "serial port, is not modelled)") ||
        !expression(s.expr[0]) ||
        !expect_symbol(",", "',' after the channel of GET #")) {
      return false;
    }
    const token& target = peek();
    if (target.kind == token_kind::name && target.text == "VR") {
      next();
      s.flag = true;
      if (!expect_symbol("(", "'(' after VR") || !expression(s.expr[1]) ||
          !expect_symbol(")", "')' to close VR(")) {
        return false;
      }
    } else if (target.kind == token_kind::name && declared_.count(to_lower(target.raw)) != 0 &&
               declared_.at(to_lower(target.raw)).global) {
      next();
      s.flag = true;
      s.expr[1] = constant_expression(declared_.at(to_lower(target.raw)).number);
    } else {
      if (!variable_name(target, "a variable or VR(n) to hold the character")) return false;
      s.slot = slot_of(next().raw);
    }
    p_.statements.push_back(s);
    return true;
  }

  bool send_statement(source_position where) {
    next();
    statement s;
    s.kind = statement_kind::send;
    s.line = where.line;
    if (!expect_symbol("(", "'(' after SEND (SEND(n,type,data1[,data2]))") || !expression(s.expr[0]) ||
        !expect_symbol(",", "',' and the message type after SEND(n") || !expression(s.expr[1]) ||
        !expect_symbol(",", "',' and data1 after SEND(n,type") || !expression(s.expr[2])) {
      return false;
    }
    if (is_symbol(",")) {
      next();
      if (!expression(s.expr[3])) return false;
    }
    if (!expect_symbol(")", "')' to close SEND(")) return false;
    p_.statements.push_back(s);
    return true;
  }

  bool if_statement(source_position where, bool one_line_if) {
    nesting guard(*this, "IF");
    if (!guard.ok()) return false;
    next();
    std::uint32_t condition = 0;
    if (!expression(condition) || !expect_word("THEN", "THEN after the IF condition")) return false;
    const std::uint32_t branch = emit(statement_kind::branch_unless, where);
    at_index(branch).expr[0] = condition;
    if (at_end_of_line()) {
      if (one_line_if) {
        return fail(compile_status::syntax_error, where, "a block IF (THEN at the end of the line) cannot be "
                                                         "part of a one-line IF");
      }
      return open_block({block::kind::if_block, where, branch, 0, {}});
    }
    if (!statements(true)) return false;
    if (is_word("ELSE")) {
      const source_position else_at = next().at;
      const std::uint32_t over = emit(statement_kind::jump, else_at);
      at_index(over).counted = false;
      at_index(branch).target = here();
      if (!statements(true)) return false;
      at_index(over).target = here();
    } else {
      at_index(branch).target = here();
    }
    return true;
  }

  bool open_block(block b) {
    if (blocks_.size() >= static_cast<std::size_t>(max_nesting))
      return fail(compile_status::too_large, b.at, "blocks nested more than " + std::to_string(max_nesting) + " deep");
    blocks_.push_back(std::move(b));
    return true;
  }

  // The innermost open block, which `word` must close (one of `kinds`).
  bool close_block(source_position where, const std::string& word, std::initializer_list<block::kind> kinds) {
    if (blocks_.empty()) {
      return fail(compile_status::unmatched_block, where, word + " without " + opening_word(*kinds.begin()));
    }
    const block& b = blocks_.back();
    if (std::find(kinds.begin(), kinds.end(), b.what) == kinds.end()) {
      return fail(compile_status::unmatched_block, where,
                  "expected " + std::string(closing_word(b.what)) + " to close the " + opening_word(b.what) +
                      " at line " + std::to_string(b.at.line) + ", found " + word);
    }
    return true;
  }

  // Ends the part of an IF block that is open: a jump to ENDIF, and its branch goes to what follows.
  void end_if_part(block& b, source_position where) {
    const std::uint32_t over = emit(statement_kind::jump, where);
    at_index(over).counted = false;
    b.ends.push_back(over);
    at_index(b.statement).target = here();
  }

  bool elseif_statement(source_position where) {
    if (!close_block(where, "ELSEIF", {block::kind::if_block})) return false;
    next();
    block& b = blocks_.back();
    end_if_part(b, where);
    std::uint32_t condition = 0;
    if (!expression(condition) || !expect_word("THEN", "THEN after the ELSEIF condition")) return false;
    if (!at_end_of_line()) return expected("the end of the line after ELSEIF ... THEN");
    const std::uint32_t branch = emit(statement_kind::branch_unless, where);
    at_index(branch).expr[0] = condition;
    blocks_.back().statement = branch;
    return true;
  }

  bool else_statement(source_position where) {
    if (!close_block(where, "ELSE", {block::kind::if_block})) return false;
    next();
    block& b = blocks_.back();
    end_if_part(b, where);
    b.what = block::kind::else_block;
    return true;
  }

  bool endif_statement(source_position where) {
    if (!close_block(where, "ENDIF", {block::kind::if_block, block::kind::else_block})) return false;
    next();
    block& b = blocks_.back();
    if (b.what == block::kind::if_block) at_index(b.statement).target = here();
    for (std::uint32_t end : b.ends) at_index(end).target = here();
    blocks_.pop_back();
    return true;
  }

  bool until_statement(source_position where) {
    if (!close_block(where, "UNTIL", {block::kind::repeat})) return false;
    next();
    std::uint32_t condition = 0;
    if (!expression(condition)) return false;
    const std::uint32_t s = emit(statement_kind::branch_unless, where);
    at_index(s).expr[0] = condition;
    at_index(s).target = blocks_.back().statement;
    blocks_.pop_back();
    return true;
  }

  bool wend_statement(source_position where) {
    if (!close_block(where, "WEND", {block::kind::while_loop})) return false;
    next();
    const std::uint32_t loop = blocks_.back().statement;
    at_index(emit(statement_kind::jump, where)).target = loop;
    at_index(loop).target = here();
    blocks_.pop_back();
    return true;
  }

  bool for_statement(source_position where) {
    next();
    const token& variable = peek();
    if (!variable_name(variable, "a variable after FOR (FOR i=first TO last [STEP step])")) return false;
    statement s;
    s.kind = statement_kind::for_start;
    s.line = where.line;
    s.slot = slot_of(next().raw);
    if (!expect_symbol("=", "'=' after the FOR variable") || !expression(s.expr[0]) ||
        !expect_word("TO", "TO after the first value of FOR") || !expression(s.expr[1])) {
      return false;
    }
    if (is_word("STEP")) {
      next();
      if (!expression(s.expr[2])) return false;
    }
    s.extra = 2 * for_loops_++;  // the hidden end and step values; moved past the named variables at the end
    p_.statements.push_back(s);
    return open_block({block::kind::for_loop, where, here() - 1, s.slot, {}});
  }

  bool next_statement(source_position where) {
    if (!close_block(where, "NEXT", {block::kind::for_loop})) return false;
    next();
    const std::uint32_t loop = blocks_.back().statement;
    const std::uint32_t loop_slot = blocks_.back().slot;
    const source_position loop_at = blocks_.back().at;
    if (peek().kind == token_kind::name) {
      const token& variable = peek();
      if (!variable_name(variable, "the FOR variable after NEXT")) return false;
      next();
      const auto found_slot = slots_.find(to_lower(variable.raw));
      if (found_slot == slots_.end() || found_slot->second != loop_slot) {
        return fail(compile_status::unmatched_block, variable.at,
                    "NEXT " + shown(variable.raw) + " does not match the FOR " + p_.variable_names[loop_slot] +
                        " at line " + std::to_string(loop_at.line));
      }
    }
    const std::uint32_t s = emit(statement_kind::for_next, where);
    at_index(s).slot = loop_slot;
    at_index(s).extra = at_index(loop).extra;
    at_index(s).target = loop + 1;
    at_index(loop).target = here();
    blocks_.pop_back();
    return true;
  }

  // ---- expressions ----
  //   or:    and { (OR | XOR) and }            lowest
  //   and:   not { (AND | &) not }
  //   not:   NOT not | comparison
  //   comparison: sum { (= <> < > <= >=) sum }
  //   sum:   product { (+ | -) product }
  //   product: unary { (* | / | MOD) unary }
  //   unary: - unary | + unary | power
  //   power: value { ^ exponent }               left to right: 2^3^2 is 64
  //   exponent: - exponent | + exponent | value  highest

  // One more level of nesting (a parenthesis, an operator, a one-line IF) while it lives; ok() says whether
  // that is still within max_nesting, so that no text can recurse the compiler deeper.
  class nesting {
   public:
    explicit nesting(compiler& c, const char* what = "expression") : c_(c), what_(what) { ++c_.nesting_; }
    ~nesting() { --c_.nesting_; }
    nesting(const nesting&) = delete;
    nesting& operator=(const nesting&) = delete;
    bool ok() {
      if (c_.nesting_ <= max_nesting) return true;
      return c_.fail(compile_status::too_large, c_.peek().at,
                     std::string(what_) + " nested more than " + std::to_string(max_nesting) + " deep");
    }

   private:
    compiler& c_;
    const char* what_;
  };

  bool expression(std::uint32_t& id) {
    const auto begin = static_cast<std::uint32_t>(p_.code.size());
    depth_ = 0;
    reads_ = 0;
    if (!or_expression()) return false;
    id = static_cast<std::uint32_t>(p_.expressions.size());
    p_.expressions.push_back({begin, static_cast<std::uint32_t>(p_.code.size()), reads_});
    if ((reads_ & reads_clock) != 0) p_.reads_clock = true;
    return true;
  }

  void push(expr_op op, std::uint32_t index = 0, double value = 0) {
    p_.code.push_back({op, index, value});
    switch (op) {
      case expr_op::constant:
      case expr_op::variable:
      case expr_op::axis:
      case expr_op::system:
      case expr_op::ticks:
      case expr_op::in_all:
        ++depth_;
        p_.stack_depth = std::max(p_.stack_depth, depth_);
        break;
      case expr_op::vr:
      case expr_op::table:
      case expr_op::axis_of:
      case expr_op::key:
      case expr_op::in_one:
      case expr_op::read_op:
      case expr_op::negate:
      case expr_op::logical_not:
      case expr_op::absolute:
      case expr_op::integer_part:
      case expr_op::fraction:
      case expr_op::sign:
      case expr_op::square_root:
      case expr_op::sine:
      case expr_op::cosine:
      case expr_op::tangent:
      case expr_op::arc_sine:
      case expr_op::arc_cosine:
      case expr_op::arc_tangent:
      case expr_op::exponential:
      case expr_op::logarithm:
        break;
      default:
        --depth_;  // binary, and in_range
        break;
    }
  }

  bool or_expression() {
    if (!and_expression()) return false;
    while (is_word("OR") || is_word("XOR")) {
      const expr_op op = next().text == "OR" ? expr_op::bit_or : expr_op::bit_xor;
      if (!and_expression()) return false;
      push(op);
    }
    return true;
  }

  bool and_expression() {
    if (!not_expression()) return false;
    while (is_word("AND") || is_symbol("&")) {
      next();
      if (!not_expression()) return false;
      push(expr_op::bit_and);
    }
    return true;
  }

  bool not_expression() {
    if (!is_word("NOT")) return comparison();
    nesting guard(*this);
    if (!guard.ok()) return false;
    next();
    if (!not_expression()) return false;
    push(expr_op::logical_not);
    return true;
  }

  bool comparison() {
    if (!sum()) return false;
    static constexpr std::pair<const char*, expr_op> relations[] = {
        {"=", expr_op::equal},      {"<>", expr_op::not_equal},  {"<", expr_op::less},
        {">", expr_op::greater},    {"<=", expr_op::less_equal}, {">=", expr_op::greater_equal}};
    for (;;) {
      const auto relation = std::find_if(std::begin(relations), std::end(relations),
                                         [&](const auto& r) { return is_symbol(r.first); });
      if (relation == std::end(relations)) return true;
      next();
      if (!sum()) return false;
      push(relation->second);
    }
  }

  bool sum() {
    if (!product()) return false;
    while (is_symbol("+") || is_symbol("-")) {
      const expr_op op = next().text == "+" ? expr_op::add : expr_op::subtract;
      if (!product()) return false;
      push(op);
    }
    return true;
  }

  bool product() {
    if (!unary()) return false;
    while (is_symbol("*") || is_symbol("/") || is_word("MOD")) {
      const std::string op = next().text;
      if (!unary()) return false;
      push(op == "*" ? expr_op::multiply : op == "/" ? expr_op::divide : expr_op::modulo);
    }
    return true;
  }

  bool signed_operand(bool (compiler::*operand)()) {
    nesting guard(*this);
    if (!guard.ok()) return false;
    const bool minus = next().text == "-";
    if (!(this->*operand)()) return false;
    if (!minus) return true;
    if (p_.code.back().op == expr_op::constant && depth_ > 0 && last_was_constant_) {
      p_.code.back().value = -p_.code.back().value;  // a negative constant
    } else {
      push(expr_op::negate);
    }
    return true;
  }

  bool unary() {
    if (is_symbol("-") || is_symbol("+")) return signed_operand(&compiler::unary);
    return power();
  }

  bool power() {
    if (!value()) return false;
    while (is_symbol("^")) {
      nesting guard(*this);
      if (!guard.ok()) return false;
      next();
      if (!exponent()) return false;
      push(expr_op::power);
    }
    return true;
  }

  bool exponent() {
    if (is_symbol("-") || is_symbol("+")) return signed_operand(&compiler::exponent);
    return value();
  }

  // `(expr)` after a function name, or two for ATAN2.
  bool call(const std::string& word, int arguments) {
    nesting guard(*this);
    if (!guard.ok()) return false;
    next();
    if (!expect_symbol("(", "'(' after " + word) || !or_expression()) return false;
    for (int i = 1; i < arguments; ++i) {
      if (!expect_symbol(",", "',' and the next value of " + word + "(") || !or_expression()) return false;
    }
    return expect_symbol(")", "')' to close " + word + "(");
  }

  bool value() {
    last_was_constant_ = false;
    const token& t = peek();
    switch (t.kind) {
      case token_kind::number:
        push(expr_op::constant, 0, next().value);
        last_was_constant_ = true;
        return true;
      case token_kind::string:
        return fail(compile_status::syntax_error, t.at, "a string can only be an item of PRINT");
      case token_kind::symbol:
        if (t.text == "(") {
          nesting guard(*this);
          if (!guard.ok()) return false;
          const source_position open = next().at;
          return or_expression() &&
                 expect_symbol(")", "')' to close the '(' at column " + std::to_string(open.column));
        }
        return expected("a value");
      case token_kind::end_of_line:
      case token_kind::end_of_file:
        return expected("a value");
      case token_kind::name:
        break;
    }
    const std::string word = t.text;
    if (dollar_name(t)) return false;
    const reserved_word* reserved = find_reserved_word(word);
    if (reserved == nullptr) {
      if (const auto d = declared_.find(to_lower(t.raw)); d != declared_.end()) {
        next();
        if (d->second.global) {
          push(expr_op::constant, 0, d->second.number);
          push(expr_op::vr);
        } else {
          push(expr_op::constant, 0, d->second.number);
          last_was_constant_ = true;
        }
        return true;
      }
      if (is_symbol("(", 1)) {
        return fail(compile_status::syntax_error, t.at,
                    "'" + shown(t.raw) + "' is not a Trio BASIC function (docs/basic.md lists the words)");
      }
      push(expr_op::variable, slot_of(next().raw));
      return true;
    }
    if (!reserved->modelled) return refuse(*reserved, t.at);
    if (word == "TRUE" || word == "FALSE" || word == "ON" || word == "OFF" || word == "PI") {
      next();
      push(expr_op::constant, 0, named_constant(word));
      last_was_constant_ = true;
      return true;
    }
    if (word == "VR" || word == "TABLE") {
      if (!call(word, 1)) return false;
      push(word == "VR" ? expr_op::vr : expr_op::table);
      return true;
    }
    for (const function_word& f : functions) {
      if (word != f.name) continue;
      if (!call(word, 1)) return false;
      push(f.op);
      return true;
    }
    if (word == "ATAN2") {
      if (!call(word, 2)) return false;
      push(expr_op::arc_tangent2);
      return true;
    }
    if (word == "IN") {
      reads_ |= reads_inputs;
      if (!is_symbol("(", 1)) {
        next();
        push(expr_op::in_all);
        return true;
      }
      nesting guard(*this);
      if (!guard.ok()) return false;
      next();
      next();  // '('
      if (!or_expression()) return false;
      const bool range = is_symbol(",");
      if (range && (!expect_symbol(",", "','") || !or_expression())) return false;
      if (!expect_symbol(")", "')' to close IN(")) return false;
      push(range ? expr_op::in_range : expr_op::in_one);
      return true;
    }
    if (word == "KEY") {
      next();
      if (!expect_symbol("#", "'#' and a channel after KEY (KEY#n; KEY alone, the controller's own serial port, "
                              "is not modelled)")) {
        return false;
      }
      nesting guard(*this);
      if (!guard.ok() || !unary()) return false;
      push(expr_op::key);
      return true;
    }
    if (word == "TICKS") {
      next();
      reads_ |= reads_clock;
      push(expr_op::ticks);
      return true;
    }
    if (word == "BASE") {
      next();
      push(expr_op::system, static_cast<std::uint32_t>(system_value::base_axis));
      return true;
    }
    for (const system_word& s : system_words) {
      if (word != s.name) continue;
      next();
      push(expr_op::system, static_cast<std::uint32_t>(s.value));
      return true;
    }
    if (axis_parameter p{}; find_axis_parameter(word, p)) {
      next();
      reads_ |= reads_axes;
      std::uint32_t axis = no_expression;
      if (is_word("AXIS")) {
        nesting guard(*this);
        if (!guard.ok()) return false;
        next();
        if (!expect_symbol("(", "'(' after AXIS (AXIS(n))") || !or_expression() ||
            !expect_symbol(")", "')' to close AXIS(")) {
          return false;
        }
        axis = 0;
      }
      push(axis == no_expression ? expr_op::axis : expr_op::axis_of, static_cast<std::uint32_t>(p));
      return true;
    }
    if (word == "CHR" || word == "CURSOR" || word == "HEX")
      return fail(compile_status::syntax_error, t.at, word + "(...) can only be an item of PRINT");
    return fail(compile_status::syntax_error, t.at,
                "expected a value, found " + found(t) + (reserved->kind == word_kind::program_structure ||
                                                                 reserved->kind == word_kind::motion_command ||
                                                                 reserved->kind == word_kind::io_command ||
                                                                 reserved->kind == word_kind::system_command
                                                             ? " (a command, not a value)"
                                                             : ""));
  }

  const std::vector<token>& t_;
  program& p_;
  std::size_t pos_ = 0;
  std::vector<block> blocks_;
  std::map<std::string, std::uint32_t> slots_;
  std::map<std::string, label_definition> labels_;
  std::map<std::string, declared_name> declared_;
  std::vector<label_use> label_uses_;
  std::uint32_t for_loops_ = 0;
  std::uint32_t depth_ = 0;
  std::uint8_t reads_ = 0;
  bool last_was_constant_ = false;
  int nesting_ = 0;
};

}  // namespace

std::string compile_result::located_message() const {
  return shown(compiled.name, 80) + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) +
         ": " + message;
}

compile_result compile(std::string_view name, std::string_view text) {
  compile_result result;
  result.compiled.name = std::string(name);
  if (text.size() > max_program_text) {
    result.status = compile_status::too_large;
    result.at = {1, 1};
    result.message = "the program is " + std::to_string(text.size()) + " bytes long; at most " +
                     std::to_string(max_program_text) + " are read";
    return result;
  }
  // A UTF-8 byte order mark, as Windows editors write one, is not program text.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::vector<token> tokens;
  lex_error error;
  if (!lexer(text).run(tokens, error)) {
    result.status = compile_status::syntax_error;
    result.at = error.at;
    result.message = std::move(error.message);
    return result;
  }
  compiler c(tokens, result.compiled);
  if (!c.run()) {
    result.status = c.status;
    result.at = c.at;
    result.message = std::move(c.message);
    program kept_name;
    kept_name.name = std::move(result.compiled.name);
    result.compiled = std::move(kept_name);
  }
  return result;
}

}  // namespace trionet::basic

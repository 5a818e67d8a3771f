// Trio BASIC text -> program (program.hpp): a lexer, then one recursive-descent pass that emits statements
// and reverse-Polish expressions, resolving block ends as they close and labels at the end.
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <map>
#include <utility>

#include "basic/program.hpp"

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
  if (is_digit(c)) return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
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

std::string shown(char c) {
  const auto byte = static_cast<unsigned char>(c);
  char text[16];
  if (byte >= 32 && byte < 127) {
    std::snprintf(text, sizeof text, "'%c'", c);
  } else {
    std::snprintf(text, sizeof text, "byte 0x%02x", byte);
  }
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
        if (!name(out)) return false;
      } else if (is_digit(c) || (c == '.' && i_ + 1 < s_.size() && is_digit(s_[i_ + 1]))) {
        if (!number(out, error)) return false;
      } else if (c == '$') {
        if (!hex_number(out, error)) return false;
      } else if (c == '"') {
        if (!string(out, error)) return false;
      } else if (!symbol(out)) {
        error = {here(i_), "unexpected character " + shown(c)};
        return false;
      }
    }
    if (out.empty() || out.back().kind != token_kind::end_of_line) emit(out, token_kind::end_of_line, "", i_);
    emit(out, token_kind::end_of_file, "", i_);
    return true;
  }

 private:
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

  bool name(std::vector<token>& out) {
    const std::size_t start = i_;
    while (i_ < s_.size() && (is_letter(s_[i_]) || is_digit(s_[i_]) || s_[i_] == '_')) ++i_;
    std::string text(s_.substr(start, i_ - start));
    std::string raw = text;
    for (char& c : text) c = upper(c);
    if (text == "REM") {  // a comment to the end of the line
      skip_to_end_of_line();
      return true;
    }
    emit(out, token_kind::name, std::move(text), start);
    out.back().raw = std::move(raw);
    return true;
  }

  bool number(std::vector<token>& out, lex_error& error) {
    const std::size_t start = i_;
    while (i_ < s_.size() && is_digit(s_[i_])) ++i_;
    if (i_ < s_.size() && s_[i_] == '.') {
      ++i_;
      while (i_ < s_.size() && is_digit(s_[i_])) ++i_;
    }
    const std::string_view text = s_.substr(start, i_ - start);
    double value = 0;
    const auto parsed = std::from_chars(text.data(), text.data() + text.size(), value, std::chars_format::fixed);
    if (parsed.ec != std::errc() || parsed.ptr != text.data() + text.size()) {
      error = {here(start), "the number " + std::string(text) + " is out of range"};
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
    if (digits == 0 || digits > 13) {  // 13 hex digits are exact in a double
      error = {here(start), digits == 0 ? "expected hex digits after '$'" : "the hex number is out of range"};
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
        error = {here(i_), shown(s_[i_]) + " in a string: the ring carries characters 0..127"};
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
    static constexpr std::string_view one = "(),;:#[]=<>+-*/&";
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

constexpr const char* statement_words[] = {"PRINT",  "GET",  "SEND", "IF",    "ELSE", "ENDIF", "GOTO",
                                           "GOSUB",  "RETURN", "REPEAT", "UNTIL", "WHILE", "WEND", "FOR",
                                           "NEXT",   "WAIT", "WA",   "STOP"};
constexpr const char* other_words[] = {"THEN", "TO",  "STEP",  "VR",    "NETSTAT", "KEY", "CHR", "CURSOR", "NOT",
                                       "AND",  "OR",  "XOR",   "MOD",   "TRUE",    "FALSE", "ABS", "INT", "DEFKEY"};

bool in(const char* const* first, const char* const* last, const std::string& word) {
  return std::any_of(first, last, [&](const char* w) { return word == w; });
}
int axis_parameter_index(const std::string& word) {
  for (std::size_t i = 0; i < axis_parameter_count; ++i) {
    if (word == axis_parameter_names[i]) return static_cast<int>(i);
  }
  return -1;
}
bool reserved(const std::string& word) {
  return in(std::begin(statement_words), std::end(statement_words), word) ||
         in(std::begin(other_words), std::end(other_words), word) || axis_parameter_index(word) >= 0;
}
bool block_word(const std::string& word) {
  return word == "ELSE" || word == "ENDIF" || word == "REPEAT" || word == "UNTIL" || word == "WHILE" ||
         word == "WEND" || word == "FOR" || word == "NEXT";
}

std::string found(const token& t) {
  switch (t.kind) {
    case token_kind::end_of_line:
      return "the end of the line";
    case token_kind::end_of_file:
      return "the end of the file";
    case token_kind::name:
      return "'" + t.raw + "'";
    case token_kind::number:
      return "the number " + t.text;
    case token_kind::string:
      return "the string \"" + t.text + "\"";
    case token_kind::symbol:
      return "'" + t.text + "'";
  }
  return "?";
}

// ---- parser and code generator ----

struct block {
  enum class kind : std::uint8_t { if_block, else_block, repeat, while_loop, for_loop } what;
  source_position at;
  std::uint32_t statement;  // if: its branch; else: the jump over it; repeat: the body's first; while, for: theirs
  std::uint32_t slot;       // for: the loop variable
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
  source_position at;
};

struct label_definition {
  std::uint32_t statement;
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
        return fail(compile_status::unknown_label, use.at, "no label '" + use.name + "' in the program");
      p_.statements[use.statement].target = found_label->second.statement;
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

  // ---- lines and statements ----

  bool line() {
    if (peek().kind == token_kind::name && !reserved(peek().text) && is_symbol(":", 1)) {
      const token& label = next();
      const std::string name = to_lower(label.raw);
      const auto [where, added] = labels_.emplace(name, label_definition{here(), label.at.line});
      if (!added) {
        return fail(compile_status::duplicate_label, label.at,
                    "label '" + name + "' is already defined at line " + std::to_string(where->second.line));
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

  bool one_statement(bool one_line_if) {
    const token& first = peek();
    const source_position where = first.at;
    if (first.kind != token_kind::name) return expected("a statement");
    const std::string word = first.text;
    if (one_line_if && block_word(word)) {
      return fail(compile_status::syntax_error, where,
                  word + " cannot be part of a one-line IF (write IF ... THEN at the end of a line, then ENDIF)");
    }
    if (word == "PRINT") return print_statement(where);
    if (word == "GET") return get_statement(where);
    if (word == "SEND") return send_statement(where);
    if (word == "IF") return if_statement(where, one_line_if);
    if (word == "ELSE") return else_statement(where);
    if (word == "ENDIF") return endif_statement(where);
    if (word == "GOTO" || word == "GOSUB") {
      next();
      const token& label = peek();
      if (label.kind != token_kind::name || reserved(label.text)) return expected("a label after " + word);
      const std::uint32_t s = emit(word == "GOTO" ? statement_kind::jump : statement_kind::gosub, where);
      label_uses_.push_back({to_lower(label.raw), s, label.at});
      next();
      return true;
    }
    if (word == "RETURN" || word == "STOP") {
      next();
      emit(word == "RETURN" ? statement_kind::return_from_gosub : statement_kind::stop, where);
      return true;
    }
    if (word == "REPEAT") {
      next();
      return open_block({block::kind::repeat, where, here(), 0});
    }
    if (word == "UNTIL") return until_statement(where);
    if (word == "WHILE") {
      next();
      std::uint32_t condition = 0;
      if (!expression(condition)) return false;
      const std::uint32_t s = emit(statement_kind::branch_unless, where);
      at_index(s).expr[0] = condition;
      return open_block({block::kind::while_loop, where, s, 0});
    }
    if (word == "WEND") return wend_statement(where);
    if (word == "FOR") return for_statement(where);
    if (word == "NEXT") return next_statement(where);
    if (word == "WAIT") {
      next();
      if (!expect_word("UNTIL", "UNTIL after WAIT (WAIT UNTIL condition)")) return false;
      std::uint32_t condition = 0;
      if (!expression(condition)) return false;
      at_index(emit(statement_kind::wait_until, where)).expr[0] = condition;
      return true;
    }
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
    return assignment(where);
  }

  bool assignment(source_position where) {
    const token& target = next();
    const std::string word = target.text;
    statement s;
    s.line = where.line;
    if (word == "VR") {
      s.kind = statement_kind::assign_vr;
      if (!expect_symbol("(", "'(' after VR") || !expression(s.expr[0]) ||
          !expect_symbol(")", "')' to close VR(")) {
        return false;
      }
    } else if (word == "NETSTAT") {
      s.kind = statement_kind::assign_netstat;
    } else if (const int parameter = axis_parameter_index(word); parameter >= 0) {
      s.kind = statement_kind::assign_parameter;
      s.slot = static_cast<std::uint32_t>(parameter);
    } else if (word == "DEFKEY") {
      return fail(compile_status::syntax_error, where,
                  "DEFKEY is not supported: GET #3 translates through the default DEFKEY table (docs/basic.md)");
    } else if (reserved(word)) {
      return fail(compile_status::syntax_error, where, "expected a statement, found " + found(target));
    } else {
      if (is_symbol("(")) {
        return fail(compile_status::syntax_error, where,
                    "'" + target.raw + "' is not a command this interpreter knows (docs/basic.md lists them)");
      }
      if (is_symbol(":")) {
        return fail(compile_status::syntax_error, where,
                    "a label must start its line ('" + target.raw + ":' follows another statement)");
      }
      s.kind = statement_kind::assign_variable;
      s.slot = slot_of(target.raw);
    }
    if (!expect_symbol("=", "'=' after " + found(target))) return false;
    const std::uint32_t value_expr = s.kind == statement_kind::assign_vr ? 1 : 0;
    if (!expression(s.expr[value_expr])) return false;
    p_.statements.push_back(s);
    return true;
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
    if (peek().kind == token_kind::string) {
      item.what = print_item::kind::text;
      item.source = static_cast<std::uint32_t>(p_.texts.size());
      p_.texts.push_back(next().text);
      return true;
    }
    if (is_word("CHR") || is_word("CURSOR")) {
      const std::string word = next().text;
      item.what = word == "CHR" ? print_item::kind::character : print_item::kind::cursor;
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
    if (!expect_symbol("#", "'#' and a channel after GET (GET #n,variable)") || !expression(s.expr[0]) ||
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
    } else if (target.kind == token_kind::name && !reserved(target.text)) {
      s.slot = slot_of(next().raw);
    } else {
      return expected("a variable or VR(n) to hold the character");
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
      return open_block({block::kind::if_block, where, branch, 0});
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

  bool open_block(const block& b) {
    if (blocks_.size() >= static_cast<std::size_t>(max_nesting))
      return fail(compile_status::too_large, b.at, "blocks nested more than " + std::to_string(max_nesting) + " deep");
    blocks_.push_back(b);
    return true;
  }

  // The innermost open block, which `word` must close (one of `kinds`).
  bool close_block(source_position where, const std::string& word, std::initializer_list<block::kind> kinds) {
    if (blocks_.empty()) {
      return fail(compile_status::unmatched_block, where,
                  word + " without " + opening_word(*kinds.begin()));
    }
    const block& b = blocks_.back();
    if (std::find(kinds.begin(), kinds.end(), b.what) == kinds.end()) {
      return fail(compile_status::unmatched_block, where,
                  "expected " + std::string(closing_word(b.what)) + " to close the " + opening_word(b.what) +
                      " at line " + std::to_string(b.at.line) + ", found " + word);
    }
    return true;
  }

  bool else_statement(source_position where) {
    if (!close_block(where, "ELSE", {block::kind::if_block})) return false;
    next();
    block& b = blocks_.back();
    const std::uint32_t over = emit(statement_kind::jump, where);
    at_index(over).counted = false;
    at_index(b.statement).target = here();
    b.what = block::kind::else_block;
    b.statement = over;
    return true;
  }

  bool endif_statement(source_position where) {
    if (!close_block(where, "ENDIF", {block::kind::if_block, block::kind::else_block})) return false;
    next();
    at_index(blocks_.back().statement).target = here();
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
    if (variable.kind != token_kind::name || reserved(variable.text))
      return expected("a variable after FOR (FOR i=first TO last [STEP step])");
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
    return open_block({block::kind::for_loop, where, here() - 1, s.slot});
  }

  bool next_statement(source_position where) {
    if (!close_block(where, "NEXT", {block::kind::for_loop})) return false;
    next();
    const block b = blocks_.back();
    if (peek().kind == token_kind::name && !reserved(peek().text)) {
      const token& variable = next();
      const auto found_slot = slots_.find(to_lower(variable.raw));
      if (found_slot == slots_.end() || found_slot->second != b.slot) {
        return fail(compile_status::unmatched_block, variable.at,
                    "NEXT " + variable.raw + " does not match the FOR " + p_.variable_names[b.slot] + " at line " +
                        std::to_string(b.at.line));
      }
    }
    const std::uint32_t s = emit(statement_kind::for_next, where);
    at_index(s).slot = b.slot;
    at_index(s).extra = at_index(b.statement).extra;
    at_index(s).target = b.statement + 1;
    at_index(b.statement).target = here();
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
  //   unary: - unary | + unary | value         highest

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
    if (!or_expression()) return false;
    id = static_cast<std::uint32_t>(p_.expressions.size());
    p_.expressions.push_back({begin, static_cast<std::uint32_t>(p_.code.size())});
    return true;
  }

  void push(expr_op op, std::uint32_t index = 0, double value = 0) {
    p_.code.push_back({op, index, value});
    switch (op) {
      case expr_op::constant:
      case expr_op::variable:
      case expr_op::parameter:
      case expr_op::netstat:
        ++depth_;
        p_.stack_depth = std::max(p_.stack_depth, depth_);
        break;
      case expr_op::vr:
      case expr_op::key:
      case expr_op::negate:
      case expr_op::logical_not:
      case expr_op::absolute:
      case expr_op::integer_part:
        break;
      default:
        --depth_;  // binary
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

  bool unary() {
    if (is_symbol("-") || is_symbol("+")) {
      nesting guard(*this);
      if (!guard.ok()) return false;
      const bool minus = next().text == "-";
      if (!unary()) return false;
      if (!minus) return true;
      if (p_.code.back().op == expr_op::constant && depth_ > 0) {
        p_.code.back().value = -p_.code.back().value;  // a negative constant
      } else {
        push(expr_op::negate);
      }
      return true;
    }
    return value();
  }

  bool value() {
    const token& t = peek();
    switch (t.kind) {
      case token_kind::number:
        push(expr_op::constant, 0, next().value);
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
    if (word == "TRUE" || word == "FALSE") {
      next();
      push(expr_op::constant, 0, word == "TRUE" ? -1.0 : 0.0);
      return true;
    }
    if (word == "VR" || word == "ABS" || word == "INT") {
      nesting guard(*this);
      if (!guard.ok()) return false;
      next();
      if (!expect_symbol("(", "'(' after " + word) || !or_expression() ||
          !expect_symbol(")", "')' to close " + word + "(")) {
        return false;
      }
      push(word == "VR" ? expr_op::vr : word == "ABS" ? expr_op::absolute : expr_op::integer_part);
      return true;
    }
    if (word == "KEY") {
      next();
      if (!expect_symbol("#", "'#' and a channel after KEY (KEY#n)")) return false;
      nesting guard(*this);
      if (!guard.ok() || !unary()) return false;
      push(expr_op::key);
      return true;
    }
    if (word == "NETSTAT") {
      next();
      push(expr_op::netstat);
      return true;
    }
    if (const int parameter = axis_parameter_index(word); parameter >= 0) {
      next();
      push(expr_op::parameter, static_cast<std::uint32_t>(parameter));
      return true;
    }
    if (word == "CHR" || word == "CURSOR")
      return fail(compile_status::syntax_error, t.at, word + "(...) can only be an item of PRINT");
    if (reserved(word)) return expected("a value");
    if (is_symbol("(", 1)) {
      return fail(compile_status::syntax_error, t.at,
                  "'" + t.raw + "' is not a function this interpreter knows (docs/basic.md lists them)");
    }
    push(expr_op::variable, slot_of(next().raw));
    return true;
  }

  const std::vector<token>& t_;
  program& p_;
  std::size_t pos_ = 0;
  std::vector<block> blocks_;
  std::map<std::string, std::uint32_t> slots_;
  std::map<std::string, label_definition> labels_;
  std::vector<label_use> label_uses_;
  std::uint32_t for_loops_ = 0;
  std::uint32_t depth_ = 0;
  int nesting_ = 0;
};

}  // namespace

std::string compile_result::located_message() const {
  return compiled.name + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": " + message;
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

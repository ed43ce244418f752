#pragma once
/// \file
/// The statement level of the model language's parser (parser.hpp): a cursor over one
/// file's tokens and the parsing of a call `[Label] 'NAME [(args)]`, its argument
/// groups and items (numbers, $DATA names, KEY=value, W:Name(k)). Errors are lang_error
/// with the file:line:column of the offending text.

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pradis/lang/ast.hpp"
#include "pradis/lang/lexer.hpp"

namespace pradis::lang {

/// The tokens of one source file and the statements they make; parser (parser.hpp) adds
/// the sections and $INCLUDE.
class statement_parser {
 protected:
  explicit statement_parser(std::shared_ptr<const source_file> src) : src_(std::move(src)), t_(lex(src_)) {}

  // ---- token helpers -----------------------------------------------------------
  const token& cur() const { return t_[p_]; }
  const token& next() const { return t_[std::min(p_ + 1, t_.size() - 1)]; }
  bool at(tok k) const { return cur().kind == k; }
  bool at_statement_end() const {
    const tok k = cur().kind;
    return k == tok::newline || k == tok::eof || k == tok::section || k == tok::subsection;
  }
  bool at_block_end() const { return at(tok::eof) || at(tok::section); }
  void skip_newlines() {
    while (at(tok::newline)) ++p_;
  }
  [[noreturn]] static void fail(const location& l, const std::string& msg) { throw lang_error(l, msg); }
  void optional_colon() {
    if (at(tok::colon)) ++p_;
  }
  void end_statement(const char* what) {
    if (!at_statement_end()) fail(cur().loc, "unexpected " + describe(cur()) + " after " + what);
  }
  static bool name_start(const std::string& w) {
    const auto c = static_cast<unsigned char>(w[0]);
    return detail::is_alpha(w[0]) || c >= 0x80;
  }

  // ---- statements -----------------------------------------------------------------
  /// Words up to a token of kind `stop` (not consumed... it is left current), joined by one blank.
  std::string words_until(tok stop, const char* expected) {
    std::string s;
    while (at(tok::word)) {
      if (!s.empty()) s += ' ';
      s += cur().text;
      ++p_;
    }
    if (s.empty() || !at(stop)) fail(cur().loc, std::string("expected ") + expected + ", found " + describe(cur()));
    return s;
  }
  std::string words_until_any(const char*) {
    std::string s;
    while (at(tok::word)) {
      if (!s.empty()) s += ' ';
      s += cur().text;
      ++p_;
    }
    return s;
  }

  // ---- calls -----------------------------------------------------------------------
  ast::call call() {
    ast::call c;
    c.loc = cur().loc;
    c.label = words_until_any("");
    if (!c.label.empty() && !name_start(c.label))
      fail(c.loc, "a label must start with a letter or '_': '" + c.label + "'");
    if (!at(tok::quote))
      fail(cur().loc, c.label.empty() ? "expected a statement `Label 'NAME (...)`, found " + describe(cur())
                                      : "expected \"'\" and a model or program name after '" + c.label + "', found " +
                                            describe(cur()));
    ++p_;
    if (!at(tok::word) || !name_start(cur().text))
      fail(cur().loc, "expected a model or program name after \"'\", found " + describe(cur()));
    c.program_loc = cur().loc;
    c.program = upper(cur().text);
    ++p_;
    c.args_loc = c.program_loc;
    if (at(tok::lparen)) {
      c.args_loc = cur().loc;
      ++p_;
      c.args = arguments(c.args_loc);
    }
    end_statement(("the call of '" + c.program + "' (one statement per line)").c_str());
    return c;
  }

  ast::groups arguments(const location& open) {
    ast::groups g(1);
    for (;;) {
      skip_newlines();
      const token& t = cur();
      switch (t.kind) {
        case tok::rparen:
          ++p_;
          return g;
        case tok::semicolon:
          ++p_;
          g.emplace_back();
          continue;
        case tok::eof:
        case tok::section:
        case tok::subsection:
          fail(open, "missing ')' for this '(' (found " + describe(t) + " at " + std::to_string(t.loc.line) + ":" +
                         std::to_string(t.loc.col) + ")");
        case tok::word:
          break;
        case tok::quote:
          fail(open, "missing ')' for this '(' (a new statement starts at " + std::to_string(t.loc.line) + ":" +
                         std::to_string(t.loc.col) + ")");
        default:
          fail(t.loc, "expected a number, a name or KEY=value, found " + describe(t));
      }
      g.back().push_back(item());
      if (at(tok::comma)) {
        ++p_;
        skip_newlines();
        if (!at(tok::word)) fail(cur().loc, "expected a value after ',', found " + describe(cur()));
      }
    }
  }

  ast::item item() {
    const token& t = cur();
    if (next().kind == tok::equals) {
      ast::item k;
      k.what = ast::item::kind::keyed;
      k.loc = t.loc;
      k.text = upper(t.text);
      if (!name_start(t.text)) fail(t.loc, "expected a key name before '=', found " + describe(t));
      p_ += 2;
      if (!at(tok::word)) fail(cur().loc, "expected a value after '" + k.text + "=', found " + describe(cur()));
      k.value.push_back(value());
      return k;
    }
    if ((t.text == "W" || t.text == "w") && next().kind == tok::colon) {
      ast::item w;
      w.what = ast::item::kind::work;
      w.loc = t.loc;
      p_ += 2;
      w.text = words_until(tok::lparen, "an element name and '(' after 'W:' (W:Name(k))");
      ++p_;
      w.index_loc = cur().loc;
      if (!at(tok::word)) fail(cur().loc, "expected the work-vector index k in W:Name(k), found " + describe(cur()));
      const auto k = parse_number(cur().text);
      if (!k || !(*k >= 1 && *k <= 1e9) || *k != std::floor(*k))  // range first: no UB in the cast
        fail(cur().loc, "the work-vector index in W:Name(k) must be a whole number >= 1, found '" + cur().text + "'");
      w.index = static_cast<int>(*k);
      ++p_;
      if (!at(tok::rparen))
        fail(cur().loc,
             "expected ')' after W:" + w.text + "(" + std::to_string(w.index) + ", found " + describe(cur()));
      ++p_;
      return w;
    }
    return value();
  }

  /// A number, or a $DATA name (words up to the next punctuation), optionally negated.
  ast::item value() {
    const token& t = cur();
    ast::item v;
    v.loc = t.loc;
    if (t.kind != tok::word) fail(t.loc, "expected a number or a name, found " + describe(t));
    if (looks_numeric(t.text)) {
      const auto x = parse_number(t.text);
      if (!x && t.text.size() > 400)
        fail(t.loc, "unparsable number: a word of " + std::to_string(t.text.size()) +
                        " characters starting with a digit (a number has at most 400)");
      if (!x) fail(t.loc, "unparsable number '" + t.text + "'");
      if (underflows(t.text, *x))
        fail(t.loc, "the number " + t.text + " is too small for double precision (it would become 0; the smallest "
                    "normal magnitude is 2.2E-308): write 0 if 0 is meant");
      v.number = *x;
      ++p_;
      return v;
    }
    v.what = ast::item::kind::name;
    std::string first = t.text;
    if (first[0] == '-' || first[0] == '+') {
      v.negate = first[0] == '-';
      first.erase(0, 1);
    }
    if (first.empty() || !name_start(first)) fail(t.loc, "expected a number or a name, found '" + t.text + "'");
    v.text = first;
    ++p_;
    while (at(tok::word)) {
      v.text += ' ' + cur().text;
      ++p_;
    }
    return v;
  }

  std::shared_ptr<const source_file> src_;
  std::vector<token> t_;
  std::size_t p_ = 0;
};

}  // namespace pradis::lang

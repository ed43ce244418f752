#pragma once
/// \file
/// Lexer of the model language (see docs/language.md).
///
/// Tokens: `$NAME` (section), `#NAME` (subsection, blanks allowed after '#'),
/// words (maximal runs of characters other than blanks and `= , ; ( ) ' : " $ #`),
/// "strings" (one line), the punctuation `= , ; ( ) ' :`, end of line, end of file.
/// Comments: a line whose first non-blank character is `*`, and everything
/// from `//` to the end of the line. Control characters other than tab, CR and
/// LF (binary data) are an error. Nothing after `$END` is read. Bytes >= 0x80
/// (UTF-8) may appear in words. A line ends at LF, CR LF or a lone CR.

#include <cctype>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pradis/lang/source.hpp"

namespace pradis::lang {

/// Kinds of tokens.
enum class tok {
  word,
  string,
  section,
  subsection,
  equals,
  comma,
  semicolon,
  lparen,
  rparen,
  quote,
  colon,
  newline,
  eof
};

/// One token. For sections and subsections `text` is the keyword in upper case;
/// for strings the contents without quotes.
struct token {
  tok kind = tok::eof;  ///< what the token is
  std::string text;     ///< its text (see above)
  location loc;         ///< where it starts
};

/// Human-readable description of a token for messages ("'('", "end of line", "'Body'").
inline std::string describe(const token& t) {
  switch (t.kind) {
    case tok::word:
      return "'" + t.text + "'";
    case tok::string:
      return "string \"" + t.text + "\"";
    case tok::section:
      return "section $" + t.text;
    case tok::subsection:
      return "subsection #" + t.text;
    case tok::equals:
      return "'='";
    case tok::comma:
      return "','";
    case tok::semicolon:
      return "';'";
    case tok::lparen:
      return "'('";
    case tok::rparen:
      return "')'";
    case tok::quote:
      return "\"'\"";
    case tok::colon:
      return "':'";
    case tok::newline:
      return "end of line";
    case tok::eof:
      return "end of file";
  }
  return "?";
}

namespace detail {
inline bool is_punct(char c) {
  switch (c) {
    case '=':
    case ',':
    case ';':
    case '(':
    case ')':
    case '\'':
    case ':':
    case '"':
    case '$':
    case '#':
      return true;
    default:
      return false;
  }
}
inline bool is_control(char c) {
  const auto u = static_cast<unsigned char>(c);
  return (u < 0x20 && c != '\t' && c != '\r' && c != '\n') || u == 0x7f;
}
inline bool is_alpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; }
}  // namespace detail

/// Splits a source into tokens. Throws lang_error on a control character, an
/// unterminated string or a '$'/'#' without a keyword.
inline std::vector<token> lex(const std::shared_ptr<const source_file>& src) {
  std::vector<token> out;
  const std::string& s = src->text;
  std::size_t i = 0;
  int line = 1;
  std::size_t line_start = 0;
  bool line_blank = true;                      // only blanks so far on this line
  if (s.rfind("\xEF\xBB\xBF", 0) == 0) i = 3;  // UTF-8 byte-order mark
  line_start = i;
  auto loc_at = [&](std::size_t p) { return location{src, line, static_cast<int>(p - line_start) + 1}; };
  auto push = [&](tok k, std::string text, std::size_t p) { out.push_back({k, std::move(text), loc_at(p)}); };
  auto skip_to_eol = [&] {
    while (i < s.size() && s[i] != '\n' && s[i] != '\r') {
      if (detail::is_control(s[i]))
        throw lang_error(loc_at(i), "invalid character (byte " + std::to_string(static_cast<unsigned char>(s[i])) +
                                        "): this does not look like a text file");
      ++i;
    }
  };
  while (i < s.size()) {
    const char c = s[i];
    if (c == '\n' || (c == '\r' && (i + 1 >= s.size() || s[i + 1] != '\n'))) {  // LF, or a lone CR (old Mac)
      push(tok::newline, {}, i);
      ++i;
      ++line;
      line_start = i;
      line_blank = true;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
      continue;
    }
    if (detail::is_control(c))
      throw lang_error(loc_at(i), "invalid character (byte " + std::to_string(static_cast<unsigned char>(c)) +
                                      "): this does not look like a text file");
    if ((c == '*' && line_blank) || (c == '/' && i + 1 < s.size() && s[i + 1] == '/')) {
      skip_to_eol();
      continue;
    }
    line_blank = false;
    const std::size_t start = i;
    switch (c) {
      case '=':
        push(tok::equals, "=", i++);
        continue;
      case ',':
        push(tok::comma, ",", i++);
        continue;
      case ';':
        push(tok::semicolon, ";", i++);
        continue;
      case '(':
        push(tok::lparen, "(", i++);
        continue;
      case ')':
        push(tok::rparen, ")", i++);
        continue;
      case '\'':
        push(tok::quote, "'", i++);
        continue;
      case ':':
        push(tok::colon, ":", i++);
        continue;
      case '"': {
        ++i;
        while (i < s.size() && s[i] != '"' && s[i] != '\n' && s[i] != '\r') {
          if (detail::is_control(s[i])) throw lang_error(loc_at(i), "invalid character in a string");
          ++i;
        }
        if (i >= s.size() || s[i] != '"') throw lang_error(loc_at(start), "unterminated string (missing '\"')");
        push(tok::string, s.substr(start + 1, i - start - 1), start);
        ++i;
        continue;
      }
      case '$':
      case '#': {
        ++i;
        if (c == '#')
          while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
        const std::size_t k = i;
        // Non-ASCII bytes are taken into the keyword so that a look-alike letter
        // ($DАTA with a Cyrillic А) gives "unknown section $DАTA (did you mean 'DATA'?)".
        while (i < s.size() && (detail::is_alpha(s[i]) || static_cast<unsigned char>(s[i]) >= 0x80)) ++i;
        if (i == k)
          throw lang_error(loc_at(start), std::string("expected a ") + (c == '$' ? "section" : "subsection") +
                                              " keyword after '" + c + "'");
        push(c == '$' ? tok::section : tok::subsection, upper(std::string_view(s).substr(k, i - k)), start);
        if (c == '$' && out.back().text == "END") {  // the rest of the file is not read
          out.push_back({tok::eof, {}, loc_at(i)});
          return out;
        }
        continue;
      }
      default:
        break;
    }
    while (i < s.size()) {
      const char d = s[i];
      if (d == ' ' || d == '\t' || d == '\r' || d == '\n' || detail::is_punct(d) || detail::is_control(d)) break;
      if (d == '/' && i + 1 < s.size() && s[i + 1] == '/') break;
      ++i;
    }
    push(tok::word, s.substr(start, i - start), start);
  }
  out.push_back({tok::eof, {}, loc_at(i)});
  return out;
}

/// Whether a word is meant as a number: it starts with a digit or '.', or with
/// a sign followed by a digit or '.'.
inline bool looks_numeric(std::string_view w) {
  if (w.empty()) return false;
  auto digitish = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0 || c == '.'; };
  if (digitish(w[0])) return true;
  return (w[0] == '+' || w[0] == '-') && w.size() > 1 && digitish(w[1]);
}

/// Parses a number: [+-] (digits [. [digits]] | . digits) [(E|e|D|d) [+-] digits].
/// The Fortran exponent letter D is accepted. Returns nothing if the word is
/// not exactly a number or is out of the range of double.
inline std::optional<double> parse_number(std::string_view w) {
  std::string t;
  std::size_t i = 0;
  auto digits = [&] {
    const std::size_t k = i;
    while (i < w.size() && std::isdigit(static_cast<unsigned char>(w[i]))) t += w[i++];
    return i - k;
  };
  if (i < w.size() && (w[i] == '+' || w[i] == '-')) t += w[i++];
  std::size_t n = digits();
  if (i < w.size() && w[i] == '.') {
    t += w[i++];
    n += digits();
  }
  if (n == 0) return std::nullopt;
  if (i < w.size() && (w[i] == 'e' || w[i] == 'E' || w[i] == 'd' || w[i] == 'D')) {
    t += 'e';
    ++i;
    if (i < w.size() && (w[i] == '+' || w[i] == '-')) t += w[i++];
    if (digits() == 0) return std::nullopt;
  }
  if (i != w.size()) return std::nullopt;
  if (t.size() > 400) return std::nullopt;
  char* end = nullptr;
  const double x = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || !(x - x == 0)) return std::nullopt;  // out of range (inf)
  return x;
}

/// Whether a word that parse_number accepted as 0 has a non-zero digit in its
/// mantissa: a number such as 1E-400 that underflows to 0 (an error, not a silent 0).
inline bool underflows(std::string_view w, double x) {
  if (x != 0) return false;
  for (char c : w) {
    if (c == 'e' || c == 'E' || c == 'd' || c == 'D') break;
    if (c >= '1' && c <= '9') return true;
  }
  return false;
}

}  // namespace pradis::lang

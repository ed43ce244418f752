#pragma once
/// \file
/// Source files, locations and the one error type of the model language:
/// `file:line:column: error: message`, with the offending line and a caret.
/// Also the "did you mean" helper (edit distance) used for unknown names.

#include <algorithm>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace pradis::lang {

/// One source text (a model file, an included file or a string under test).
struct source_file {
  std::string name;  ///< file name as shown in messages
  std::string text;  ///< the whole text

  /// Line n (1-based) without its end-of-line characters; empty if out of range.
  /// A line ends at LF, CR LF or a lone CR (old Mac files), as in the lexer.
  std::string_view line(int n) const {
    if (n < 1) return {};
    std::size_t pos = 0;
    for (int k = 1; k < n; ++k) {
      pos = text.find_first_of("\r\n", pos);
      if (pos == std::string::npos) return {};
      pos += (text[pos] == '\r' && pos + 1 < text.size() && text[pos + 1] == '\n') ? 2 : 1;
    }
    std::size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = text.size();
    return std::string_view(text.data() + pos, end - pos);
  }
};

namespace detail {
/// Length of the valid UTF-8 sequence starting at s[i] (1 to 4), or 0 if the
/// byte does not start one.
inline std::size_t utf8_length(std::string_view s, std::size_t i) {
  const auto b = static_cast<unsigned char>(s[i]);
  std::size_t n = b < 0x80 ? 1 : (b >> 5) == 0x6 ? 2 : (b >> 4) == 0xE ? 3 : (b >> 3) == 0x1E ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(s[i + k]) >> 6) != 0x2) return 0;
  return n;
}
}  // namespace detail

/// Text from the input made safe for a message: control bytes and bytes that
/// are not valid UTF-8 become '?', and any run of more than 200 non-blank bytes
/// (a megabyte token, a 100,000-digit number) is cut to its first 60 bytes
/// followed by "...(N bytes)". A message never echoes binary data or a huge
/// token raw.
inline std::string printable(std::string_view s) {
  constexpr std::size_t max_run = 200, keep = 60;
  std::string o;
  std::size_t i = 0;
  while (i < s.size()) {
    if (s[i] == ' ') {
      o += s[i++];
      continue;
    }
    std::size_t e = i;
    while (e < s.size() && s[e] != ' ') ++e;
    const std::size_t run = e - i;
    const std::size_t stop = run > max_run ? i + keep : e;
    while (i < stop) {
      const std::size_t n = detail::utf8_length(s, i);
      const auto b = static_cast<unsigned char>(s[i]);
      if (n == 0 || (n == 1 && (b < 0x20 || b == 0x7f))) {
        o += b == '\t' ? ' ' : '?';
        ++i;
      } else if (i + n > stop) {
        break;  // do not cut a UTF-8 character in two
      } else {
        o.append(s.substr(i, n));
        i += n;
      }
    }
    if (run > max_run) o += "...(" + std::to_string(run) + " bytes)";
    i = e;
  }
  return o;
}

/// A position in a source: file, 1-based line and column (columns count bytes).
struct location {
  std::shared_ptr<const source_file> file;  ///< the source (nullptr: an input without a file)
  int line = 0;                             ///< 1-based line (0: unknown)
  int col = 0;                              ///< 1-based column in bytes

  /// `file:line:column` (or just the file name when the line is unknown).
  std::string str() const {
    std::string s = file ? file->name : std::string("<input>");
    if (line > 0) s += ":" + std::to_string(line) + ":" + std::to_string(col);
    return s;
  }
};

/// An error in a model file or during its run, located in the source.
/// what() is `file:line:column: error: message`; excerpt() adds the line and a caret.
/// The message is passed through printable(): no binary bytes, no huge tokens.
class lang_error : public std::runtime_error {
 public:
  /// The error `message` at `loc`.
  lang_error(location loc, std::string message)
      : std::runtime_error(printable(loc.str()) + ": error: " + printable(message)),
        loc_(std::move(loc)),
        message_(printable(message)) {}

  /// Where the error is.
  const location& where() const noexcept { return loc_; }
  /// The message without the location prefix.
  const std::string& message() const noexcept { return message_; }

  /// The offending source line and a caret under the column (two lines, each
  /// ending in '\n'); control bytes are shown as '?'; empty if the line is unknown.
  std::string excerpt() const {
    if (!loc_.file || loc_.line < 1) return {};
    std::string_view l = loc_.file->line(loc_.line);
    constexpr std::size_t max_width = 160;
    std::size_t from = 0;
    const auto col = static_cast<std::size_t>(std::max(loc_.col, 1));
    if (col > max_width) from = col - max_width / 2;
    l = l.substr(std::min(from, l.size()), max_width);
    // A line with control bytes is binary data: show only printable ASCII.
    bool binary = false;
    for (char c : l) binary = binary || (static_cast<unsigned char>(c) < 0x20 && c != '\t');
    std::string text;
    for (char c : l) {
      const auto u = static_cast<unsigned char>(c);
      text += (u < 0x20 && c != '\t') || u == 0x7f || (binary && u >= 0x80) ? '?' : (c == '\t' ? ' ' : c);
    }
    const std::string num = std::to_string(loc_.line);
    std::string out = " " + num + " | " + text + "\n";
    out += " " + std::string(num.size(), ' ') + " | " + std::string(col - 1 - from, ' ') + "^\n";
    return out;
  }

 private:
  location loc_;
  std::string message_;
};

/// Edit distance (Levenshtein with adjacent transpositions, "optimal string
/// alignment"), case-insensitive for ASCII letters.
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
  auto low = [](char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; };
  const std::size_t w = b.size() + 1;
  std::vector<std::size_t> d((a.size() + 1) * w);
  for (std::size_t j = 0; j <= b.size(); ++j) d[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    d[i * w] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const bool same = low(a[i - 1]) == low(b[j - 1]);
      std::size_t v = std::min({d[(i - 1) * w + j] + 1, d[i * w + j - 1] + 1, d[(i - 1) * w + j - 1] + (same ? 0 : 1)});
      if (i > 1 && j > 1 && low(a[i - 1]) == low(b[j - 2]) && low(a[i - 2]) == low(b[j - 1]))
        v = std::min(v, d[(i - 2) * w + j - 2] + 1);
      d[i * w + j] = v;
    }
  }
  return d[a.size() * w + b.size()];
}

/// The nearest candidate to `word` if it is close enough to be a likely typo
/// (distance at most max(1, length / 3)), else empty.
inline std::string nearest(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t bd = std::string::npos;
  if (word.size() > 200) return best;  // no typo of a catalog name is that long
  // A non-ASCII character (a Cyrillic 'А' that looks like 'A') counts as one
  // wrong character, not as its two to four bytes.
  std::string w;
  for (std::size_t i = 0; i < word.size();) {
    const bool ascii = static_cast<unsigned char>(word[i]) < 0x80;
    const std::size_t n = ascii ? 1 : std::max<std::size_t>(1, detail::utf8_length(word, i));
    w += n == 1 ? word[i] : '\x01';
    i += n;
  }
  word = w;
  for (const auto& c : candidates) {
    if (c.size() > 200) continue;
    const std::size_t d = edit_distance(word, c);
    if (d < bd) {
      bd = d;
      best = c;
    }
  }
  const std::size_t limit = std::max<std::size_t>(1, std::max(word.size(), best.size()) / 3);
  return bd <= limit ? best : std::string{};
}

/// " (did you mean 'X'?)" or "" — for appending to an error message.
inline std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates) {
  const std::string n = nearest(word, candidates);
  return n.empty() ? std::string{} : " (did you mean '" + n + "'?)";
}

/// ASCII upper case.
inline std::string upper(std::string_view s) {
  std::string o(s);
  for (char& c : o)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return o;
}

}  // namespace pradis::lang

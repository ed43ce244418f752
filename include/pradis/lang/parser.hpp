#pragma once
/// \file
/// Parser of the model language: tokens to ast::program (grammar in docs/language.md).
/// $INCLUDE is resolved here (relative to the including file), so the program
/// holds the merged contents of every file; locations keep their own file.

#include <cerrno>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pradis/lang/ast.hpp"
#include "pradis/lang/data_files.hpp"
#include "pradis/lang/lexer.hpp"
#include "pradis/lang/statement_parser.hpp"

namespace pradis::lang {

/// Section keywords, for suggestions.
inline const std::vector<std::string>& section_names() {
  static const std::vector<std::string> v{"DATA",    "FRAGMENT", "RUN",     "PRINT", "REPLACE",
                                          "RESTORE", "SAVE",     "INCLUDE", "END",   "SHOW"};
  return v;
}

/// The recursive-descent parser of one source file: appends its sections to `prog`,
/// parsing each $INCLUDE file with a parser of its own (depth + 1). Use parse_file or
/// parse_string rather than this class directly; errors are lang_error with the
/// file:line:column of the offending text.
class parser : statement_parser {
 public:
  /// Deepest $INCLUDE nesting accepted (an include cycle ends here with an error).
  static constexpr int max_include_depth = 16;

  /// A parser of `src` into `prog`; $INCLUDE files are read with `load`, at nesting `depth`.
  parser(std::shared_ptr<const source_file> src, ast::program& prog, const file_loader& load, int depth = 0)
      : statement_parser(std::move(src)), prog_(prog), load_(load), depth_(depth) {}

  /// Parses the whole source into the program. Returns true if $END was met.
  bool parse() {
    for (;;) {
      skip_newlines();
      if (cur().kind == tok::eof) break;
      const token& t = cur();
      if (t.kind != tok::section) {
        if (t.kind == tok::subsection) fail(t.loc, "subsection #" + t.text + " outside $FRAGMENT");
        fail(t.loc, "expected a section ($DATA, $FRAGMENT, $RUN, ...), found " + describe(t));
      }
      ++p_;
      const std::string& s = t.text;
      if (s == "END") {
        prog_.end = t.loc;
        return true;  // the rest of the file is ignored
      }
      if (s == "DATA")
        data_section(t);
      else if (s == "FRAGMENT")
        fragment_section(t);
      else if (s == "RUN" || s == "PRINT")
        call_section(t, s == "RUN" ? ast::action::kind::run : ast::action::kind::print);
      else if (s == "REPLACE")
        replace_section(t);
      else if (s == "RESTORE" || s == "SAVE")
        path_section(t);
      else if (s == "INCLUDE")
        include_section(t);
      else if (s == "SHOW")
        fail(t.loc, "section $SHOW is not implemented by pradis yet");
      else
        fail(t.loc, "unknown section $" + s + did_you_mean(s, section_names()));
    }
    prog_.end = cur().loc;
    return false;
  }

 private:
  // ---- sections ----------------------------------------------------------------
  void no_actions_yet(const token& t) {
    if (!prog_.actions.empty())
      fail(t.loc, "section $" + t.text +
                      " after $RUN/$PRINT/$REPLACE: the model must be complete before the first "
                      "run (use $REPLACE to change $DATA values between stages)");
  }

  void data_section(const token& t) {
    no_actions_yet(t);
    optional_colon();
    definitions(prog_.data);
  }

  void replace_section(const token& t) {
    optional_colon();
    ast::action a;
    a.what = ast::action::kind::replace;
    a.loc = t.loc;
    definitions(a.definitions);
    if (a.definitions.empty()) fail(t.loc, "$REPLACE without any `Name = values` line");
    prog_.actions.push_back(std::move(a));
  }

  void definitions(std::vector<ast::definition>& out) {
    for (;;) {
      skip_newlines();
      if (at_block_end()) return;
      if (at(tok::subsection)) fail(cur().loc, "subsection #" + cur().text + " outside $FRAGMENT");
      ast::definition d;
      d.loc = cur().loc;
      d.name = words_until(tok::equals, "a name followed by '=' (Name = value, value, ...)");
      if (!name_start(d.name)) fail(d.loc, "a $DATA name must start with a letter: '" + d.name + "'");
      ++p_;  // '='
      for (;;) {
        if (at_statement_end()) fail(cur().loc, "expected a value after '=' or ',', found " + describe(cur()));
        if (at(tok::word) && next().kind == tok::lparen &&
            (upper(cur().text) == "FILE" || upper(cur().text) == "CRAIGBAMPTON"))
          function_values(d.values);
        else
          d.values.push_back(value());
        if (at(tok::comma)) {
          ++p_;
          skip_newlines();  // a trailing comma continues the list on the next line
          continue;
        }
        break;
      }
      end_statement("the value list (separate values with ',')");
      out.push_back(std::move(d));
    }
  }

  /// `FILE("table.csv")` or `CRAIGBAMPTON("k.mtx", "m.mtx", modes, dof, ...)` in a
  /// value list (data_files.hpp): their numbers, each located at the call. Paths
  /// are relative to this model file; errors in a data file point into it.
  void function_values(std::vector<ast::item>& out) {
    const location where = cur().loc;
    const std::string name = upper(cur().text);
    const bool table = name == "FILE";
    const std::size_t nfiles = table ? 1 : 2;
    p_ += 2;  // NAME (
    std::vector<data_file> files;
    std::vector<ast::item> numbers;
    for (;;) {
      if (files.size() < nfiles) {
        if (!at(tok::string))
          fail(cur().loc, name + " needs " + (table ? "a file name" : "two file names") + " in double quotes, " +
                              (table ? "FILE(\"table.csv\")" : "CRAIGBAMPTON(\"k.mtx\", \"m.mtx\", modes, dof, ...)") +
                              ", found " + describe(cur()));
        data_file f;
        f.loc = cur().loc;
        if (cur().text.empty()) fail(f.loc, name + " with an empty file name");
        f.text = *load_relative(cur().text, f.name, f.loc, table ? "table file" : "matrix file");
        ++p_;
        files.push_back(std::move(f));
      } else {
        const ast::item v = value();
        if (v.what != ast::item::kind::number)
          fail(v.loc, name + " takes numbers after its file names, not a $DATA name: '" + v.text + "'");
        numbers.push_back(v);
      }
      if (table || !at(tok::comma)) break;
      ++p_;
      skip_newlines();  // a long DOF list may continue on the next line
    }
    if (!at(tok::rparen))
      fail(cur().loc, std::string("expected ") + (table ? "')' after the file name of FILE" : "',' or ')' in CRAIGBAMPTON") +
                          ", found " + describe(cur()));
    ++p_;
    if (files.size() < nfiles)
      fail(where, "CRAIGBAMPTON needs two matrix files: CRAIGBAMPTON(\"k.mtx\", \"m.mtx\", modes, dof, dof, ...)");
    if (table)
      table_file_items(files[0], where, out);
    else
      craig_bampton_items(files[0], files[1], numbers, where, out);
  }

  void fragment_section(const token& t) {
    no_actions_yet(t);
    ast::fragment f;
    f.loc = t.loc;
    if (at(tok::word)) f.name = upper(words_until_any("the fragment name"));
    optional_colon();
    end_statement("the fragment header");
    for (;;) {
      skip_newlines();
      if (at_block_end()) break;
      if (!at(tok::subsection))
        fail(cur().loc, "expected a subsection (#BASE, #STRUCTURE, #EXTERNAL, #OUTPUT), found " + describe(cur()));
      const token s = cur();
      ++p_;
      optional_colon();
      if (s.text == "STRUCTURE") {
        f.has_structure = true;
        calls(f.structure, true);
      } else if (s.text == "OUTPUT") {
        calls(f.outputs, true);
      } else if (s.text == "BASE") {
        while (!at(tok::subsection) && !at_block_end()) ++p_;  // accepted and ignored (one built-in library)
      } else if (s.text == "EXTERNAL") {
        f.has_external = true;
        f.external_loc = s.loc;
        for (;;) {
          skip_newlines();
          if (at(tok::subsection) || at_block_end()) break;
          if (at(tok::comma)) {
            ++p_;
            continue;
          }
          f.external.push_back(value());
        }
      } else if (s.text == "MAP") {
        fail(s.loc, "subsection #MAP is not implemented by pradis yet");
      } else {
        fail(s.loc, "unknown subsection #" + s.text +
                        did_you_mean(s.text, {"BASE", "STRUCTURE", "EXTERNAL", "OUTPUT", "MAP"}));
      }
    }
    if (!f.has_structure)
      fail(f.loc, "$FRAGMENT" + (f.name.empty() ? std::string() : " " + f.name) + " has no #STRUCTURE subsection");
    prog_.fragments.push_back(std::move(f));
  }

  void call_section(const token& t, ast::action::kind k) {
    optional_colon();
    std::vector<ast::call> cs;
    calls(cs, false);
    if (cs.empty())
      fail(t.loc, "$" + t.text + " lists no program calls (expected `Label '" +
                      (k == ast::action::kind::run ? "SHTERM (END=1)`" : "TABL ()`") + ")");
    for (auto& c : cs) {
      ast::action a;
      a.what = k;
      a.loc = c.loc;
      a.stage = std::move(c);
      prog_.actions.push_back(std::move(a));
    }
  }

  std::string path_argument(const token& t) {
    optional_colon();
    skip_newlines();
    if (!at(tok::string))
      fail(cur().loc, "$" + t.text + " needs a file name in double quotes, found " + describe(cur()));
    std::string path = cur().text;
    ++p_;
    end_statement("the file name");
    if (path.empty()) fail(t.loc, "$" + t.text + " with an empty file name");
    return path;
  }

  void path_section(const token& t) {
    ast::action a;
    a.what = t.text == "SAVE" ? ast::action::kind::save : ast::action::kind::restore;
    a.loc = t.loc;
    a.path = path_argument(t);
    prog_.actions.push_back(std::move(a));
  }

  /// Reads `path` (relative to this source file) through the loader; sets `resolved`.
  /// Fails at `loc` ("cannot read the <what> '<path>'", with the reason) if it cannot.
  std::optional<std::string> load_relative(const std::string& path, std::string& resolved, const location& loc,
                                           const char* what) {
    std::filesystem::path p(path);
    if (p.is_relative()) p = std::filesystem::path(src_->name).parent_path() / p;
    resolved = p.lexically_normal().string();
    std::error_code ec;
    errno = 0;
    std::optional<std::string> text =
        load_ && !std::filesystem::is_directory(resolved, ec) ? load_(resolved) : std::nullopt;
    if (!text)
      fail(loc, std::string("cannot read the ") + what + " '" + resolved + "'" +
                    (std::filesystem::is_directory(resolved, ec) ? ": it is a directory" : os_reason()));
    return text;
  }

  void include_section(const token& t) {
    const std::string path = path_argument(t);
    if (depth_ + 1 > max_include_depth)
      fail(t.loc, "$INCLUDE nested more than " + std::to_string(max_include_depth) +
                      " levels deep (does a file include itself?)");
    std::string resolved;
    std::optional<std::string> text = load_relative(path, resolved, t.loc, "included file");
    auto src = std::make_shared<const source_file>(source_file{resolved, std::move(*text)});
    parser sub(src, prog_, load_, depth_ + 1);
    sub.parse();  // $END in an included file ends that file only
  }

  /// Statements `[Label] 'NAME [(args)]`, one per line, until a (sub)section or EOF.
  void calls(std::vector<ast::call>& out, bool in_fragment) {
    for (;;) {
      skip_newlines();
      if (at_block_end() || (in_fragment && at(tok::subsection))) return;
      if (at(tok::subsection)) fail(cur().loc, "subsection #" + cur().text + " outside $FRAGMENT");
      out.push_back(call());
    }
  }

  ast::program& prog_;
  const file_loader& load_;
  int depth_ = 0;
};

/// Parses a model from a string (`name` is used in messages and to resolve
/// $INCLUDE). Throws lang_error. `load` reads included files (default: from disk).
inline ast::program parse_string(std::string text, std::string name = "<input>", const file_loader& load = read_file) {
  ast::program prog;
  auto src = std::make_shared<const source_file>(source_file{std::move(name), std::move(text)});
  parser p(src, prog, load);
  prog.has_end = p.parse();
  if (!prog.has_end) throw lang_error(prog.end, "missing $END at the end of the file (is the file truncated?)");
  return prog;
}

/// Parses a model file from disk. Throws lang_error (also if it cannot be read).
inline ast::program parse_file(const std::string& path) {
  std::error_code ec;
  const bool dir = std::filesystem::is_directory(path, ec);
  auto text = dir ? std::nullopt : read_file(path);
  if (!text)
    throw lang_error(location{std::make_shared<const source_file>(source_file{path, {}}), 0, 0},
                     dir ? "this is a directory, not a model file" : "cannot read the model file" + os_reason());
  return parse_string(std::move(*text), path);
}

}  // namespace pradis::lang

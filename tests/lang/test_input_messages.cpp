// Messages about odd input: binary bytes and huge tokens are never echoed raw,
// old Mac (CR-only) line endings are lines, read errors give the system's
// reason, numbers that underflow are errors, labels start with a letter or '_',
// and a look-alike non-ASCII letter in a keyword still gets a suggestion.

#include <cerrno>
#include <cstring>
#include <string>

#include "lang_test_support.hpp"

using namespace pradis;
using lang_test::error_of;
using lang_test::small_model;
using lang_test::small_with;

namespace {
/// The lang_error of `text`, whose message and excerpt must be short.
lang::lang_error error_object(const std::string& text) {
  try {
    lang_test::run(text);
  } catch (const lang::lang_error& e) {
    return e;
  }
  FAIL("no error for the text");
  return lang::lang_error({}, "");
}
}  // namespace

TEST_SUITE("lang/input messages") {
  TEST_CASE("a 100,000-digit number gives a short message, the token cut") {
    const auto e = error_object(small_with("Mass = 2", "Mass = " + std::string(100000, '7')));
    CHECK(std::string(e.what()).rfind("test.prd:2:10: error: unparsable number: a word of 100000 characters", 0) ==
          0);
    CHECK(std::string(e.what()).size() < 200);
    CHECK(e.excerpt().size() < 400);  // the source line is shown up to 160 characters
    // A long number in a message of its own is cut with its length.
    const auto f = error_object(small_with("Mass = 2", "Mass = 1" + std::string(300, '0') + "x"));
    CHECK(std::string(f.what()).find("...(304 bytes)") != std::string::npos);
    CHECK(std::string(f.what()).size() < 200);
  }

  TEST_CASE("a megabyte name is cut in the message") {
    const std::string big(1 << 20, 'q');
    const auto e = error_object(small_with("'MASS (1; Mass)", "'MASS (1; " + big + ")"));
    CHECK(std::string(e.what()).find("undefined $DATA name 'qqqq") != std::string::npos);
    CHECK(std::string(e.what()).find("...(" + std::to_string(big.size() + 2) + " bytes)") != std::string::npos);
    CHECK(std::string(e.what()).size() < 300);
  }

  TEST_CASE("bytes that are not UTF-8 are shown as '?' in messages") {
    const auto e = error_object(small_with("'MASS (1", "'MA\xff\xfeSS (1"));
    const std::string w = e.what();
    CHECK(w.find("unknown element model 'MA??SS'") != std::string::npos);
    for (char c : w) CHECK(static_cast<unsigned char>(c) < 0x80);
    CHECK(lang::printable("a\x01\x7f b") == "a?? b");
    CHECK(lang::printable("\xc3\xa9t\xc3") == "\xc3\xa9t?");  // é kept, a cut sequence replaced
  }

  TEST_CASE("CR-only line endings (old Mac files) are lines") {
    std::string mac = small_model;
    for (char& c : mac)
      if (c == '\n') c = '\r';
    CHECK(error_of(mac).empty());
    // An error in such a file is located on its line and shows that line only.
    std::string bad = small_with("'SPRING (0 1", "'SPRNG (0 1");
    for (char& c : bad)
      if (c == '\n') c = '\r';
    const auto e = error_object(bad);
    CHECK(std::string(e.what()).rfind("test.prd:8:11: error: unknown element model 'SPRNG'", 0) == 0);
    CHECK(e.excerpt() == " 8 |   Spring 'SPRNG (0 1; Stiffness)\n   |           ^\n");
  }

  TEST_CASE("a model file that cannot be read: the system's reason") {
    try {
      lang::parse_file("/nonexistent-pradis-dir/model.prd");
      FAIL("no error");
    } catch (const lang::lang_error& e) {
      CHECK(e.message() == std::string("cannot read the model file: ") + std::strerror(ENOENT));
    }
  }

  TEST_CASE("a number that underflows to 0 is an error at the number") {
    CHECK(error_of(small_with("Mass = 2", "Mass = 1E-400"))
              .rfind("test.prd:2:10: error: the number 1E-400 is too small for double precision", 0) == 0);
    CHECK(error_of(small_with("Mass = 2", "Mass = -0.0000001D-399")).find("too small") != std::string::npos);
    // Zero written in any way is zero, and subnormal numbers are numbers.
    CHECK(error_of(small_with("Load = 10", "Load = 0.000E-400")).empty());
    CHECK(lang_test::build(small_with("Load = 10", "Load = 1E-310"))->data("Load").front() == 1e-310);
  }

  TEST_CASE("a label must start with a letter or '_'") {
    CHECK(error_of(small_with("  Body 'MASS", "  1st 'MASS"))
              .rfind("test.prd:7:3: error: a label must start with a letter or '_': '1st'", 0) == 0);
    CHECK(error_of(small_with("  Position 'X", "  2 nd 'X")).find("must start with a letter") != std::string::npos);
    CHECK(error_of(small_with("  Body 'MASS", "  _1st 'MASS")).empty());
  }

  TEST_CASE("a keyword with a look-alike non-ASCII letter is named whole, with the suggestion") {
    // $DАTA with a Cyrillic А (U+0410, bytes D0 90).
    CHECK(error_of(small_with("$DATA", "$D\xd0\x90TA"))
              .rfind("test.prd:1:1: error: unknown section $D\xd0\x90TA (did you mean 'DATA'?)", 0) == 0);
    CHECK(error_of(small_with("'MASS (1", "'M\xd0\x90SS (1")).find("did you mean 'MASS'?") != std::string::npos);
  }
}

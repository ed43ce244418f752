// Replays the fuzzing corpus (fuzz/corpus/) and every input that once crashed
// the fuzzer (fuzz/regressions/, written by scripts/fuzz.sh): each must build
// or be refused with a located lang_error, exactly as fuzz/fuzz_parser.cpp
// requires.

#include <fstream>
#include <sstream>

#include "../../fuzz/fuzz_input.hpp"  // the fuzz targets' $INCLUDE file
#include "lang_test_support.hpp"

TEST_SUITE("lang/fuzz") {
  TEST_CASE("the fuzz corpus and the fuzz regressions build or give a located error") {
    const auto root = lang_test::models_dir().parent_path().parent_path() / "fuzz";
    const pradis::lang::file_loader load = pradis_fuzz::loader();
    int files = 0;
    for (const char* sub : {"corpus", "regressions"}) {
      if (!std::filesystem::exists(root / sub)) continue;
      for (const auto& e : std::filesystem::directory_iterator(root / sub)) {
        if (!e.is_regular_file() || e.path().filename().string().front() == '.') continue;
        std::ifstream f(e.path(), std::ios::binary);
        std::ostringstream os;
        os << f.rdbuf();
        CAPTURE(e.path().string());
        try {
          pradis::lang::session s(pradis::lang::parse_string(os.str(), "fuzz.prd", load));
        } catch (const pradis::lang::lang_error& err) {
          CHECK(std::string(err.what()).rfind("fuzz.prd", 0) == 0);
        }
        ++files;
      }
    }
    CHECK(files >= 5);
  }
}

// pradis-expect: pradis: an element type needs `static constexpr pradis::passport passport = {...};`
//
// Compile-fail test: a type without a passport is not an element.
// Run by tests/build_tests.cmake; this file must NOT compile, and the compiler
// output must contain the text after "pradis-expect:" on the first line.

#include "pradis/core/element.hpp"

struct not_an_element {
  double k = 1.0;
};

static_assert(pradis::check_element<not_an_element>());

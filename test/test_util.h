// SPDX-License-Identifier: LGPL-3.0-or-later
// Minimal checks for the test programs: a failed check prints where and why
// and makes the program exit non-zero (unlike assert(), it survives NDEBUG).
#ifndef CGAL_BLENDED_SHAPE_TEST_UTIL_H
#define CGAL_BLENDED_SHAPE_TEST_UTIL_H

#include <cstdlib>
#include <iostream>
#include <string>

namespace blended_shape_test {
// Sanitizer builds (BLENDED_SHAPE_REDUCED_TESTS, see the top-level
// CMakeLists.txt): the same code paths on fewer cases and points.
#ifdef BLENDED_SHAPE_REDUCED_TESTS
constexpr bool reduced = true;
#else
constexpr bool reduced = false;
#endif
inline int& failures() { static int n = 0; return n; }
// "name: SUCCESS" if no check failed since there were `before` failures.
inline void report(const std::string& name, int before = 0)
{
  std::cout << name << (failures() == before ? ": SUCCESS" : ": FAILED") << std::endl;
}
inline int exit_code() { return failures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE; }
} // namespace blended_shape_test

#define BS_CHECK(cond, what)                                                         \
  do {                                                                               \
    if(!(cond)) {                                                                    \
      ++blended_shape_test::failures();                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #cond " -- "    \
                << what << std::endl;                                                \
    }                                                                                \
  } while(false)

// Checks that `call()` throws an exception of type `Exception` whose message
// contains `expected` (BS_CHECK_REFUSED names the place of the check).
#define BS_CHECK_REFUSED(Exception, call, expected)                                  \
  do {                                                                               \
    const std::string bs_expected_ = (expected);                                     \
    try {                                                                            \
      call;                                                                          \
      BS_CHECK(false, "accepted: expected an error saying \"" << bs_expected_ << "\""); \
    } catch(const Exception& bs_error_) {                                            \
      BS_CHECK(std::string(bs_error_.what()).find(bs_expected_) != std::string::npos, \
               "message \"" << bs_error_.what() << "\" does not say \"" << bs_expected_ << "\""); \
    }                                                                                \
  } while(false)

#endif

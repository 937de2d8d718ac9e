// SPDX-License-Identifier: LGPL-3.0-or-later
// Minimal checks for the test programs: a failed check prints where and why
// and makes the program exit non-zero (unlike assert(), it survives NDEBUG).
#ifndef CGAL_BLENDED_SHAPE_TEST_UTIL_H
#define CGAL_BLENDED_SHAPE_TEST_UTIL_H

#include <cstdlib>
#include <iostream>
#include <string>

namespace blended_shape_test {
inline int& failures() { static int n = 0; return n; }
inline void report(const std::string& name)
{
  std::cout << name << (failures() == 0 ? ": SUCCESS" : ": FAILED") << std::endl;
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

#endif

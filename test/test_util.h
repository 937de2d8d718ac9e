// SPDX-License-Identifier: LGPL-3.0-or-later
// Minimal checks for the test programs: a failed check prints where and why
// and makes the program exit non-zero (unlike assert(), it survives NDEBUG).
#ifndef CGAL_BLENDED_SHAPE_TEST_UTIL_H
#define CGAL_BLENDED_SHAPE_TEST_UTIL_H

#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

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

// A test program made of parts that share one compilation of what they test
// (compiling the package's templates once per program, not once per part, is
// what keeps the build short): `program [all|part]` runs one part, or every
// part in turn; CTest runs each part as its own test (`program_part`). Prints
// "program part: SUCCESS" or "FAILED" per part run; returns the exit code.
struct Test_part
{
  std::string name;
  std::function<void()> run;
};
inline int run_parts(int argc, char** argv, const std::string& program, const std::vector<Test_part>& parts)
{
  const std::string asked = argc > 1 ? argv[1] : "all";
  bool known = asked == "all";
  std::string names = "all";
  for(const auto& part : parts)
  {
    known = known || part.name == asked;
    names += "|" + part.name;
  }
  if(argc > 2 || !known)
  {
    std::cerr << "usage: " << program << " [" << names << "]" << std::endl;
    return EXIT_FAILURE;
  }
  for(const auto& part : parts)
    if(asked == "all" || asked == part.name)
    {
      const int before = failures();
      part.run();
      report(program + " " + part.name, before);
    }
  return exit_code();
}
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

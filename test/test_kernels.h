// SPDX-License-Identifier: LGPL-3.0-or-later
// The kernels the tests run with: `for_each_kernel(f)` calls
// `f(kernel, name)` with a default-constructed Epick, then (except in
// sanitizer builds, BLENDED_SHAPE_ONE_KERNEL, see the top-level
// CMakeLists.txt) Simple_cartesian<double>; `f` is a generic lambda that
// takes the kernel type as `decltype(kernel)`.
#ifndef CGAL_BLENDED_SHAPE_TEST_KERNELS_H
#define CGAL_BLENDED_SHAPE_TEST_KERNELS_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

namespace blended_shape_test {

template <class Function>
void for_each_kernel(const Function& f)
{
  f(CGAL::Exact_predicates_inexact_constructions_kernel(), "Epick");
#ifndef BLENDED_SHAPE_ONE_KERNEL
  f(CGAL::Simple_cartesian<double>(), "Simple_cartesian<double>");
#endif
}

} // namespace blended_shape_test

#endif

// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef BLENDED_SHAPE_TESTING_SAME_BITS_H
#define BLENDED_SHAPE_TESTING_SAME_BITS_H

#include <CGAL/Blended_shape/Fitting/Fitting_visitor.h>

#include <Eigen/Core>

#include <cstring>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace testing {

// Bit-for-bit equality of results that must not depend on how they were
// computed (e.g. on the number of threads): memcmp, stricter than == (which
// takes -0 for 0). For tests.
inline bool same_bits(const double* a, const double* b, std::size_t n)
{
  return n == 0 || std::memcmp(a, b, n * sizeof(double)) == 0;
}
inline bool same_bits(double a, double b) { return same_bits(&a, &b, 1); }
inline bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b)
{
  return a.size() == b.size() && same_bits(a.data(), b.data(), std::size_t(a.size()));
}
inline bool same_bits(const std::vector<double>& a, const std::vector<double>& b)
{
  return a.size() == b.size() && same_bits(a.data(), b.data(), a.size());
}

// A fitting visitor that records the energy after each iteration in `energies`.
struct Energy_recorder : Default_fitting_visitor
{
  explicit Energy_recorder(std::vector<double>& energies, std::vector<std::size_t>* points_used = nullptr)
    : energies(&energies), points_used(points_used)
  {}
  void on_iteration(std::size_t, double energy, std::size_t points) const
  {
    energies->push_back(energy);
    if(points_used != nullptr)
      points_used->push_back(points);
  }
  std::vector<double>* energies; // a pointer: fit_superquadric() copies its visitor
  std::vector<std::size_t>* points_used; // if given, the points each iteration used
};

} // namespace testing
} // namespace Blended_shapes
} // namespace CGAL

#endif // BLENDED_SHAPE_TESTING_SAME_BITS_H

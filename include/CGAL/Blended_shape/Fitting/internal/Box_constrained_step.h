// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_INTERNAL_BOX_CONSTRAINED_STEP_H
#define CGAL_BLENDED_SHAPE_FITTING_INTERNAL_BOX_CONSTRAINED_STEP_H

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// The step of a box trust region: the maximum of the quadratic model
//
//   m(dq) = g^T dq - (1/2) dq^T A dq      (A symmetric positive definite)
//
// over the box low <= dq <= high (low <= 0 <= high componentwise), as
// Deformable_model_fitter's Gauss-Newton step takes it.
struct Box_constrained_step
{
  Eigen::VectorXd delta;   // the step, in the box (unless a solve gave non-finite values)
  bool held = false;       // whether some component ended on a face of the box (the free solution left it)
  int sweeps = 0;          // projected Gauss-Seidel sweeps taken (0 when the free solution is in the box)
  bool converged = true;   // the sweeps stopped because no component moved, not at maximum_sweeps
};

// The quadratic model m(dq) above.
inline double quadratic_model(const Eigen::MatrixXd& A, const Eigen::VectorXd& g, const Eigen::VectorXd& dq)
{
  return g.dot(dq) - 0.5 * dq.dot(A * dq);
}

// Sets the components of `x` that are not `held` to the stationary point
// of m with the held ones where `x` has them: A_FF x_F = g_F - A_FH x_H.
inline void solve_free_components(const Eigen::MatrixXd& A, const Eigen::VectorXd& g, const std::vector<bool>& held,
                                  Eigen::VectorXd& x)
{
  const Eigen::Index n = A.rows();
  std::vector<Eigen::Index> free_indices;
  for(Eigen::Index i = 0; i < n; ++i)
    if(!held[std::size_t(i)])
      free_indices.push_back(i);
  const Eigen::Index m = Eigen::Index(free_indices.size());
  Eigen::MatrixXd A_free(m, m);
  Eigen::VectorXd rhs(m);
  for(Eigen::Index a = 0; a < m; ++a)
  {
    const Eigen::Index i = free_indices[std::size_t(a)];
    rhs[a] = g[i];
    for(Eigen::Index k = 0; k < n; ++k)
      if(held[std::size_t(k)])
        rhs[a] -= A(i, k) * x[k];
    for(Eigen::Index b = 0; b < m; ++b)
      A_free(a, b) = A(i, free_indices[std::size_t(b)]);
  }
  const Eigen::VectorXd x_free = A_free.ldlt().solve(rhs);
  for(Eigen::Index a = 0; a < m; ++a)
    x[free_indices[std::size_t(a)]] = x_free[a];
}

// Projected Gauss-Seidel sweeps on m over the box, from `delta` (in the
// box): each update is the best along one parameter within the box, so m
// only grows, and a component on a face whose force points back into the
// box leaves the face. They stop when no component moves by more than
// 1e-12 of its `scale` (the size of its box), or after `maximum_sweeps`.
inline void maximize_in_box(const Eigen::MatrixXd& A, const Eigen::VectorXd& g, const Eigen::VectorXd& low,
                            const Eigen::VectorXd& high, const Eigen::VectorXd& scale, int maximum_sweeps,
                            Box_constrained_step& step)
{
  Eigen::VectorXd& delta = step.delta;
  step.converged = false;
  for(step.sweeps = 0; step.sweeps < maximum_sweeps;)
  {
    ++step.sweeps;
    double change = 0.;
    for(Eigen::Index i = 0; i < A.rows(); ++i)
    {
      if(!(A(i, i) > 0.))
        continue;
      const double r = g[i] - A.row(i).dot(delta) + A(i, i) * delta[i];
      const double d = (std::min)((std::max)(r / A(i, i), low[i]), high[i]);
      change = (std::max)(change, std::abs(d - delta[i]) / scale[i]);
      delta[i] = d;
    }
    if(change <= 1e-12)
    {
      step.converged = true;
      return;
    }
  }
}

// The maximum of m over the box [low, high]: the free solution A dq = g if
// it lies in the box. Otherwise the components that leave the box are held
// on its face and the others solved again with them, until none leaves (an
// active set: the held set only grows). Clamping the free solution instead
// would keep its other components, which were balanced against the clamped
// ones' full move. Holding several at once can hold one whose force points
// back into the box, and even make a step that does not raise m; projected
// Gauss-Seidel sweeps (maximize_in_box()) then take the step to the maximum
// in the box, from the active set's step if it raises m, else from 0.
// Where A is badly conditioned they converge slowly and stop at
// `maximum_sweeps` short of the maximum, with a step that still raises m
// (reported: Box_constrained_step::converged). Finishing the search exactly
// instead (a primal active-set method after the sweeps; and 1000 sweeps)
// was tried: it moved those steps farther along the directions the points
// hardly constrain, and more split fits of part evolution stalled at their
// start (the mannequin's; one of the real mug's); see the manual.
// `scale[i]` > 0 is the size of component i's box (the sweeps' stopping test).
inline Box_constrained_step solve_in_box(const Eigen::MatrixXd& A, const Eigen::VectorXd& g,
                                         const Eigen::VectorXd& low, const Eigen::VectorXd& high,
                                         const Eigen::VectorXd& scale, int maximum_sweeps = 100)
{
  const Eigen::Index n = A.rows();
  Box_constrained_step step;
  step.delta = A.ldlt().solve(g);
  if(!step.delta.allFinite())
  {
    step.converged = false; // no step: the caller rejects it
    return step;
  }
  Eigen::VectorXd& delta = step.delta;
  std::vector<bool> held(std::size_t(n), false);
  for(;;) // the held set only grows: at most n rounds
  {
    bool more = false;
    for(Eigen::Index i = 0; i < n; ++i)
      if(!held[std::size_t(i)] && (delta[i] < low[i] || delta[i] > high[i]))
      {
        held[std::size_t(i)] = more = true;
        delta[i] = delta[i] < low[i] ? low[i] : high[i];
      }
    if(!more || std::find(held.begin(), held.end(), false) == held.end())
      break;
    solve_free_components(A, g, held, delta);
  }
  step.held = std::find(held.begin(), held.end(), true) != held.end();
  if(!step.held || !delta.allFinite())
    return step; // the free step, inside the box
  if(!(quadratic_model(A, g, delta) > 0.))
    delta.setZero();
  maximize_in_box(A, g, low, high, scale, maximum_sweeps, step);
  return step;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_INTERNAL_BOX_CONSTRAINED_STEP_H

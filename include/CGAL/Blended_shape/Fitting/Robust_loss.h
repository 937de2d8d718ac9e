// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_ROBUST_LOSS_H
#define CGAL_BLENDED_SHAPE_FITTING_ROBUST_LOSS_H

#include <CGAL/Blended_shape/Fitting/Fitting_settings.h>

#include <CGAL/number_utils.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeFitting
/// The scale of the Cauchy weights of points at the distances `distances` to a model:
/// `c = 2.385 * 1.4826 * median(d_i)` (1.4826 median: the standard deviation of
/// Gaussian noise, robustly; 2.385: 95 % efficiency at Gaussian noise), at least `floor`.
inline double cauchy_scale(std::vector<double> distances, double floor)
{
  if(distances.empty())
    return floor;
  const auto middle = distances.begin() + std::ptrdiff_t(distances.size() / 2);
  std::nth_element(distances.begin(), middle, distances.end());
  return (std::max)(2.385 * 1.4826 * *middle, floor);
}

/*!
\ingroup PkgBlendedShapeFitting
The loss `rho(d)` of a point at distance `d` from the model in one step of
the fit, and its weight `w(d) = rho'(d) / (2 d)` (iteratively reweighted
least squares: the step minimizes `(1/2) sum_i w_i r_i^2` at fixed weights),
as chosen by Fitting_settings::robust_weighting:
- `None`: `rho(d) = d^2`, `w = 1`;
- `Cauchy`: `rho(d) = c^2 log(1 + (d / c)^2)`, `w = 1 / (1 + (d / c)^2)`, `c` = cauchy_scale();
- `Mixture`: the points are a mixture of inliers spread over the model's
  surface (area `A`) with Gaussian noise of deviation `sigma` along the
  normal, in proportion `1 - omega`, and strays spread uniformly over a
  volume `V`, in proportion `omega`. With `t = d^2 / (2 sigma^2)` and
  `kappa = omega / (1 - omega) * A sqrt(2 pi) sigma / V` (the ratio of the
  strays' density to the inliers' density on the surface),
  `w(d) = 1 / (1 + kappa e^t)`, the probability that the point is an inlier, and
  `rho(d) = -2 sigma^2 log((e^-t + kappa) / (1 + kappa))`, the negative
  log-likelihood, which is `d^2` near the surface and bounded (`2 sigma^2
  log(1 + 1 / kappa)`) far away, where strays pull no more.
  `sigma` and `omega` are estimated (estimate()) from the distances by
  expectation-maximization, as in EMS (Liu et al., CVPR 2022).
*/
struct Robust_loss
{
  Robust_weighting weighting = Robust_weighting::None; ///< the kind of loss
  double scale = HUGE_VAL;   ///< `c` (Cauchy) or `sigma` (Mixture)
  double stray_density = 0.; ///< `kappa` (Mixture)

  /// `w(d)`.
  double weight(double d) const
  {
    switch(weighting)
    {
    case Robust_weighting::Cauchy: return 1. / (1. + CGAL::square(d / scale));
    case Robust_weighting::Mixture: return 1. / (1. + stray_density * std::exp(exponent(d)));
    default: return 1.;
    }
  }
  /// `rho(d)`.
  double loss(double d) const
  {
    switch(weighting)
    {
    case Robust_weighting::Cauchy: return scale * scale * std::log1p(CGAL::square(d / scale));
    case Robust_weighting::Mixture:
      return -2. * scale * scale * (std::log(std::exp(-exponent(d)) + stray_density) - std::log1p(stray_density));
    default: return d * d;
    }
  }
  /// Whether a point at distance `d` is judged stray: its inlier probability
  /// `w(d)` is below 1/2 (Mixture); `d > 3 c`, where `w(d) < 0.1` (Cauchy); never (None).
  bool is_stray(double d) const
  {
    switch(weighting)
    {
    case Robust_weighting::Cauchy: return d > 3. * scale;
    case Robust_weighting::Mixture: return weight(d) < 0.5;
    default: return false;
    }
  }

  /*!
  The loss of the kind `weighting` for points at distances `distances` from
  a model of surface area `area`, the strays being spread over the volume
  `volume`; scales at least `floor`. Mixture: 20 iterations of
  expectation-maximization from `sigma = 1.4826 median(d_i)` and `omega = 1/2`:
  `w_i = w(d_i)`, `sigma^2 = sum_i w_i d_i^2 / sum_i w_i`, `omega = 1 - mean(w_i)`
  (kept in [1e-12, 0.99]), with `sigma` at most `ceiling`: far from the rest
  state, one broad Gaussian explains inliers and nearby strays alike (the
  likelihood prefers it), and the strays would then pull the model towards them.
  */
  static Robust_loss estimate(Robust_weighting weighting, const std::vector<double>& distances, double area,
                              double volume, double floor, double ceiling)
  {
    Robust_loss r;
    r.weighting = weighting;
    if(weighting == Robust_weighting::None || distances.empty())
      return r;
    r.scale = cauchy_scale(distances, floor);
    if(weighting == Robust_weighting::Cauchy)
      return r;
    r.scale = (std::min)((std::max)(r.scale / 2.385, floor), ceiling);
    double omega = 0.5;
    for(int iteration = 0; iteration < 20; ++iteration)
    {
      r.stray_density = omega / (1. - omega) * area * std::sqrt(2. * CGAL_PI) * r.scale / volume;
      double sum_w = 0., sum_wd2 = 0.;
      for(double d : distances)
      {
        const double w = r.weight(d);
        sum_w += w;
        sum_wd2 += w * d * d;
      }
      if(!(sum_w > 0.))
        break;
      r.scale = (std::min)((std::max)(std::sqrt(sum_wd2 / sum_w), floor), ceiling);
      omega = (std::min)((std::max)(1. - sum_w / double(distances.size()), 1e-12), 0.99);
    }
    r.stray_density = omega / (1. - omega) * area * std::sqrt(2. * CGAL_PI) * r.scale / volume;
    return r;
  }

private:
  double exponent(double d) const { return 0.5 * CGAL::square(d / scale); }
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_ROBUST_LOSS_H

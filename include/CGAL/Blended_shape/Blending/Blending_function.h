// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_BLENDING_FUNCTION_H
#define CGAL_BLENDED_SHAPE_BLENDING_BLENDING_FUNCTION_H

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeBlending

The blending function of a blending region, as a function of the signed strip
coordinate `d` in [-1, 1] (App. A.1):

- the base function, eq. 15, a C1 cubic step of half-width `w`:

      alpha0(d; w) = 0                                for d < -w
                     1                                for d > w
                     (d + w)^2 (2 w - d) / (4 w^3)    otherwise

- the blending function, eq. 4: `alpha = alpha0 (1 - h) + h`, which
  maps the range of `alpha0` from [0, 1] to [h, 1]
  (`h = 1`: only the base shape is expressed).

`w` in [minimum_w, 1] is the "steepness" (the transition covers
`|d| <= w`), `h` in [0, 1] the degree to which the base shape
still covers the discarded part. Both are parameters of the blend
(eq. 28, 29); all derivatives are analytic.

`alpha0` is C1 everywhere (value and slope match at
`d = +-w`) but only C0 in its second derivative there.
*/
class Blending_function
{
public:
  /// \throws std::invalid_argument if `w` is not in [minimum_w, 1] or `h` not in [0, 1].
  explicit Blending_function(double w = 1., double h = 0.)
  {
    set_w(w);
    set_h(h);
  }

  /// The smallest steepness `w` (the paper's range is (0, 1]). A fit can
  /// drive `w` to its bound (a transition as sharp as a cut), so the bound
  /// must evaluate: below about 1e-77, `4 w^4` in the derivatives of eq. 15
  /// is no longer a normal double, and at `w` = DBL_MIN `alpha0(0)` itself is
  /// 0 / 0 (seen as a fit's NaN mesh vertices on a region curve).
  static constexpr double minimum_w = 1e-60;

  /// The steepness `w`.
  double w() const { return m_w; }
  /// The blending parameter `h`.
  double h() const { return m_h; }

  /// \throws std::invalid_argument if `w` is not a finite value in [minimum_w, 1].
  void set_w(double w)
  {
    if(!(w >= minimum_w && w <= 1.))
    {
      std::ostringstream msg;
      msg.precision(17);
      msg << "Blending_function: steepness w = " << w << " is not in [" << minimum_w
          << ", 1]; it is the half-width of the transition in strip units";
      throw std::invalid_argument(msg.str());
    }
    m_w = w;
  }

  /// \throws std::invalid_argument if `h` is not a finite value in [0, 1].
  void set_h(double h)
  {
    if(!(h >= 0. && h <= 1.))
    {
      std::ostringstream msg;
      msg.precision(17);
      msg << "Blending_function: blending parameter h = " << h << " is not in [0, 1]";
      throw std::invalid_argument(msg.str());
    }
    m_h = h;
  }

  /// \name The base function, eq. 15
  /// These static forms do not validate their arguments (they are evaluated
  /// at every model point).
  /// \pre `w >= minimum_w`
  /// @{

  /// `alpha0(d; w)`.
  static double alpha0(double d, double w)
  {
    if(d <= -w)
      return 0.;
    if(d >= w)
      return 1.;
    return (d + w) * (d + w) * (2. * w - d) / (4. * w * w * w);
  }

  /// `d alpha0 / d d = 3 (w^2 - d^2) / (4 w^3)` inside the transition, 0 outside.
  static double alpha0_derivative_d(double d, double w)
  {
    if(d <= -w || d >= w)
      return 0.;
    return 3. * (w * w - d * d) / (4. * w * w * w);
  }

  /// `d alpha0 / d w = -3 d (w^2 - d^2) / (4 w^4)` inside the
  /// transition (`alpha0` depends on `d / w` only), 0 outside.
  static double alpha0_derivative_w(double d, double w)
  {
    if(d <= -w || d >= w)
      return 0.;
    return -3. * d * (w * w - d * d) / (4. * w * w * w * w);
  }
  /// @}

  /// `alpha0(d; w)` with this function's `w`.
  double alpha0(double d) const { return alpha0(d, m_w); }

  /// `alpha(d)`, eq. 4.
  double alpha(double d) const { return alpha0(d, m_w) * (1. - m_h) + m_h; }
  /// `alpha(d)`, eq. 4.
  double operator()(double d) const { return alpha(d); }

  /// `alpha`, `alpha0` and the partial derivatives of `alpha`.
  struct Derivatives
  {
    double alpha;  ///< `alpha(d)`
    double alpha0; ///< `alpha0(d; w)`
    double d_d; ///< `d alpha / d d = (1 - h) d alpha0 / d d`
    double d_w; ///< `d alpha / d w = (1 - h) d alpha0 / d w`
    double d_h; ///< `d alpha / d h = 1 - alpha0`
  };

  /// `alpha`, `alpha0` and the partial derivatives of `alpha` at `d`.
  Derivatives derivatives(double d) const
  {
    Derivatives r;
    r.alpha0 = alpha0(d, m_w);
    r.alpha = r.alpha0 * (1. - m_h) + m_h;
    r.d_d = (1. - m_h) * alpha0_derivative_d(d, m_w);
    r.d_w = (1. - m_h) * alpha0_derivative_w(d, m_w);
    r.d_h = 1. - r.alpha0;
    return r;
  }

private:
  double m_w = 1.;
  double m_h = 0.;
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_BLENDING_FUNCTION_H

// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_PARAMETER_LAYOUT_H
#define CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_PARAMETER_LAYOUT_H

// Where each parameter of a blended shape sits in its parameter vector: the
// root's shape parameters, then for every other component its placement (3 + 4)
// and its shape parameters, then the seven parameters of every blend (eq. 29).

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

class Parameter_layout
{
public:
  /// Number of placement parameters of a non-root component (translation, quaternion).
  static constexpr std::size_t number_of_placement_parameters = 7;

  /// What parameter `i` is: of a blend or of a component (`index`), a
  /// placement parameter or a shape parameter, and its index there (`local`).
  struct Address
  {
    bool is_blend = false, is_placement = false;
    std::size_t index = 0, local = 0;
  };

  /// The layout of components with `shape_sizes[c]` shape parameters each and
  /// `blends` blends of `blend_size` parameters each.
  void reset(const std::vector<std::size_t>& shape_sizes, std::size_t blends, std::size_t blend_size)
  {
    m_component_offset.resize(shape_sizes.size());
    std::size_t o = 0;
    for(std::size_t c = 0; c < shape_sizes.size(); ++c)
    {
      m_component_offset[c] = o;
      o += (c == 0 ? 0 : number_of_placement_parameters) + shape_sizes[c];
    }
    m_blend_offset.resize(blends);
    for(std::size_t b = 0; b < blends; ++b)
    {
      m_blend_offset[b] = o;
      o += blend_size;
    }
    m_size = o;
  }

  /// The dimension of the parameter vector.
  std::size_t size() const { return m_size; }
  /// The index of component `c`'s first parameter (its placement, or for the root its shape).
  std::size_t component_offset(std::size_t c) const { return m_component_offset.at(c); }
  /// The index of component `c`'s first shape parameter.
  std::size_t shape_offset(std::size_t c) const
  {
    return m_component_offset.at(c) + (c == 0 ? 0 : number_of_placement_parameters);
  }
  /// The index of blend `b`'s first parameter.
  std::size_t blend_offset(std::size_t b) const { return m_blend_offset.at(b); }
  /// The index of the first blend parameter: the size if there are no blends.
  std::size_t first_blend_parameter() const { return m_blend_offset.empty() ? m_size : m_blend_offset.front(); }

  /// \throws std::out_of_range if `i` is not below size().
  Address address(std::size_t i) const
  {
    if(i >= m_size)
      throw std::out_of_range("Blended_shape: parameter index " + std::to_string(i) + " out of range");
    // Binary searches over the (increasing) offsets: O(log n) per parameter,
    // so that a layout's addresses cost O(n log n) for large models.
    Address a;
    if(!m_blend_offset.empty() && i >= m_blend_offset.front())
    {
      const auto it = std::upper_bound(m_blend_offset.begin(), m_blend_offset.end(), i) - 1;
      a.is_blend = true;
      a.index = std::size_t(it - m_blend_offset.begin());
      a.local = i - *it;
      return a;
    }
    const auto it = std::upper_bound(m_component_offset.begin(), m_component_offset.end(), i) - 1;
    a.index = std::size_t(it - m_component_offset.begin());
    a.local = i - *it;
    if(a.index != 0)
    {
      if(a.local < number_of_placement_parameters)
        a.is_placement = true;
      else
        a.local -= number_of_placement_parameters;
    }
    return a;
  }

private:
  std::vector<std::size_t> m_component_offset, m_blend_offset;
  std::size_t m_size = 0;
};

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_PARAMETER_LAYOUT_H

// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_INTERNAL_SHARED_CALLBACK_H
#define CGAL_BLENDED_SHAPE_FITTING_INTERNAL_SHARED_CALLBACK_H

#include <functional>
#include <mutex>
#include <utility>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// The abort callback of fits that run concurrently (Point_blocks::for_each_task()):
// function() calls the caller's callback one call at a time, and once it has
// returned false it is not called again and every call returns false, so
// every fit stops at its next iteration. (Not copyable: the fits refer to it.)
class Shared_callback
{
public:
  explicit Shared_callback(std::function<bool(double)> callback) : m_callback(std::move(callback)) {}
  Shared_callback(const Shared_callback&) = delete;
  Shared_callback& operator=(const Shared_callback&) = delete;

  // Empty if the caller's callback is.
  std::function<bool(double)> function()
  {
    if(!m_callback)
      return {};
    return [this](double fraction) {
      const std::lock_guard<std::mutex> lock(m_mutex);
      m_stopped = m_stopped || !m_callback(fraction);
      return !m_stopped;
    };
  }

private:
  std::function<bool(double)> m_callback;
  std::mutex m_mutex;
  bool m_stopped = false;
};

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_INTERNAL_SHARED_CALLBACK_H

// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_INTERNAL_POINT_BLOCKS_H
#define CGAL_BLENDED_SHAPE_FITTING_INTERNAL_POINT_BLOCKS_H

#include <CGAL/config.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/parallel_for.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>
#endif

#include <algorithm>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// The per-point loops of Deformable_model_fitter, cut into blocks of a fixed
// number of points that run in parallel (with TBB, in a task arena of the
// requested number of threads) or one after another (without TBB); and
// a few whole tasks in the same way (for_each_task(): the short fits of
// Superquadric_multistart_search; for_each_task_sharing_threads(): the
// evolution runs of fit_blended_shape()).
// Determinism: a block is the unit of every floating-point sum. Each block
// adds up its own points in order into its own slot, and the slots are added
// in block order afterwards: the association of every sum depends on the
// number of points only, never on the number of threads or on the scheduling,
// so the results are bit-identical at any number of threads.
class Point_blocks
{
public:
  // Small enough for two blocks a core on a few thousand points, large
  // enough that a block's partial normal equations cost little to add.
  static constexpr std::size_t block_size = 256;

  // `number_of_threads`: 0 for all cores.
  explicit Point_blocks(std::size_t number_of_threads = 0)
  {
#ifdef CGAL_LINKED_WITH_TBB
    // Made within a task of for_each_task_sharing_threads(): that task's
    // arena, of the same number of threads.
    if(sharing_threads())
    {
      m_arena = std::make_unique<tbb::task_arena>(tbb::task_arena::attach());
      return;
    }
    // More threads than TBB may run would only make it warn on stderr (and
    // the results are the same at any number): capped at its concurrency.
    const std::size_t available = std::size_t((std::max)(1, tbb::info::default_concurrency()));
    m_arena = std::make_unique<tbb::task_arena>(
      number_of_threads == 0 ? int(tbb::task_arena::automatic) : int((std::min)(number_of_threads, available)));
#else
    (void)number_of_threads;
#endif
  }

  static std::size_t number_of_blocks(std::size_t points) { return (points + block_size - 1) / block_size; }

  // Calls `f(k)` for each point k in [0, points), concurrently across blocks:
  // `f` may only write to slots of its own point.
  template <class F>
  void for_each_point(std::size_t points, const F& f) const
  {
    for_each_block(points, [&](std::size_t, std::size_t first, std::size_t last) {
      for(std::size_t k = first; k < last; ++k)
        f(k);
    });
  }

  // The sum of `f(first, last)` (the partial sum of the points first..last-1,
  // of type T with +=) over the blocks, added in block order to `zero`.
  template <class T, class F>
  T sum_over_blocks(std::size_t points, T zero, const F& f) const
  {
    std::vector<T> partial(number_of_blocks(points));
    for_each_block(points, [&](std::size_t b, std::size_t first, std::size_t last) { partial[b] = f(first, last); });
    for(const T& p : partial)
      zero += p;
    return zero;
  }

  // Calls `f(i)` for each i in [0, tasks), concurrently on the arena's
  // threads (in order on one thread, or without TBB): `f` may only write to
  // slots of its own task. The blocks of points, and a few large tasks such
  // as whole fits.
  // A thread that waits for its tasks to end runs only tasks of this call
  // meanwhile (isolated), never a task it would then wait for in turn.
  template <class F>
  void for_each_task(std::size_t tasks, const F& f) const
  {
#ifdef CGAL_LINKED_WITH_TBB
    if(concurrent(tasks))
    {
      m_arena->execute([&] { tbb::this_task_arena::isolate([&] { tbb::parallel_for(std::size_t(0), tasks, f); }); });
      return;
    }
#endif
    for(std::size_t i = 0; i < tasks; ++i)
      f(i);
  }

  // As for_each_task(), for tasks that are whole fits: the Point_blocks
  // made within a task (its fits') run their blocks on this arena's threads
  // instead of an arena of their own, and a thread whose task has ended
  // takes blocks of the others' instead of waiting for them (it is not
  // isolated: the blocks are tasks of their own, isolated, calls).
  template <class F>
  void for_each_task_sharing_threads(std::size_t tasks, const F& f) const
  {
#ifdef CGAL_LINKED_WITH_TBB
    if(concurrent(tasks))
    {
      m_arena->execute([&] {
        tbb::parallel_for(std::size_t(0), tasks, [&](std::size_t i) {
          struct Sharing // (while f(i) runs on this thread)
          {
            const bool before = std::exchange(sharing_threads(), true);
            ~Sharing() { sharing_threads() = before; }
          } sharing;
          f(i);
        });
      });
      return;
    }
#endif
    for_each_task(tasks, f);
  }

private:
  // Calls `f(b, first, last)` for each block b, of the points first..last-1.
  template <class F>
  void for_each_block(std::size_t points, const F& f) const
  {
    for_each_task(number_of_blocks(points),
                  [&](std::size_t b) { f(b, b * block_size, (std::min)(points, (b + 1) * block_size)); });
  }

#ifdef CGAL_LINKED_WITH_TBB
  bool concurrent(std::size_t tasks) const { return tasks > 1 && m_arena->max_concurrency() > 1; }

  // Whether this thread runs a task of for_each_task_sharing_threads().
  static bool& sharing_threads()
  {
    static thread_local bool sharing = false;
    return sharing;
  }

  std::unique_ptr<tbb::task_arena> m_arena; // a pointer: the fitter stays movable
#endif
};

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_INTERNAL_POINT_BLOCKS_H

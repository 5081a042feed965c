#pragma once
// Work that splits into independent parts (the elements of a mesh, its faces), run on the threads
// a run may use. Each part writes only what it owns, and whatever combines the parts does so in
// their order afterwards, so the result is the same, byte for byte, for any number of threads.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <cstddef>
#include <utility>

namespace curvemesh::base {

// Calls part(i) for every i in [0, n), in parallel where the caller's arena has threads; part(i)
// must write only what part i owns. `grain`: the fewest parts a thread takes at once.
template <class Part>
void for_each_part(std::size_t n, const Part& part, std::size_t grain = 32) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) part(i);
                    });
}

// Calls a() and b(), side by side when `side_by_side` and the caller's arena has threads; a and b
// must write nothing the other reads or writes.
template <class A, class B>
void both(const A& a, const B& b, bool side_by_side = true) {
  if (side_by_side) {
    tbb::parallel_invoke(a, b);
  } else {
    a();
    b();
  }
}

// Runs `work` on at most `threads` threads (0: every hardware thread): what for_each_part inside
// it uses. Returns what `work` returns.
template <class Work>
auto with_threads(int threads, Work&& work) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  return arena.execute(std::forward<Work>(work));
}

}  // namespace curvemesh::base

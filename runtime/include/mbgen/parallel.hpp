// Independent tasks on worker threads: the one way the runtime and the compiler run work in parallel (the starts
// of a fit's global search, Sobol samples, the candidates of a diagnosis round). Results go by index, so they do
// not depend on which thread ran what; progress can be reported in index order (a diagnosis round's candidates
// are fitted two at a time, and their progress lines still come out in the order of the candidate list).
#pragma once

#include <cstddef>
#include <functional>

namespace mbgen {

// Runs task(i) for i = 0..count-1 on `threads` workers (at least one). done(i) is called once per index, in index
// order, as soon as task i and every task before it have finished: one call at a time, on whichever thread
// finished last. If tasks throw, the exception of the lowest index is rethrown after all workers have stopped
// (done() is not called for that index or any after it).
void ordered_parallel(std::size_t count, int threads, const std::function<void(std::size_t)>& task,
                      const std::function<void(std::size_t)>& done);

// Runs task(i) for i = 0..count-1 on `threads` workers (at least one); the exception of the lowest index is
// rethrown after all workers have stopped.
void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& task);

}  // namespace mbgen

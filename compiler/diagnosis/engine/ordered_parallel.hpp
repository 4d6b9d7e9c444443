// Independent tasks on worker threads, reported in index order: the candidates of a diagnosis round are fitted
// two at a time, and their progress lines still come out in the order of the candidate list.
#pragma once

#include <cstddef>
#include <functional>

namespace mbgen::diagnosis {

// Runs task(i) for i = 0..count-1 on `threads` workers (at least one). done(i) is called once per index, in index
// order, as soon as task i and every task before it have finished: one call at a time, on whichever thread
// finished last. If tasks throw, the exception of the lowest index is rethrown after all workers have stopped
// (done() is not called for that index or any after it).
void ordered_parallel(std::size_t count, int threads, const std::function<void(std::size_t)>& task,
                      const std::function<void(std::size_t)>& done);

}  // namespace mbgen::diagnosis

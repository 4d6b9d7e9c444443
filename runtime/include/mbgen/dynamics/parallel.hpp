// Independent tasks on worker threads: the one way the runtime and the compiler run work in parallel (the starts
// of a fit's global search, Sobol samples, the candidates of a diagnosis round). Results go by index, so they do
// not depend on which thread ran what; progress can be reported in index order (a diagnosis round's candidates
// are fitted two at a time, and their progress lines still come out in the order of the candidate list).
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>

namespace mbgen {

// The cores that nested parallel loops share (a diagnosis round's candidates, and within each candidate's fit its
// starts). A loop run on a budget keeps its caller's thread busy and adds a worker whenever a core is free and
// tasks are left; a worker gives its core back when it finds no task, and a caller waiting for its workers lends
// its own. So the core that finished the round's short candidates joins the starts of the long one instead of
// idling. Which thread runs what never changes a result (results go by index).
class ThreadBudget {
 public:
  // `cores` in all, one of them held by the thread that creates the budget.
  explicit ThreadBudget(int cores) : free_(cores > 1 ? cores - 1 : 0) {}
  ThreadBudget(const ThreadBudget&) = delete;
  ThreadBudget& operator=(const ThreadBudget&) = delete;

  // Takes a free core, if there is one.
  bool try_take() {
    int n = free_.load();
    while (n > 0)
      if (free_.compare_exchange_weak(n, n - 1)) return true;
    return false;
  }
  void give_back() { ++free_; }
  // A caller done waiting takes its core back whether or not it is free at that moment: never a wait, at worst one
  // thread too many until the task of whoever borrowed the core meanwhile ends.
  void take_back() { --free_; }
  int free_cores() const { return free_.load(); }

 private:
  std::atomic<int> free_;
};

// Runs task(i) for i = 0..count-1 on `threads` workers (at least one). done(i) is called once per index, in index
// order, as soon as task i and every task before it have finished: one call at a time, on whichever thread
// finished last. If tasks throw, the exception of the lowest index is rethrown after all workers have stopped
// (done() is not called for that index or any after it).
void ordered_parallel(std::size_t count, int threads, const std::function<void(std::size_t)>& task,
                      const std::function<void(std::size_t)>& done);

// The same on the caller's thread and on as many of `cores`' free cores as there are tasks left (ThreadBudget).
void ordered_parallel(std::size_t count, ThreadBudget& cores, const std::function<void(std::size_t)>& task,
                      const std::function<void(std::size_t)>& done);

// Runs produce(i) for i = 0..count-1 in order on the caller's thread, and on `cores`' other cores prepare() once
// and then consume(i) for each i as soon as produce(i) has returned (several at once; by ordered_parallel on the
// budget). Once the production is done, the caller lends its core to the consumers until they finish. For work of
// which one stage must stay on one thread (GiNaC's derivations of a diagnosis round's candidate models, which are
// not thread-safe) and the next may run anywhere (their screening fits): the other cores need not wait for the
// whole first stage. Without a free core (or a thread for it): every produce(i), then prepare() and every
// consume(i), on the caller's thread. A produce() that throws ends the production: no consume() starts for it or
// any later index, and its exception is rethrown once the consumers have stopped; else the exception of prepare()
// or of the lowest failing consume() is.
void consume_while_producing(std::size_t count, ThreadBudget& cores, const std::function<void(std::size_t)>& produce,
                             const std::function<void()>& prepare, const std::function<void(std::size_t)>& consume);

// Runs task(i) for i = 0..count-1 on `threads` workers (at least one); the exception of the lowest index is
// rethrown after all workers have stopped.
void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& task);

}  // namespace mbgen

// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::thread_pool: worker threads that live as long as the pool, for
// hush::exec::parallel(inner, pool). Starting a std::thread costs tens of
// microseconds, as long as a whole small batch (a 512 x 512 Perlin grid takes
// ~90 us on one core), so exec::parallel(inner, threads), which starts its
// threads per call, only pays for large batches; a pool wakes sleeping
// workers instead (docs/performance.md "Threads" has both measured).
//
//   hush::thread_pool pool(4);  // the calling thread plus 3 workers
//   hush::evaluate_grid(noise, hush::exec::parallel(hush::exec::simd, pool), g, out);
//
// Contract:
//  - thread_pool(threads): threads in 0 ... 1024, 0 meaning one per hardware
//    thread (std::thread::hardware_concurrency(), at least 1); else
//    hush::invalid_argument naming `threads`. It starts threads - 1 workers:
//    the thread that calls run() is the first. If the system refuses a
//    thread, the pool keeps the workers it got (size() says how many run).
//  - run(parts, body): calls body(0) ... body(parts - 1), each exactly once,
//    body(0) and any parts beyond size() - 1 workers on the calling thread, and
//    returns when all have returned. body must not throw (hush's batch
//    bodies do not: they run after validation). Calls from several threads
//    are serialised (one batch at a time); a call from inside a body of the
//    same pool runs all its parts on the calling thread instead of waiting
//    for itself.
//  - The destructor wakes and joins the workers; a pool must not be destroyed
//    while a run() is in progress.
//  - The pool is not copyable or movable (workers hold its address).
#ifndef HUSH_THREAD_POOL_HPP
#define HUSH_THREAD_POOL_HPP

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "hush/core/error.hpp"

namespace hush {

class thread_pool {
 public:
  static constexpr int kMaxThreads = 1024;

  explicit thread_pool(int threads = 0) {
    detail::require_in_range("hush::thread_pool", "threads", threads, 0, kMaxThreads,
                             "0 (one per hardware thread) ... 1024");
    const unsigned n =
        threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : unsigned(threads);
    workers_.reserve(n - 1);
    try {
      for (unsigned w = 1; w < n; ++w) workers_.emplace_back([this, w] { work(w); });
    } catch (...) {  // no more threads to be had: the pool runs with those it has
    }
  }
  thread_pool(const thread_pool&) = delete;
  thread_pool& operator=(const thread_pool&) = delete;
  ~thread_pool() {
    {
      const std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
  }

  // Threads that run parts: the workers plus the calling thread.
  unsigned size() const { return unsigned(workers_.size()) + 1; }

  template <class Body>
  void run(std::size_t parts, const Body& body) {
    if (parts == 0) return;
    if (parts == 1 || workers_.empty() || inside_ == this) {
      for (std::size_t p = 0; p < parts; ++p) body(p);
      return;
    }
    const std::lock_guard<std::mutex> batch(run_m_);  // one batch at a time
    const std::size_t on_workers = std::min<std::size_t>(parts - 1, workers_.size());
    {
      const std::lock_guard<std::mutex> lock(m_);
      body_ = [&body](std::size_t p) { body(p); };
      active_ = on_workers;
      pending_ = on_workers;
      ++generation_;
    }
    wake_.notify_all();
    const thread_pool* outer = inside_;
    inside_ = this;
    body(0);
    for (std::size_t p = on_workers + 1; p < parts; ++p) body(p);  // more parts than workers
    inside_ = outer;
    std::unique_lock<std::mutex> lock(m_);
    done_.wait(lock, [this] { return pending_ == 0; });
    body_ = nullptr;
  }

 private:
  // Worker w runs part w of every batch that has at least w + 1 parts.
  void work(unsigned w) {
    inside_ = this;
    std::uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(m_);
    for (;;) {
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      if (w > active_) continue;  // this batch has fewer parts
      lock.unlock();
      body_(w);
      lock.lock();
      if (--pending_ == 0) done_.notify_one();
    }
  }

  std::vector<std::thread> workers_;
  std::mutex run_m_;  // serialises run()
  std::mutex m_;      // guards the fields below
  std::condition_variable wake_, done_;
  std::function<void(std::size_t)> body_;
  std::size_t active_ = 0, pending_ = 0;
  std::uint64_t generation_ = 0;
  bool stop_ = false;
  static inline thread_local const thread_pool* inside_ = nullptr;  // the pool this thread serves
};

}  // namespace hush

#endif  // HUSH_THREAD_POOL_HPP

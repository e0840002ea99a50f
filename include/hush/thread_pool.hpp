// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::thread_pool: worker threads that live as long as the pool, for
// hush::exec::parallel(inner, pool). Starting a std::thread costs tens of
// microseconds, as long as a whole small batch (a 512 x 512 Perlin grid takes
// ~90 us on one core), so exec::parallel(inner, threads), which starts its
// threads per call, only pays for large batches. A pool's workers wait for
// the next batch spinning a few tens of microseconds, then asleep, so batches
// that follow each other closely start at once (docs/performance.md has both
// measured).
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
//    Built without exceptions, std::thread cannot report a refusal but ends
//    the program (the standard library's behaviour, e.g. libstdc++ aborts).
//  - run(parts, body): calls body(0) ... body(parts - 1), each exactly once,
//    on whichever of the pool's threads and the calling thread takes it first
//    (the caller takes parts too, so a worker that is not running delays only
//    the parts it took), and returns when all have returned. body must not throw (hush's batch
//    bodies do not: they run after validation); the pool neither catches nor rethrows: an
//    exception leaving a body on a worker ends the program (std::terminate). Calls from several threads
//    are serialised (one batch at a time); a call from inside a body of the
//    same pool runs all its parts on the calling thread instead of waiting
//    for itself.
//  - The destructor wakes and joins the workers; a pool must not be destroyed
//    while a run() is in progress.
//  - The pool is not copyable or movable (workers hold its address).
#ifndef HUSH_THREAD_POOL_HPP
#define HUSH_THREAD_POOL_HPP

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "hush/core/error.hpp"

#if defined(__x86_64__) || defined(__i386__) || defined(_M_X64) || defined(_M_IX86)
#include <immintrin.h>  // _mm_pause
#endif

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
#if HUSH_CONFIG_CXX_EXCEPTIONS
    try {
      for (unsigned w = 1; w < n; ++w) workers_.emplace_back([this] { work(); });
    } catch (...) {  // no more threads to be had: the pool runs with those it has
    }
#else
    for (unsigned w = 1; w < n; ++w) workers_.emplace_back([this] { work(); });
#endif
  }
  thread_pool(const thread_pool&) = delete;
  thread_pool& operator=(const thread_pool&) = delete;
  ~thread_pool() {
    {
      const std::lock_guard<std::mutex> lock(m_);
      stop_.store(true, std::memory_order_release);
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
    for (std::size_t base = 0; base < parts; base += kMaxParts) {  // a word holds 2^32 - 1
      const std::size_t n = std::min<std::size_t>(parts - base, kMaxParts);
      batch(n, [&body, base](std::size_t p) { body(base + p); });
    }
  }

 private:
  static constexpr std::size_t kMaxParts = 0xffffffffu;
  // Waking a sleeping thread takes a system call and a trip through the
  // scheduler (tens of microseconds on a busy machine); a batch's end and the
  // next batch often come sooner. So waiters first spin for this long, then
  // sleep.
  static constexpr std::chrono::microseconds kSpin{50};

  template <class Body>
  void batch(std::size_t parts, const Body& body) {
    const std::lock_guard<std::mutex> one_batch(run_m_);
    {
      const std::lock_guard<std::mutex> lock(m_);
      body_ = [&body](std::size_t p) { body(p); };
      pending_.store(parts, std::memory_order_relaxed);
      next_.store(std::uint64_t(parts) << 32, std::memory_order_release);  // publishes body_
    }
    wake_.notify_all();
    // The caller takes parts too: a worker that is not running (asleep, or
    // waiting for a core) holds up only the parts it has already taken.
    const thread_pool* outer = inside_;
    inside_ = this;
    run_parts();
    inside_ = outer;
    if (!spin_until([this] { return pending_.load(std::memory_order_acquire) == 0; })) {
      std::unique_lock<std::mutex> lock(m_);
      done_.wait(lock, [this] { return pending_.load(std::memory_order_acquire) == 0; });
    }
    body_ = nullptr;
  }

  // next_ holds the batch's part count (high 32 bits) and the next part to
  // take (low 32 bits): one compare-and-swap takes a part of the batch the
  // word describes, and body_ is that batch's until all its parts returned.
  bool take(std::size_t& part) {
    std::uint64_t w = next_.load(std::memory_order_acquire);
    while ((w & 0xffffffffu) < (w >> 32))
      if (next_.compare_exchange_weak(w, w + 1, std::memory_order_acq_rel,
                                      std::memory_order_acquire)) {
        part = std::size_t(w & 0xffffffffu);
        return true;
      }
    return false;
  }
  bool work_left() const {
    const std::uint64_t w = next_.load(std::memory_order_acquire);
    return (w & 0xffffffffu) < (w >> 32);
  }
  void run_parts() {
    std::size_t p = 0;
    while (take(p)) {
      body_(p);
      if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        const std::lock_guard<std::mutex> lock(m_);  // the caller may be about to sleep
        done_.notify_one();
      }
    }
  }

  static void pause() {
#if defined(__x86_64__) || defined(__i386__) || defined(_M_X64) || defined(_M_IX86)
    _mm_pause();
#elif defined(__aarch64__) || defined(__arm__)
    __asm__ __volatile__("yield");
#endif
  }
  template <class Ready>
  static bool spin_until(const Ready& ready) {
    const auto until = std::chrono::steady_clock::now() + kSpin;
    for (;;) {
      for (int s = 0; s < 64; ++s) {
        if (ready()) return true;
        pause();
      }
      if (std::chrono::steady_clock::now() > until) return ready();
    }
  }

  void work() {
    inside_ = this;
    auto ready = [this] { return stop_.load(std::memory_order_acquire) || work_left(); };
    for (;;) {
      if (!spin_until(ready)) {
        std::unique_lock<std::mutex> lock(m_);
        wake_.wait(lock, ready);
      }
      if (stop_.load(std::memory_order_acquire)) return;
      run_parts();
    }
  }

  std::vector<std::thread> workers_;
  std::mutex run_m_;  // serialises run()
  std::mutex m_;      // with wake_ and done_: sleeping and waking
  std::condition_variable wake_, done_;
  std::function<void(std::size_t)> body_;  // set before next_ is published
  std::atomic<std::uint64_t> next_{0};
  std::atomic<std::size_t> pending_{0};  // parts of the batch not yet returned
  std::atomic<bool> stop_{false};
  static inline thread_local const thread_pool* inside_ = nullptr;  // the pool this thread serves
};

}  // namespace hush

#endif  // HUSH_THREAD_POOL_HPP

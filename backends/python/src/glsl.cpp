// hush's Python module: the process's GL device and the thread it lives on (glsl.hpp).
#include "glsl.hpp"

#include <stdexcept>

#if HUSH_PYTHON_HAVE_GLSL
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include <unistd.h>

#include "hush/glsl/headless.hpp"
#endif

namespace hush_python {

#if HUSH_PYTHON_HAVE_GLSL

namespace {

// One job at a time: the caller holds `calls`, posts the job and waits for `done`.
class gl_thread {
 public:
  gl_thread() : thread_([this] { loop(); }) { thread_.detach(); }

  void run(const std::function<void(hush::glsl::device&)>& job) {
    const std::lock_guard<std::mutex> one_call(calls_);
    std::unique_lock<std::mutex> lock(m_);
    job_ = &job;
    error_ = nullptr;
    done_ = false;
    cv_.notify_all();
    cv_.wait(lock, [this] { return done_; });
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void loop() {
    std::unique_ptr<hush::glsl::headless_device> h;
    std::exception_ptr failed;  // the context could not be made: every call reports it
    try {
      h = std::make_unique<hush::glsl::headless_device>();
    } catch (...) {
      failed = std::current_exception();
    }
    std::unique_lock<std::mutex> lock(m_);
    for (;;) {
      cv_.wait(lock, [this] { return job_ != nullptr; });
      try {
        if (failed) std::rethrow_exception(failed);
        (*job_)(h->device);
      } catch (const std::exception& e) {
        error_ = failed ? std::make_exception_ptr(std::runtime_error(
                              std::string("backend 'glsl': no GL context: ") + e.what()))
                        : std::current_exception();
      } catch (...) {
        error_ = std::current_exception();
      }
      job_ = nullptr;
      done_ = true;
      cv_.notify_all();
    }
  }

  std::mutex calls_, m_;
  std::condition_variable cv_;
  const std::function<void(hush::glsl::device&)>* job_ = nullptr;
  std::exception_ptr error_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace

bool glsl_available() { return true; }

void run_on_glsl_device(const std::function<void(hush::glsl::device&)>& job) {
  // Never destroyed: the thread waits for jobs until the process exits, and the context
  // outlives every call (a device destroyed at exit would race the interpreter's teardown).
  // A child process made by fork() has none of its parent's threads, and the GL library's
  // state (llvmpipe's threads, locks) is not usable there: it gets an error, not a hang.
  static std::mutex m;
  static gl_thread* t = nullptr;
  static pid_t owner = 0;
  gl_thread* mine = nullptr;
  {
    const std::lock_guard<std::mutex> lock(m);
    if (t && owner != getpid())
      throw std::runtime_error(
          "backend 'glsl': the GL device belongs to the parent of this forked process; start "
          "worker processes with multiprocessing's 'spawn' or 'forkserver' method (dask's "
          "default), or make no glsl call before fork()");
    if (!t) {
      t = new gl_thread();  // NOLINT(cppcoreguidelines-owning-memory): see above
      owner = getpid();
    }
    mine = t;
  }
  mine->run(job);
}

#else

bool glsl_available() { return false; }

void run_on_glsl_device(const std::function<void(hush::glsl::device&)>&) {
  throw std::runtime_error(
      "backend 'glsl': this hush module was built without the GL backend (CMake found neither "
      "OSMesa nor EGL: apt-get install libosmesa6-dev or libegl-dev and rebuild)");
}

#endif

std::string glsl_renderer() {
  std::string r;
  run_on_glsl_device([&](hush::glsl::device& d) { r = d.renderer(); });
  return r;
}

}  // namespace hush_python

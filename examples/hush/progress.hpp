// hush — the `hush` program: progress of long work, on stderr.
//
// Short work stays silent: nothing is printed during the first 0.5 s. After that the
// percentage done is shown, rewritten in place (at most 10 times a second) when stderr
// is a terminal, or as one line per 10 % when it is a file or a pipe, so logs stay short.
#ifndef HUSH_CLI_PROGRESS_HPP
#define HUSH_CLI_PROGRESS_HPP

#include <chrono>
#include <cstdint>
#include <string>

namespace hush_cli {

class progress {
 public:
  progress(std::string label, std::uint64_t total);
  // Ends the in-place line, if one was started.
  ~progress();
  progress(const progress&) = delete;
  progress& operator=(const progress&) = delete;

  // `done` of `total` units are finished.
  void update(std::uint64_t done);

 private:
  using clock = std::chrono::steady_clock;
  std::string label_;
  std::uint64_t total_;
  clock::time_point start_ = clock::now();
  clock::time_point last_print_{};
  int last_percent_ = -1;
  bool terminal_;
  bool line_open_ = false;
};

}  // namespace hush_cli

#endif  // HUSH_CLI_PROGRESS_HPP

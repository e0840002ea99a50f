// hush — the `hush` program: progress of long work, on stderr (see progress.hpp).
#include "progress.hpp"

#include <cstdio>
#include <utility>

#if defined(__has_include)
#if __has_include(<unistd.h>)
#include <unistd.h>
#define HUSH_CLI_HAVE_ISATTY 1
#endif
#endif

namespace hush_cli {
namespace {

constexpr std::chrono::milliseconds kQuietTime{500};
constexpr std::chrono::milliseconds kRedrawInterval{100};

bool stderr_is_terminal() {
#if defined(HUSH_CLI_HAVE_ISATTY)
  return isatty(fileno(stderr)) != 0;
#else
  return false;
#endif
}

}  // namespace

progress::progress(std::string label, std::uint64_t total)
    : label_(std::move(label)), total_(total == 0 ? 1 : total), terminal_(stderr_is_terminal()) {}

progress::~progress() {
  if (line_open_) std::fputc('\n', stderr);
}

void progress::update(std::uint64_t done) {
  const clock::time_point now = clock::now();
  if (now - start_ < kQuietTime) return;
  const int percent = static_cast<int>(100 * done / total_);
  if (terminal_) {
    if (percent == last_percent_ || (now - last_print_ < kRedrawInterval && percent != 100)) return;
    std::fprintf(stderr, "\r%s: %3d%%", label_.c_str(), percent);
    line_open_ = true;
  } else {
    if (last_percent_ >= 0 && percent / 10 == last_percent_ / 10) return;
    std::fprintf(stderr, "%s: %d%%\n", label_.c_str(), percent / 10 * 10);
  }
  std::fflush(stderr);
  last_percent_ = percent;
  last_print_ = now;
}

}  // namespace hush_cli

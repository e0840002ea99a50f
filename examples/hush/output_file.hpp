// hush — the `hush` program: an output file that is either completely written or absent.
//
// Opening, writing and closing report failures as run_error naming the path and the
// system's reason. A file that is not closed successfully (an error, an exception
// unwinding past it) is removed, so a failed run never leaves a truncated .npy or .png.
#ifndef HUSH_CLI_OUTPUT_FILE_HPP
#define HUSH_CLI_OUTPUT_FILE_HPP

#include <cstddef>
#include <cstdio>
#include <string>

namespace hush_cli {

class output_file {
 public:
  // Creates or truncates `path` for binary writing; throws run_error when it cannot.
  explicit output_file(std::string path);
  ~output_file();
  output_file(const output_file&) = delete;
  output_file& operator=(const output_file&) = delete;

  void write(const void* data, std::size_t bytes);
  // Flushes and closes; throws run_error (and removes the file) when any write failed.
  void close();
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(const std::string& what);  // run_error: what + strerror(errno)
  std::string path_;
  std::FILE* file_ = nullptr;
};

}  // namespace hush_cli

#endif  // HUSH_CLI_OUTPUT_FILE_HPP

// hush — an output file that is either completely written or absent: what hush_tools::npy::writer
// writes to, and what the hush program writes its other files (PNG, JSON, GLSL) with.
//
// Opening, writing and closing report failures as std::runtime_error naming the path and the
// system's reason. A file that is not closed successfully (an error, an exception unwinding
// past it) is removed, so a failed run never leaves a truncated .npy or .png.
#ifndef HUSH_NPY_OUTPUT_FILE_HPP
#define HUSH_NPY_OUTPUT_FILE_HPP

#include <cstddef>
#include <cstdio>
#include <string>

namespace hush_tools {
namespace npy {

class output_file {
 public:
  // Creates or truncates `path` for binary writing; throws std::runtime_error
  // "cannot open '<path>' for writing: <system reason>" when it cannot.
  explicit output_file(std::string path);
  // Removes the file unless close() succeeded.
  ~output_file();
  output_file(const output_file&) = delete;
  output_file& operator=(const output_file&) = delete;

  // Appends `bytes` bytes; throws std::runtime_error "cannot write '<path>': <reason>" (the
  // file is removed then, or at destruction). Not after close().
  void write(const void* data, std::size_t bytes);
  // Flushes and closes; throws std::runtime_error "cannot write '<path>': <reason>" (and
  // removes the file) when any write failed. Call once.
  void close();
  // Closes and removes the file now (a no-op once closed): for a caller that finds the
  // content wrong before close().
  void discard();
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(const std::string& what);  // discard(), then what + strerror(errno)
  std::string path_;
  std::FILE* file_ = nullptr;
};

}  // namespace npy
}  // namespace hush_tools

#endif  // HUSH_NPY_OUTPUT_FILE_HPP

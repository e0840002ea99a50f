// hush — an output file that is either completely written or absent (see output_file.hpp).
#include "npy/output_file.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace hush_tools {
namespace npy {

output_file::output_file(std::string path) : path_(std::move(path)) {
  file_ = std::fopen(path_.c_str(), "wb");
  if (!file_) fail("cannot open '" + path_ + "' for writing");
}

output_file::~output_file() { discard(); }

void output_file::write(const void* data, std::size_t bytes) {
  if (!file_) errno = EBADF;  // written after close() or a failure
  if (bytes != 0 && (!file_ || std::fwrite(data, 1, bytes, file_) != bytes))
    fail("cannot write '" + path_ + "'");
}

void output_file::close() {
  if (!file_) {
    errno = EBADF;  // closed twice, or after a failure
    fail("cannot write '" + path_ + "'");
  }
  bool ok = std::fflush(file_) == 0 && !std::ferror(file_);
  int error = ok ? 0 : errno;
  if (std::fclose(file_) != 0 && ok) {
    ok = false;
    error = errno;
  }
  file_ = nullptr;
  if (!ok) {
    std::remove(path_.c_str());
    throw std::runtime_error("cannot write '" + path_ + "': " + std::strerror(error));
  }
}

void output_file::discard() {
  if (!file_) return;
  std::fclose(file_);
  file_ = nullptr;
  std::remove(path_.c_str());
}

void output_file::fail(const std::string& what) {
  const int error = errno;  // before discard() may change it
  discard();
  throw std::runtime_error(what + ": " + std::strerror(error));
}

}  // namespace npy
}  // namespace hush_tools

// hush — the `hush` program: an output file that is either completely written or absent.
#include "output_file.hpp"

#include <cerrno>
#include <cstring>

#include "args.hpp"

namespace hush_cli {

output_file::output_file(std::string path) : path_(std::move(path)) {
  file_ = std::fopen(path_.c_str(), "wb");
  if (!file_) fail("cannot open '" + path_ + "' for writing");
}

output_file::~output_file() {
  if (file_) {
    std::fclose(file_);
    std::remove(path_.c_str());
  }
}

void output_file::write(const void* data, std::size_t bytes) {
  if (bytes != 0 && std::fwrite(data, 1, bytes, file_) != bytes)
    fail("cannot write '" + path_ + "'");
}

void output_file::close() {
  bool ok = std::fflush(file_) == 0 && !std::ferror(file_);
  int error = ok ? 0 : errno;
  if (std::fclose(file_) != 0 && ok) {
    ok = false;
    error = errno;
  }
  file_ = nullptr;
  if (!ok) {
    std::remove(path_.c_str());
    throw run_error("cannot write '" + path_ + "': " + std::strerror(error));
  }
}

void output_file::fail(const std::string& what) {
  throw run_error(what + ": " + std::strerror(errno));
}

}  // namespace hush_cli

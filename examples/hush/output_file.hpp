// hush — the `hush` program: an output file that is either completely written or absent.
//
// hush_tools::npy::output_file (examples/npy/output_file.hpp) with the program's error type:
// opening, writing and closing report failures as run_error naming the path and the
// system's reason. A file that is not closed successfully (an error, an exception
// unwinding past it) is removed, so a failed run never leaves a truncated .npy or .png.
#ifndef HUSH_CLI_OUTPUT_FILE_HPP
#define HUSH_CLI_OUTPUT_FILE_HPP

#include <cstddef>
#include <stdexcept>
#include <string>

#include "args.hpp"
#include "npy/output_file.hpp"

namespace hush_cli {

// Runs `io`, a call of hush_tools::npy (files): its failures, std::runtime_error, are run errors
// of the program (exit code 1) with the same message.
template <class Io>
void as_run_error(Io io) {
  try {
    io();
  } catch (const std::runtime_error& e) {
    throw run_error(e.what());
  }
}

class output_file {
 public:
  // Creates or truncates `path` for binary writing; throws run_error when it cannot.
  explicit output_file(std::string path);

  void write(const void* data, std::size_t bytes);
  // Flushes and closes; throws run_error (and removes the file) when any write failed.
  void close();
  const std::string& path() const { return file_.path(); }

 private:
  hush_tools::npy::output_file file_;
};

}  // namespace hush_cli

#endif  // HUSH_CLI_OUTPUT_FILE_HPP

// hush — the `hush` program: an output file that is either completely written or absent.
#include "output_file.hpp"

#include <utility>

namespace hush_cli {

output_file::output_file(std::string path) try : file_(std::move(path)) {
} catch (const std::runtime_error& e) {
  throw run_error(e.what());
}

void output_file::write(const void* data, std::size_t bytes) {
  as_run_error([&] { file_.write(data, bytes); });
}

void output_file::close() {
  as_run_error([&] { file_.close(); });
}

}  // namespace hush_cli

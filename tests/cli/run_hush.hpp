// Running the built `hush` program from a test: the one harness of the suites that test the
// program (tests/cli, tests/scene's scene_cli_test, tests/coherence's cli_coherence_test).
//
// Header only. The including suite's target defines HUSH_CLI_EXE (the path of the built
// program, $<TARGET_FILE:hush_cli>) and HUSH_CLI_SCRATCH (a directory for the suite's scratch
// files, created on demand).
#ifndef HUSH_TESTS_CLI_RUN_HUSH_HPP
#define HUSH_TESTS_CLI_RUN_HUSH_HPP

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#if !defined(HUSH_CLI_EXE) || !defined(HUSH_CLI_SCRATCH)
#error "run_hush.hpp: the suite must define HUSH_CLI_EXE and HUSH_CLI_SCRATCH"
#endif

namespace hush_cli_test {

// What one run of the program did.
struct result {
  int exit_code = -1;  // -1: did not exit normally (a signal, e.g. a sanitizer abort)
  std::string out, err;
};

// The whole of a file's bytes ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// HUSH_CLI_SCRATCH/name, emptied and created: a fresh scratch directory per test case, so that
// test cases may run in parallel.
inline std::filesystem::path scratch(const std::string& name) {
  std::filesystem::path dir = std::filesystem::path(HUSH_CLI_SCRATCH) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Runs `hush <args>` (args as typed in a shell), capturing stdout and stderr in files
// `dir`/stdout.txt and `dir`/stderr.txt.
inline result run_hush(const std::string& args, const std::filesystem::path& dir) {
  const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string command = std::string("'") + HUSH_CLI_EXE + "' " + args + " >'" + out.string() +
                              "' 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  result r;
  if (status != -1 && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

}  // namespace hush_cli_test

#endif  // HUSH_TESTS_CLI_RUN_HUSH_HPP

// hush — the `hush` program: command-line parsing and the program's two kinds of error.
//
// A command's arguments are its positional arguments followed by options written
// "--name value" or "--name=value". Every option takes exactly one value, so a value may
// start with '-' (a negative number, "-3,1") without quoting. Numbers are parsed strictly:
// the whole token must be the number (no trailing text, no spaces, no '+'), and NaN and
// infinities are refused. Every mistake throws usage_error with one line that names the
// option and its valid values.
#ifndef HUSH_CLI_ARGS_HPP
#define HUSH_CLI_ARGS_HPP

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace hush_cli {

// A mistake on the command line: main prints "hush <command>: <message>", exit code 2.
class usage_error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A failure while doing valid work, e.g. an unwritable output file: exit code 1.
class run_error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One option of a command; tables of these drive parsing, error messages and --help.
struct option_spec {
  const char* name;     // "--seed"
  const char* metavar;  // "n", shown in usage
  const char* help;     // what it sets, its valid values and its default
  // The library parameter this option becomes (e.g. "period"), so that a
  // hush::invalid_argument naming that parameter is reported against the option.
  const char* library_param = nullptr;
};

// "<option> '<token>' is invalid; valid: <valid>".
[[noreturn]] void throw_bad_value(const std::string& option, const std::string& token,
                                  const std::string& valid);

// Walks a command's arguments front to back.
class arg_reader {
 public:
  explicit arg_reader(std::vector<std::string> args) : args_(std::move(args)) {}

  bool done() const { return pos_ == args_.size(); }
  // The next argument, which must not be an option; `what` names it in the error.
  std::string positional(const std::string& what, const std::string& valid);
  // The next option, looked up in `options`. Refuses a non-option, an unknown option
  // (listing the valid ones) and an option given twice.
  const option_spec& option(const std::vector<option_spec>& options);
  // The value of the option just returned by option(): its "=value" part or the next
  // argument, which must exist and must not itself be an option ("--x").
  std::string value();

 private:
  std::vector<std::string> args_;
  std::size_t pos_ = 0;
  const option_spec* current_ = nullptr;
  std::string inline_value_;
  bool has_inline_value_ = false;
  std::set<std::string> seen_;
};

// Options as given on the command line: name ("--seed") -> value.
using option_values = std::map<std::string, std::string>;
// The value given for `name`, or nullptr when the option was not given.
const std::string* find_value(const option_values& given, const std::string& name);

// ---- Strict value parsers. `option` and `token` only phrase the error.

// True when the whole of `s` is one integer, respectively one finite double; from_chars
// rules: no leading spaces or '+', and no trailing text, so "7x", " 7" and "" are refused.
bool to_integer(const std::string& s, long long& v);
bool to_finite(const std::string& s, double& v);

// An integer in lo ... hi.
long long parse_integer(const std::string& option, const std::string& token, long long lo,
                        long long hi);
// A finite double; `valid` phrases the error (the caller may check more, e.g. != 0).
double parse_finite(const std::string& option, const std::string& token,
                    const std::string& valid = "a finite number");
// Exactly `count` comma-separated finite doubles.
std::vector<double> parse_finite_list(const std::string& option, const std::string& token,
                                      std::size_t count);
// Exactly `count` comma-separated integers in lo ... hi.
std::vector<long long> parse_integer_list(const std::string& option, const std::string& token,
                                          std::size_t count, long long lo, long long hi);
// `token` split at every `sep` (empty parts kept, so "1,,2" has three parts).
std::vector<std::string> split(const std::string& token, char sep);

// One of a fixed set of words, e.g. --fractal fbm|turbulence.
template <class T>
T parse_choice(const std::string& option, const std::string& token,
               const std::vector<std::pair<const char*, T>>& choices) {
  std::string valid;
  for (const auto& c : choices) {
    if (token == c.first) return c.second;
    valid += (valid.empty() ? "" : ", ") + std::string(c.first);
  }
  throw_bad_value(option, token, valid);
}

}  // namespace hush_cli

#endif  // HUSH_CLI_ARGS_HPP

// hush — the `hush` program: command-line parsing (see args.hpp).
#include "args.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

namespace hush_cli {
namespace {

bool is_option(const std::string& arg) { return arg.size() > 2 && arg.compare(0, 2, "--") == 0; }

std::string range(long long lo, long long hi) {
  return std::to_string(lo) + " ... " + std::to_string(hi);
}

template <class T>
bool parse_whole(const std::string& s, T& v) {
  const char* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, v);
  return !s.empty() && r.ec == std::errc() && r.ptr == end;
}

}  // namespace

bool to_integer(const std::string& s, long long& v) { return parse_whole(s, v); }
bool to_finite(const std::string& s, double& v) { return parse_whole(s, v) && std::isfinite(v); }

void throw_bad_value(const std::string& option, const std::string& token,
                     const std::string& valid) {
  throw usage_error(option + " '" + token + "' is invalid; valid: " + valid);
}

std::string arg_reader::positional(const std::string& what, const std::string& valid) {
  if (done() || is_option(args_[pos_])) throw usage_error("missing " + what + "; valid: " + valid);
  return args_[pos_++];
}

const option_spec& arg_reader::option(const std::vector<option_spec>& options) {
  const std::string& arg = args_[pos_++];
  std::string name = arg;
  has_inline_value_ = false;
  if (is_option(arg)) {
    const std::size_t eq = arg.find('=');
    if (eq != std::string::npos) {
      name = arg.substr(0, eq);
      inline_value_ = arg.substr(eq + 1);
      has_inline_value_ = true;
    }
  }
  std::string valid;
  for (const option_spec& o : options) {
    if (name == o.name) {
      if (!seen_.insert(name).second)
        throw usage_error(name + " is given twice; give each option once");
      current_ = &o;
      return o;
    }
    valid += (valid.empty() ? "" : ", ") + std::string(o.name);
  }
  throw usage_error((is_option(arg) ? "unknown option '" : "unexpected argument '") + name +
                    "'; valid options: " + valid);
}

std::string arg_reader::value() {
  if (has_inline_value_) return inline_value_;
  if (done() || is_option(args_[pos_]))
    throw usage_error(std::string(current_->name) + " needs a value: " + current_->name + " " +
                      current_->metavar + ", " + current_->help);
  return args_[pos_++];
}

const std::string* find_value(const option_values& given, const std::string& name) {
  const auto it = given.find(name);
  return it == given.end() ? nullptr : &it->second;
}

long long parse_integer(const std::string& option, const std::string& token, long long lo,
                        long long hi) {
  long long v = 0;
  if (!parse_whole(token, v) || v < lo || v > hi)
    throw_bad_value(option, token, "an integer in " + range(lo, hi));
  return v;
}

double parse_finite(const std::string& option, const std::string& token, const std::string& valid) {
  double v = 0;
  if (!to_finite(token, v)) throw_bad_value(option, token, valid);
  return v;
}

std::vector<std::string> split(const std::string& token, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = token.find(sep, start);
    parts.push_back(token.substr(start, at - start));
    if (at == std::string::npos) return parts;
    start = at + 1;
  }
}

std::vector<double> parse_finite_list(const std::string& option, const std::string& token,
                                      std::size_t count) {
  const std::string valid = std::to_string(count) + " comma-separated finite numbers";
  const std::vector<std::string> parts = split(token, ',');
  if (parts.size() != count) throw_bad_value(option, token, valid);
  std::vector<double> values(count);
  for (std::size_t a = 0; a < count; ++a)
    if (!to_finite(parts[a], values[a])) throw_bad_value(option, token, valid);
  return values;
}

std::vector<long long> parse_integer_list(const std::string& option, const std::string& token,
                                          std::size_t count, long long lo, long long hi) {
  const std::string valid =
      std::to_string(count) + " comma-separated integers, each in " + range(lo, hi);
  const std::vector<std::string> parts = split(token, ',');
  if (parts.size() != count) throw_bad_value(option, token, valid);
  std::vector<long long> values(count);
  for (std::size_t a = 0; a < count; ++a)
    if (!parse_whole(parts[a], values[a]) || values[a] < lo || values[a] > hi)
      throw_bad_value(option, token, valid);
  return values;
}

}  // namespace hush_cli

// libFuzzer target: the hush program's command-line parsing (examples/hush/args.hpp), which every
// command and every noise option goes through. The input is a command line, its arguments
// separated by NUL bytes; the first byte picks whether a positional argument (the noise) leads.
// It is read against an option table shaped like a command's, then every value goes through
// each strict parser. Properties: every mistake is a usage_error whose message names the option
// and its valid values (nothing else is thrown, nothing crashes or hangs); an option is taken
// once; an accepted number is the whole token (no sign '+', no spaces, no trailing text) and
// finite where finite is asked for; integers stay in their range; lists have their count; split
// keeps every part.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include "args.hpp"

namespace {

using hush_cli::usage_error;

[[noreturn]] void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "hush fuzz_args: %s: '%s'\n", what, detail.c_str());
  std::abort();
}

// Runs f, which must succeed or throw usage_error naming `option` and its valid values.
template <class F>
bool accepted(const std::string& option, F f) {
  try {
    f();
    return true;
  } catch (const usage_error& e) {
    const std::string m = e.what();
    if (m.compare(0, option.size(), option) != 0 || m.find("; valid: ") == std::string::npos)
      fail("a refusal that does not name the option and its valid values", m);
    return false;
  }
}

// What the strict parsers may accept: no leading '+', no white space, no empty token.
bool plain(const std::string& s) {
  if (s.empty() || s[0] == '+') return false;
  for (char c : s)
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') return false;
  return true;
}

void check_number(const std::string& v) {
  long long i = 0;
  if (hush_cli::to_integer(v, i)) {
    if (!plain(v)) fail("to_integer accepted a token with a sign, space or nothing", v);
    long long again = 0;
    if (!hush_cli::to_integer(std::to_string(i), again) || again != i)
      fail("an accepted integer does not print back to itself", v);
  }
  double d = 0;
  if (hush_cli::to_finite(v, d)) {
    if (!std::isfinite(d)) fail("to_finite accepted a non-finite value", v);
    if (!plain(v)) fail("to_finite accepted a token with a sign, space or nothing", v);
  }
  for (const auto& r : {std::pair<long long, long long>{0, 4294967295LL}, {-4, 65536}, {1, 32}}) {
    long long got = 0;
    if (accepted("--n", [&] { got = hush_cli::parse_integer("--n", v, r.first, r.second); }) &&
        (got < r.first || got > r.second || !hush_cli::to_integer(v, i) || i != got))
      fail("parse_integer accepted a value outside its range or not the token's", v);
  }
  double f = 0;
  if (accepted("--x", [&] { f = hush_cli::parse_finite("--x", v); }) &&
      (!hush_cli::to_finite(v, d) || d != f))
    fail("parse_finite accepted what to_finite refuses", v);
}

void check_lists(const std::string& v) {
  const std::vector<std::string> parts = hush_cli::split(v, ',');
  std::string joined;
  for (std::size_t k = 0; k < parts.size(); ++k) joined += (k ? "," : "") + parts[k];
  std::size_t commas = 0;
  for (char c : v) commas += c == ',';
  if (joined != v || parts.size() != commas + 1) fail("split lost or added text", v);
  for (std::size_t count = 1; count <= 3; ++count) {
    std::vector<double> xs;
    if (accepted("--origin", [&] { xs = hush_cli::parse_finite_list("--origin", v, count); })) {
      if (xs.size() != count || parts.size() != count) fail("a list of the wrong count", v);
      for (double x : xs)
        if (!std::isfinite(x)) fail("a non-finite number in a finite list", v);
    }
    std::vector<long long> ns;
    if (accepted("--period", [&] { ns = hush_cli::parse_integer_list("--period", v, count, -4, 65536); })) {
      if (ns.size() != count || parts.size() != count) fail("a list of the wrong count", v);
      for (long long n : ns)
        if (n < -4 || n > 65536) fail("a listed integer outside its range", v);
    }
  }
  int dim = 0;
  if (accepted("--dim", [&] { dim = hush_cli::parse_choice<int>("--dim", v, {{"2", 2}, {"3", 3}}); }) &&
      !((v == "2" && dim == 2) || (v == "3" && dim == 3)))
    fail("parse_choice accepted another word", v);
}

const std::vector<hush_cli::option_spec>& options() {
  static const std::vector<hush_cli::option_spec> o = {
      {"--dim", "2|3", "the dimension"},       {"--size", "N|NxM|NxMxK", "samples per axis"},
      {"--origin", "x,y[,z]", "the origin"},   {"--step", "s", "the spacing"},
      {"--seed", "n", "the seed"},             {"--out", "FILE", "the output"},
      {"--weights", "w,...", "band weights"}, {"--period", "px,py", "the period"}};
  return o;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool noise_first = data[0] & 1;
  std::vector<std::string> args{std::string()};
  for (std::size_t k = 1; k < size; ++k) {
    if (data[k] == 0)
      args.emplace_back();
    else
      args.back().push_back(static_cast<char>(data[k]));
  }
  if (args.size() > 64) return 0;  // a command line, not a file
  std::vector<std::string> values;
  try {
    hush_cli::arg_reader in(args);
    if (noise_first) (void)in.positional("NOISE", "perlin, wavelet, ...");
    std::set<std::string> seen;
    while (!in.done()) {
      const hush_cli::option_spec& o = in.option(options());
      if (!seen.insert(o.name).second) fail("an option taken twice", o.name);
      values.push_back(in.value());
    }
  } catch (const usage_error& e) {
    if (std::string(e.what()).empty()) fail("an empty usage message", "");
  }
  for (const std::string& v : values) {
    check_number(v);
    check_lists(v);
  }
  return 0;
}

// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::invalid_argument: the one exception hush throws, for parameters outside
// their documented domain. Messages name the parameter, the value received and
// the valid range, e.g. "hush::perlin: period[1] = -3 is out of range; valid:
// 0 (not periodic) or 1 ... 16777216". Evaluation itself never throws.
#ifndef HUSH_CORE_ERROR_HPP
#define HUSH_CORE_ERROR_HPP

#include <sstream>
#include <stdexcept>
#include <string>

namespace hush {

class invalid_argument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

namespace detail {

// Builds the standard message: "<where>: <name> = <value> is out of range; valid: <range>".
template <class T>
[[noreturn]] inline void throw_out_of_range(const char* where, const std::string& name,
                                            const T& value, const char* valid) {
  std::ostringstream os;
  os.precision(17);
  os << where << ": " << name << " = " << value << " is out of range; valid: " << valid;
  throw hush::invalid_argument(os.str());
}

// Checks lo <= value <= hi, rejecting NaN (the comparisons are false for NaN).
template <class T>
inline void require_in_range(const char* where, const std::string& name, const T& value,
                             const T& lo, const T& hi, const char* valid) {
  if (!(value >= lo && value <= hi)) throw_out_of_range(where, name, value, valid);
}

}  // namespace detail
}  // namespace hush

#endif  // HUSH_CORE_ERROR_HPP

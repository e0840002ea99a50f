// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// How hush reports errors.
//
// hush::invalid_argument: the one exception hush throws, for parameters outside
// their documented domain. Messages name the parameter, the value received and
// the valid range, e.g. "hush::perlin: period[1] = -3 is out of range; valid:
// 0 (not periodic) or 1 ... 16777216". Evaluation itself never throws. (The GLSL
// backend also throws std::runtime_error when GL fails, hush/glsl/detail/gl.hpp.)
//
// Without exceptions (compiled with -fno-exceptions, or with HUSH_NO_EXCEPTIONS
// defined; hush/config.hpp), every place that would throw calls the error handler
// instead, with the same message:
//  - hush::error_handler: void (*)(const char* message). The message is valid only
//    during the call.
//  - The default handler writes the message and a newline to stderr, then calls
//    std::abort().
//  - hush::set_error_handler(h) installs h for the whole program and returns the
//    handler it replaces; nullptr restores the default. hush::get_error_handler()
//    returns the current one. Both are thread-safe (an atomic), so a handler may
//    be swapped while other threads construct noises.
//  - A handler must not return: it ends the program (std::exit, std::_Exit,
//    std::abort) or leaves by longjmp to a point that abandons the failed call.
//    If it returns anyway, hush calls std::abort(): the code after a failed check
//    assumes the check passed.
// With exceptions on, hush throws and never calls the handler.
#ifndef HUSH_CORE_ERROR_HPP
#define HUSH_CORE_ERROR_HPP

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

#include "hush/config.hpp"

namespace hush {

class invalid_argument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

using error_handler = void (*)(const char* message);

namespace detail {

inline void default_error_handler(const char* message) {
  std::fputs(message, stderr);
  std::fputc('\n', stderr);
  std::abort();
}

// Null means the default; an inline variable, so one slot for the whole program. Constant
// initialised, so a handler set during another object's dynamic initialisation stays set.
inline std::atomic<error_handler> installed_error_handler{nullptr};

}  // namespace detail

// Installs `handler` (nullptr: the default) and returns the one it replaces.
inline error_handler set_error_handler(error_handler handler) noexcept {
  const error_handler previous =
      detail::installed_error_handler.exchange(handler, std::memory_order_acq_rel);
  return previous ? previous : &detail::default_error_handler;
}

// The handler hush calls on an error when it does not throw (never null).
inline error_handler get_error_handler() noexcept {
  const error_handler h = detail::installed_error_handler.load(std::memory_order_acquire);
  return h ? h : &detail::default_error_handler;
}

namespace detail {

// Every error hush reports goes through here: throws E(message) with exceptions on,
// else calls the error handler and aborts should it return. E is hush::invalid_argument
// for parameters; the GLSL backend passes std::runtime_error for GL failures.
template <class E = hush::invalid_argument>
[[noreturn]] inline void raise_error(const std::string& message) {
#if HUSH_CONFIG_EXCEPTIONS
  throw E(message);
#else
  get_error_handler()(message.c_str());
  std::abort();  // the handler returned: nothing after a failed check may run
#endif
}

// Builds the standard message: "<where>: <name> = <value> is out of range; valid: <range>",
// and reports it (raise_error).
template <class T>
[[noreturn]] inline void throw_out_of_range(const char* where, const std::string& name,
                                            const T& value, const char* valid) {
  std::ostringstream os;
  os.precision(17);
  os << where << ": " << name << " = " << value << " is out of range; valid: " << valid;
  raise_error(os.str());
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

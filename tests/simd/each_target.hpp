// Runs a check once per SIMD target the dispatch can pick (each compiled and supported target,
// forced in turn), or once for the static route or a build without SIMD, with the target's
// name in every failure message. Shared by the SIMD suites
// (tests/<noise>/*_simd_test.cpp).
#ifndef HUSH_TESTS_SIMD_EACH_TARGET_HPP
#define HUSH_TESTS_SIMD_EACH_TARGET_HPP

#include <cstdint>
#include <string>
#include <vector>

#include <doctest/doctest.h>

// include/ or single_include/, whichever the suite is built against: HUSH_CONFIG_SIMD*.
#include "hush/hush.hpp"

#if HUSH_CONFIG_SIMD
#include <hwy/targets.h>
#endif

// An unnamed namespace: each suite gets its own copy. With external linkage, the instantiations
// for two suites' lambdas of the same mangled name (a lambda in same-named functions) would be
// merged by the linker and one suite would run the other's check.
namespace {

template <class Check>
void for_each_target(Check check) {
#if HUSH_CONFIG_SIMD_STATIC
  INFO("static target " << hush::simd::chosen_target());
  check();
#elif HUSH_CONFIG_SIMD
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  REQUIRE(!targets.empty());
  for (std::int64_t t : targets) {
    hwy::SetSupportedTargetsForTest(t);
    INFO("target " << std::string(hwy::TargetName(t)));
    check();
  }
  hwy::SetSupportedTargetsForTest(0);
#else
  check();
#endif
}

}  // namespace

#endif  // HUSH_TESTS_SIMD_EACH_TARGET_HPP

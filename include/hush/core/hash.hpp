// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Integer hashing from 32-bit unsigned operations only (multiply, xor, shift,
// all modulo 2^32), so GLSL 330's `uint` arithmetic reproduces every bit. No
// signed arithmetic anywhere: no overflow UB for any input (HARD_CASES row 4).
#ifndef HUSH_CORE_HASH_HPP
#define HUSH_CORE_HASH_HPP

#include <cstdint>

#include "hush/config.hpp"
#include "hush/detail/constants.hpp"

static_assert(sizeof(unsigned) == 4, "hush assumes a 32-bit unsigned int (constants.hpp)");

namespace hush {

// hash32: a bijection on 32-bit words with full avalanche: flipping any input
// bit flips each output bit with probability 1/2, to within 7e-4 at 2^24
// samples (tests/core/hash_test.cpp asserts it at the 2^16-sample noise
// floor). Wellons' lowbias32; constants in detail/constants.hpp.
// hash32_high is hash32 without its last step, x ^= x >> 16, which changes
// only bits 0 ... 15: bits 16 ... 31 of the two are equal. For code that
// reads only the top half (Perlin's gradient index), two operations fewer.
HUSH_INLINE constexpr std::uint32_t hash32_high(std::uint32_t x) {
  namespace c = detail::constants;
  x ^= x >> c::kHashShift1;
  x *= c::kHashMul1;
  x ^= x >> c::kHashShift2;
  x *= c::kHashMul2;
  return x;
}
HUSH_INLINE constexpr std::uint32_t hash32(std::uint32_t x) {
  x = hash32_high(x);
  return x ^ (x >> detail::constants::kHashShift3);
}
static_assert(detail::constants::kHashShift3 >= 16,
              "hash32_high: the last step must spare bits 16+");

// hash32(a, b): hashes an ordered pair; for a fixed a it is a bijection in b
// and vice versa. Used to derive independent seeds (seed, stream) -> key.
HUSH_INLINE constexpr std::uint32_t hash32(std::uint32_t a, std::uint32_t b) {
  return hash32(hash32(a + detail::constants::kGoldenGamma) ^ b);
}

// seed_key: the per-noise-object key all lattice hashes start from. Hashing
// the seed makes nearby seeds (7, 8) give unrelated fields.
HUSH_INLINE constexpr std::uint32_t seed_key(std::uint32_t seed) {
  return hash32(seed + detail::constants::kGoldenGamma);
}

// rotl: rotate left by r in 1 ... 31 (GLSL: (x << r) | (x >> (32 - r))).
HUSH_INLINE constexpr std::uint32_t rotl(std::uint32_t x, unsigned r) {
  return (x << r) | (x >> (32u - r));
}

// The per-axis words lattice_hash folds: the cell index times an odd
// multiplier (a bijection), rotated per axis (constants.hpp says why). Batch
// evaluation precomputes them per column and row (hush/simd).
HUSH_INLINE constexpr std::uint32_t lattice_word_x(std::uint32_t i) {
  return i * detail::constants::kLatticePrimeX;
}
HUSH_INLINE constexpr std::uint32_t lattice_word_y(std::uint32_t j) {
  namespace c = detail::constants;
  return rotl(j * c::kLatticePrimeY, c::kLatticeRotateY);
}
HUSH_INLINE constexpr std::uint32_t lattice_word_z(std::uint32_t k) {
  namespace c = detail::constants;
  return rotl(k * c::kLatticePrimeZ, c::kLatticeRotateZ);
}

// lattice_hash: the hash of an integer lattice cell under a key. Cells are
// 32-bit unsigned (coordinates wrap modulo 2^32; see core/lattice.hpp). The
// cell is folded to one word by xor of the per-axis words above, then
// finished with hash32, so every input bit reaches every output bit.
HUSH_INLINE constexpr std::uint32_t lattice_hash(std::uint32_t key, std::uint32_t i,
                                                 std::uint32_t j) {
  return hash32(key ^ lattice_word_x(i) ^ lattice_word_y(j));
}
HUSH_INLINE constexpr std::uint32_t lattice_hash(std::uint32_t key, std::uint32_t i,
                                                 std::uint32_t j, std::uint32_t k) {
  return hash32(key ^ lattice_word_x(i) ^ lattice_word_y(j) ^ lattice_word_z(k));
}
// lattice_hash_high: lattice_hash in bits 16 ... 31 (hash32_high of the same word).
HUSH_INLINE constexpr std::uint32_t lattice_hash_high(std::uint32_t key, std::uint32_t i,
                                                      std::uint32_t j) {
  return hash32_high(key ^ lattice_word_x(i) ^ lattice_word_y(j));
}
HUSH_INLINE constexpr std::uint32_t lattice_hash_high(std::uint32_t key, std::uint32_t i,
                                                      std::uint32_t j, std::uint32_t k) {
  return hash32_high(key ^ lattice_word_x(i) ^ lattice_word_y(j) ^ lattice_word_z(k));
}

}  // namespace hush

#endif  // HUSH_CORE_HASH_HPP

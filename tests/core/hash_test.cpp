// Tests for hush/core/hash.hpp: avalanche of hash32 and lattice_hash (per cell of the
// input-bit x output-bit flip matrix and over the whole matrix), bijectivity with an explicit
// inverse, golden values, constexpr evaluation, and unsigned-only arithmetic at extreme inputs.
//
// Statistical tolerances are derived from the sample size, never tuned: a flip count over N
// independent samples is Binomial(N, 1/2) for an ideal hash, so its frequency has standard error
// sqrt(0.25 / N); every cell must lie within 5 of those. Over K cells the sum of squared
// z-scores is chi-square with K degrees of freedom (mean K, standard deviation sqrt(2K)), so the
// RMS bias must stay below sqrt(0.25 / N) * sqrt((K + 5 sqrt(2K)) / K), i.e. at the noise floor.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "hush/core/hash.hpp"
#include "test_util.hpp"

namespace {

namespace c = hush::detail::constants;

using hush_test::splitmix64;

// Flip counts: rows are input-bit flips (or input relations), columns the 32 output bits.
struct flip_matrix {
  int rows;
  std::uint64_t samples = 0;  // samples per row
  std::vector<std::uint64_t> count;
  explicit flip_matrix(int r) : rows(r), count(static_cast<std::size_t>(r) * 32u, 0u) {}
  void add(int row, std::uint32_t diff) {
    std::uint64_t* cell = &count[static_cast<std::size_t>(row) * 32u];
    for (unsigned o = 0; o < 32; ++o) cell[o] += (diff >> o) & 1u;
  }
  double p(int row, int out_bit) const {
    return static_cast<double>(count[static_cast<std::size_t>(row) * 32u + out_bit]) /
           static_cast<double>(samples);
  }
};

// Checks output bits [out_lo, 32) of every row: each flip frequency is 1/2 within 5 standard
// errors, and the mean square bias over the K cells is at the noise floor (chi-square bound).
void check_avalanche(const flip_matrix& m, int out_lo, const std::string& what) {
  const double n = static_cast<double>(m.samples);
  const double se = std::sqrt(0.25 / n);  // standard error of a Binomial(n, 1/2) frequency
  double worst = 0.0, sum_sq = 0.0;
  int worst_row = 0, worst_bit = 0;
  for (int r = 0; r < m.rows; ++r) {
    for (int o = out_lo; o < 32; ++o) {
      const double d = m.p(r, o) - 0.5;
      sum_sq += d * d;
      if (std::fabs(d) > worst) worst = std::fabs(d), worst_row = r, worst_bit = o;
    }
  }
  const double k = static_cast<double>(m.rows * (32 - out_lo));
  const double chi2 = sum_sq / (se * se);                  // ~ chi-square(K) for an ideal hash
  const double chi2_bound = k + 5.0 * std::sqrt(2.0 * k);  // mean + 5 standard deviations
  const double rms = std::sqrt(sum_sq / k);
  INFO(what, ": N = ", m.samples, ", output bits ", out_lo, "..31");
  INFO("worst cell: row ", worst_row, ", output bit ", worst_bit, ", |p - 1/2| = ", worst,
       " (5 SE = ", 5.0 * se, ")");
  INFO("RMS bias ", rms, " vs noise floor ", se, "; chi2 ", chi2, " vs bound ", chi2_bound);
  CHECK(worst <= 5.0 * se);
  CHECK(chi2 <= chi2_bound);
  MESSAGE(what, " (bits ", out_lo, "..31): RMS bias ", rms, " / noise floor ", se, " = ", rms / se,
          ", worst |p - 1/2| ", worst, " (5 SE ", 5.0 * se, ")");
}

// Flip statistics of f(words) under flipping each bit of each of the W input words, over n
// random inputs from splitmix64(seed). Row = word * 32 + bit.
template <int W, class F>
flip_matrix flip_each_input_bit(F f, std::uint64_t n, std::uint64_t seed) {
  flip_matrix m(W * 32);
  m.samples = n;
  splitmix64 g{seed};
  std::array<std::uint32_t, W> w{};
  for (std::uint64_t s = 0; s < n; ++s) {
    for (auto& x : w) x = g.next_u32();
    const std::uint32_t h = f(w);
    for (int word = 0; word < W; ++word) {
      for (unsigned b = 0; b < 32; ++b) {
        std::array<std::uint32_t, W> v = w;
        v[word] ^= 1u << b;
        m.add(word * 32 + static_cast<int>(b), h ^ f(v));
      }
    }
  }
  return m;
}

// Samples per avalanche row: 2^16 gives a per-cell 5 SE tolerance of 0.0098.
constexpr std::uint64_t kAvalancheSamples = 1u << 16;

// Inverse of x ^= x >> s on 32 bits: (I + S)^-1 = I + S + S^2 + ... over GF(2).
constexpr std::uint32_t unxorshift(std::uint32_t y, unsigned s) {
  std::uint32_t x = y;
  for (unsigned k = s; k < 32; k += s) x ^= y >> k;
  return x;
}

// Inverse of an odd multiplier modulo 2^32 by Newton's iteration x <- x (2 - m x), which doubles
// the number of correct low bits; x = m is right to 3 bits (m^2 = 1 mod 8), so 4 steps give 48.
constexpr std::uint32_t mul_inverse(std::uint32_t m) {
  std::uint32_t x = m;
  for (int i = 0; i < 4; ++i) x *= 2u - m * x;
  return x;
}
static_assert(c::kHashMul1 * mul_inverse(c::kHashMul1) == 1u, "odd multiplier inverse");
static_assert(c::kHashMul2 * mul_inverse(c::kHashMul2) == 1u, "odd multiplier inverse");

// hash32^-1, undoing lowbias32's five steps in reverse order.
constexpr std::uint32_t hash32_inverse(std::uint32_t y) {
  y = unxorshift(y, c::kHashShift3);
  y *= mul_inverse(c::kHashMul2);
  y = unxorshift(y, c::kHashShift2);
  y *= mul_inverse(c::kHashMul1);
  y = unxorshift(y, c::kHashShift1);
  return y;
}

// An independent reference: lowbias32 and the lattice fold evaluated in 64-bit arithmetic and
// reduced modulo 2^32 by masking (no reliance on 32-bit wraparound).
constexpr std::uint64_t kMask32 = 0xffffffffull;
std::uint32_t ref_hash32(std::uint64_t x) {
  x ^= x >> c::kHashShift1;
  x = (x * c::kHashMul1) & kMask32;
  x ^= x >> c::kHashShift2;
  x = (x * c::kHashMul2) & kMask32;
  x ^= x >> c::kHashShift3;
  return static_cast<std::uint32_t>(x);
}
// Rotation left by r in 1 ... 31 of a 32-bit value held in 64 bits.
std::uint64_t ref_rotl(std::uint64_t x, unsigned r) {
  return ((x << r) | (x >> (32u - r))) & kMask32;
}
std::uint32_t ref_lattice_hash(std::uint64_t key, std::uint64_t i, std::uint64_t j,
                               std::uint64_t k) {
  return ref_hash32(key ^ ((i * c::kLatticePrimeX) & kMask32) ^
                    ref_rotl((j * c::kLatticePrimeY) & kMask32, c::kLatticeRotateY) ^
                    ref_rotl((k * c::kLatticePrimeZ) & kMask32, c::kLatticeRotateZ));
}

// Number of repeated values among 2^log2_size consecutive inputs start, start + 1, ...
// (wrapping at 2^32).
template <class F>
std::size_t collisions_over_window(F f, std::uint32_t start, unsigned log2_size) {
  std::vector<std::uint32_t> h(std::size_t(1) << log2_size);
  for (std::size_t n = 0; n < h.size(); ++n) h[n] = f(start + static_cast<std::uint32_t>(n));
  std::sort(h.begin(), h.end());
  return static_cast<std::size_t>(h.end() - std::unique(h.begin(), h.end()));
}

}  // namespace

TEST_CASE("hash32: flipping any input bit flips each output bit with probability 1/2") {
  const auto m = flip_each_input_bit<1>(
      [](const std::array<std::uint32_t, 1>& w) { return hush::hash32(w[0]); }, kAvalancheSamples,
      1);
  check_avalanche(m, 0, "hash32");
}

TEST_CASE(
    "lattice_hash 2D: flipping any bit of key, i or j flips each output bit with "
    "probability 1/2 (all bits and the top 16 that select gradients)") {
  const auto m = flip_each_input_bit<3>(
      [](const std::array<std::uint32_t, 3>& w) { return hush::lattice_hash(w[0], w[1], w[2]); },
      kAvalancheSamples, 2);
  check_avalanche(m, 0, "lattice_hash(key, i, j)");
  check_avalanche(m, 16, "lattice_hash(key, i, j)");
}

TEST_CASE(
    "lattice_hash 3D: flipping any bit of key, i, j or k flips each output bit with "
    "probability 1/2 (all bits and the top 16 that select gradients)") {
  const auto m = flip_each_input_bit<4>(
      [](const std::array<std::uint32_t, 4>& w) {
        return hush::lattice_hash(w[0], w[1], w[2], w[3]);
      },
      kAvalancheSamples, 3);
  check_avalanche(m, 0, "lattice_hash(key, i, j, k)");
  check_avalanche(m, 16, "lattice_hash(key, i, j, k)");
}

// What noise actually evaluates: small consecutive cells around the origin under seed_key of
// small consecutive seeds. Each output bit of h(cell) ^ h(neighbour) must be set with
// probability 1/2, for the +1 neighbour along every axis and for the next seed.
TEST_CASE(
    "lattice_hash: adjacent cells and adjacent seeds have unrelated hashes (each bit of "
    "h ^ h_neighbour is 1 with probability 1/2)") {
  // 2 seeds x 256^2 cells (2D) and 2 seeds x 32^3 cells (3D): 131072 and 65536 samples.
  constexpr std::uint32_t kSeeds = 2;
  constexpr int kHalf2 = 128, kHalf3 = 16;
  flip_matrix m2(3), m3(4);  // rows: +i, +j, next seed (2D); +i, +j, +k, next seed (3D)
  for (std::uint32_t seed = 0; seed < kSeeds; ++seed) {
    const std::uint32_t key = hush::seed_key(seed), next_key = hush::seed_key(seed + 1);
    for (int a = -kHalf2; a < kHalf2; ++a) {
      for (int b = -kHalf2; b < kHalf2; ++b) {
        const auto i = static_cast<std::uint32_t>(a), j = static_cast<std::uint32_t>(b);
        const std::uint32_t h = hush::lattice_hash(key, i, j);
        m2.add(0, h ^ hush::lattice_hash(key, i + 1u, j));
        m2.add(1, h ^ hush::lattice_hash(key, i, j + 1u));
        m2.add(2, h ^ hush::lattice_hash(next_key, i, j));
      }
    }
    for (int a = -kHalf3; a < kHalf3; ++a) {
      for (int b = -kHalf3; b < kHalf3; ++b) {
        for (int d = -kHalf3; d < kHalf3; ++d) {
          const auto i = static_cast<std::uint32_t>(a), j = static_cast<std::uint32_t>(b),
                     k = static_cast<std::uint32_t>(d);
          const std::uint32_t h = hush::lattice_hash(key, i, j, k);
          m3.add(0, h ^ hush::lattice_hash(key, i + 1u, j, k));
          m3.add(1, h ^ hush::lattice_hash(key, i, j + 1u, k));
          m3.add(2, h ^ hush::lattice_hash(key, i, j, k + 1u));
          m3.add(3, h ^ hush::lattice_hash(next_key, i, j, k));
        }
      }
    }
  }
  m2.samples = kSeeds * (2 * kHalf2) * (2 * kHalf2);
  m3.samples = kSeeds * (2 * kHalf3) * (2 * kHalf3) * (2 * kHalf3);
  check_avalanche(m2, 0, "lattice_hash 2D neighbours");
  check_avalanche(m3, 0, "lattice_hash 3D neighbours");
}

// An xor fold of i*Px and j*Py cancels when two lags flip the same single bit (any odd P maps a
// lag of 2^31 to the top bit alone), which would repeat the field exactly at that lag vector.
// For an ideal hash, h(c) == h(c + lag) has probability 2^-32 per comparison, so over all
// lag vectors with components in {0, 2^0, ..., 2^31} (not all 0) and 16 random cells each
// (575k comparisons in 3D) the expected number of equalities is 1.3e-4: any equality fails.
TEST_CASE("lattice_hash: no lag vector of powers of two repeats the hash") {
  std::vector<std::uint32_t> lags{0u};
  for (unsigned b = 0; b < 32; ++b) lags.push_back(1u << b);
  splitmix64 g{6};
  constexpr int kCells = 16;
  std::array<std::array<std::uint32_t, 4>, kCells> cells{};
  for (auto& cell : cells)
    for (auto& w : cell) w = g.next_u32();
  int equal2 = 0, equal3 = 0;
  for (std::uint32_t di : lags) {
    for (std::uint32_t dj : lags) {
      for (const auto& w : cells) {
        if ((di | dj) != 0u &&
            hush::lattice_hash(w[0], w[1], w[2]) == hush::lattice_hash(w[0], w[1] + di, w[2] + dj))
          ++equal2;
      }
      for (std::uint32_t dk : lags) {
        if ((di | dj | dk) == 0u) continue;
        for (const auto& w : cells) {
          if (hush::lattice_hash(w[0], w[1], w[2], w[3]) ==
              hush::lattice_hash(w[0], w[1] + di, w[2] + dj, w[3] + dk))
            ++equal3;
        }
      }
    }
  }
  CHECK(equal2 == 0);
  CHECK(equal3 == 0);
}

TEST_CASE(
    "hash32: is a bijection (no collisions over 2^20-input windows, and an explicit inverse "
    "round-trips)") {
  const auto h = [](std::uint32_t x) { return hush::hash32(x); };
  CHECK(collisions_over_window(h, 0u, 20) == 0);
  CHECK(collisions_over_window(h, 0xfffe0000u, 18) == 0);  // straddles the wrap to 0
  CHECK(collisions_over_window(h, 0x7ffe0000u, 18) == 0);  // straddles the sign bit

  static_assert(hash32_inverse(hush::hash32(0x12345678u)) == 0x12345678u, "constexpr inverse");
  splitmix64 g{4};
  int failures = 0;
  for (int n = 0; n < 100000; ++n) {
    const std::uint32_t x = g.next_u32();
    if (hash32_inverse(hush::hash32(x)) != x || hush::hash32(hash32_inverse(x)) != x) ++failures;
  }
  CHECK(failures == 0);
}

TEST_CASE(
    "hash32(a, b), seed_key and lattice_hash along one axis are bijections (no collisions "
    "over 2^18-input windows)") {
  CHECK(collisions_over_window([](std::uint32_t b) { return hush::hash32(7u, b); }, 0u, 18) == 0);
  CHECK(collisions_over_window([](std::uint32_t a) { return hush::hash32(a, 7u); }, 0u, 18) == 0);
  CHECK(collisions_over_window([](std::uint32_t s) { return hush::seed_key(s); }, 0xfffe0000u,
                               18) == 0);
  const std::uint32_t key = hush::seed_key(7);
  CHECK(collisions_over_window([&](std::uint32_t i) { return hush::lattice_hash(key, i, 5u); },
                               0xfffe0000u, 18) == 0);
  CHECK(collisions_over_window([&](std::uint32_t j) { return hush::lattice_hash(key, 3u, j); },
                               0xfffe0000u, 18) == 0);
  CHECK(collisions_over_window([&](std::uint32_t k) { return hush::lattice_hash(key, 3u, 5u, k); },
                               0xfffe0000u, 18) == 0);
}

// golden: must never change silently; changing them changes every noise field (and the GLSL
// backend and every stored image and checksum with it). HARD_CASES row 10.
TEST_CASE("hash32, seed_key and lattice_hash: golden values") {
  CHECK(hush::hash32(0u) == 0x00000000u);  // 0 is lowbias32's fixed point
  CHECK(hush::hash32(1u) == 0x688990c0u);
  CHECK(hush::hash32(0x80000000u) == 0xcc4b4124u);
  CHECK(hush::hash32(0xffffffffu) == 0x6768824au);
  CHECK(hush::hash32(7u, 3u) == 0x0795498eu);
  CHECK(hush::seed_key(0u) == 0x01fce552u);
  CHECK(hush::seed_key(7u) == 0x3fd9abdbu);
  // The 2D lattice is the k = 0 slice of the 3D one (k * Pz = 0 adds nothing to the fold).
  CHECK(hush::lattice_hash(hush::seed_key(0u), 0u, 0u) == 0xae6f80f1u);
  CHECK(hush::lattice_hash(hush::seed_key(0u), 0u, 0u, 0u) == 0xae6f80f1u);
  CHECK(hush::lattice_hash(hush::seed_key(7u), 3u, 5u) == 0x4a1a9201u);
  CHECK(hush::lattice_hash(hush::seed_key(7u), 0xffffffffu, 1u, 2u) == 0x2207bec4u);
}

TEST_CASE("hash32, seed_key and lattice_hash: usable in constant expressions") {
  static_assert(hush::hash32(1u) == 0x688990c0u, "hash32 is constexpr");
  static_assert(hush::hash32(7u, 3u) == 0x0795498eu, "hash32(a, b) is constexpr");
  static_assert(hush::seed_key(7u) == 0x3fd9abdbu, "seed_key is constexpr");
  static_assert(hush::lattice_hash(hush::seed_key(7u), 3u, 5u) == 0x4a1a9201u,
                "lattice_hash is constexpr");
  constexpr std::uint32_t h3 = hush::lattice_hash(hush::seed_key(7u), 0xffffffffu, 1u, 2u);
  CHECK(h3 == 0x2207bec4u);
}

// Runs under UBSan in CI (HUSH_SANITIZE): any signed overflow or bad shift at the extremes is
// reported there; here the results must also match a 64-bit masked reference implementation.
TEST_CASE(
    "hash32 and lattice_hash: unsigned arithmetic at extreme inputs matches a 64-bit "
    "reference") {
  const std::uint32_t extremes[] = {0u, 1u, 0x7fffffffu, 0x80000000u, 0xfffffffeu, 0xffffffffu};
  int mismatches = 0;
  for (std::uint32_t a : extremes) {
    if (hush::hash32(a) != ref_hash32(a)) ++mismatches;
    if (hush::seed_key(a) != ref_hash32((a + std::uint64_t{c::kGoldenGamma}) & kMask32))
      ++mismatches;
    for (std::uint32_t b : extremes) {
      const std::uint32_t pair =
          ref_hash32(ref_hash32((a + std::uint64_t{c::kGoldenGamma}) & kMask32) ^ b);
      if (hush::hash32(a, b) != pair) ++mismatches;
      for (std::uint32_t i : extremes) {
        if (hush::lattice_hash(a, b, i) != ref_lattice_hash(a, b, i, 0)) ++mismatches;
        for (std::uint32_t j : extremes)
          if (hush::lattice_hash(a, b, i, j) != ref_lattice_hash(a, b, i, j)) ++mismatches;
      }
    }
  }
  CHECK(mismatches == 0);
}

TEST_CASE("hash32 and lattice_hash: match the 64-bit reference on random inputs") {
  splitmix64 g{5};
  int mismatches = 0;
  for (int n = 0; n < 100000; ++n) {
    const std::uint32_t key = g.next_u32(), i = g.next_u32(), j = g.next_u32(), k = g.next_u32();
    if (hush::hash32(key) != ref_hash32(key)) ++mismatches;
    if (hush::lattice_hash(key, i, j) != ref_lattice_hash(key, i, j, 0)) ++mismatches;
    if (hush::lattice_hash(key, i, j, k) != ref_lattice_hash(key, i, j, k)) ++mismatches;
  }
  CHECK(mismatches == 0);
}

TEST_CASE("hash32_high and lattice_hash_high: the top 16 bits of hash32 and lattice_hash") {
  // What Perlin's gradient index reads (bits 16 ... 31) must not change when
  // the last step is skipped; the low half does change (else the step would
  // be useless and the test could not fail).
  splitmix64 g{6};
  int top_mismatches = 0, low_differs = 0;
  for (int n = 0; n < 100000; ++n) {
    const std::uint32_t key = g.next_u32(), i = g.next_u32(), j = g.next_u32(), k = g.next_u32();
    if ((hush::hash32_high(key) >> 16) != (hush::hash32(key) >> 16)) ++top_mismatches;
    if ((hush::lattice_hash_high(key, i, j) >> 16) != (hush::lattice_hash(key, i, j) >> 16))
      ++top_mismatches;
    if ((hush::lattice_hash_high(key, i, j, k) >> 16) != (hush::lattice_hash(key, i, j, k) >> 16))
      ++top_mismatches;
    if (hush::hash32_high(key) != hush::hash32(key)) ++low_differs;
  }
  CHECK(top_mismatches == 0);
  CHECK(low_differs > 99000);
}

// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The single source of every numeric constant hush's algorithms use: hash
// multipliers, gradient tables, normalisation factors. The scalar path, the
// SIMD kernels and the generated GLSL all read these; no number is typed twice.
// This header includes nothing, so generators can use it without the library.
#ifndef HUSH_DETAIL_CONSTANTS_HPP
#define HUSH_DETAIL_CONSTANTS_HPP

namespace hush {
namespace detail {
namespace constants {

// ---- hash32: Chris Wellons' "lowbias32" integer finalizer (public domain,
// "Prospecting for hash functions", 2018): x ^= x >> 16; x *= M1; x ^= x >> 15;
// x *= M2; x ^= x >> 16. Measured avalanche bias 0.17 (on the scale where 0 is
// ideal), better than MurmurHash3's fmix32; uses only 32-bit unsigned ops, so
// GLSL 330 `uint` arithmetic reproduces it bit for bit.
constexpr unsigned kHashShift1 = 16;
constexpr unsigned kHashMul1 = 0x7feb352dU;
constexpr unsigned kHashShift2 = 15;
constexpr unsigned kHashMul2 = 0x846ca68bU;
constexpr unsigned kHashShift3 = 16;

// ---- Lattice hashing: a cell (i, j, k) is first folded to one word as
// key ^ i*Px ^ rotl(j*Py, Ry) ^ rotl(k*Pz, Rz) (odd multipliers are bijections
// mod 2^32, so each axis alone never collides), then finished with hash32.
// The rotations matter: every odd P maps a lag of 2^31 to a flip of the top
// bit alone, so with a plain xor fold the field repeats exactly at lag
// (2^31, 2^31); and hash32's first step collapses the difference 0x80008000
// to a single top-bit flip, so a rotation of 16 still leaves a correlation of
// 0.56 there. Ry = 11, Rz = 21 (no rotation or difference of rotations is 16)
// keep the gradient correlation at every lag 2^k, k = 0 ... 31, on every
// subset of axes at the sampling noise floor (scan of 4e4 cells per lag;
// tests/perlin/perlin_test.cpp checks the lags of HARD_CASES row 7).
// The multipliers are the 32-bit xxHash primes 1, 2 and 3.
constexpr unsigned kLatticePrimeX = 0x9E3779B1U;
constexpr unsigned kLatticePrimeY = 0x85EBCA77U;
constexpr unsigned kLatticePrimeZ = 0xC2B2AE3DU;
constexpr unsigned kLatticeRotateY = 11;
constexpr unsigned kLatticeRotateZ = 21;

// Stream separation for derived seeds (octaves, RNG streams): added before
// hashing so that seed 0 / stream 0 do not map to the fixed point of hash32(0).
constexpr unsigned kGoldenGamma = 0x9E3779B9U;  // 2^32 / golden ratio

// ---- Improved Perlin noise (Perlin 2002, "Improving Noise").
// Quintic fade s(t) = 6t^5 - 15t^4 + 10t^3 (C2 at the lattice; Perlin 2002 sec. 3).
constexpr double kFade5 = 6.0;
constexpr double kFade4 = -15.0;
constexpr double kFade3 = 10.0;

// 2D gradients: the 8 unit vectors at multiples of 45 degrees, selected by the
// top 3 bits of the lattice hash (exactly uniform). E[g g^T] = I/2.
constexpr double kInvSqrt2 = 0.70710678118654752440;
constexpr int kPerlin2GradCount = 8;
constexpr double kPerlin2GradX[kPerlin2GradCount] = {1.0,  kInvSqrt2,  0.0, -kInvSqrt2,
                                                     -1.0, -kInvSqrt2, 0.0, kInvSqrt2};
constexpr double kPerlin2GradY[kPerlin2GradCount] = {0.0, kInvSqrt2,  1.0,  kInvSqrt2,
                                                     0.0, -kInvSqrt2, -1.0, -kInvSqrt2};
constexpr unsigned kPerlin2GradShift = 29;  // index = hash >> 29

// 3D gradients: Perlin's 12 cube-edge midpoints (length sqrt 2). Perlin 2002
// pads the table to 16 by repeating four, which makes the y axis carry 20% more
// variance; hush instead maps the top 16 hash bits onto 12 buckets,
// index = ((hash >> 16) * 12) >> 16 (bucket sizes differ by 1 in 5461), so
// E[g g^T] = (2/3) I to within 2e-4.
constexpr int kPerlin3GradCount = 12;
constexpr double kPerlin3GradX[kPerlin3GradCount] = {1, -1, 1, -1, 1, -1, 1, -1, 0, 0, 0, 0};
constexpr double kPerlin3GradY[kPerlin3GradCount] = {1, 1, -1, -1, 0, 0, 0, 0, 1, -1, 1, -1};
constexpr double kPerlin3GradZ[kPerlin3GradCount] = {0, 0, 0, 0, 1, 1, -1, -1, 1, 1, -1, -1};
constexpr unsigned kPerlin3IndexShift = 16;

// Output scale. The raw noise sum_i w_i g_i.(x - c_i) is bounded by
// B = max over the cell of sum_i w_i max_g g.(x - c_i) (each corner taking its
// best gradient; some lattice cell realises any assignment, so B is attained).
// 2D, unit gradients: the maximum is at the cell centre, B = sqrt(2)/2.
// 3D, edge gradients: the maximum is NOT at the centre (value 1 there) but at
// (1/2, 0.35526, 0.48149) and its mirror images, B = 1.0363538112118029,
// found by grid search plus refinement and re-derived by
// tests/perlin/perlin_test.cpp on every run. Scaling by 1/B maps the noise onto
// exactly [-1, 1].
constexpr double kPerlin2RawBound = 0.70710678118654752440;  // sqrt(2)/2
constexpr double kPerlin3RawBound = 1.0363538112118029;
constexpr double kPerlin2Scale = 1.0 / kPerlin2RawBound;
constexpr double kPerlin3Scale = 1.0 / kPerlin3RawBound;

// Variance of the raw noise over space and seeds, derived in docs/design.md:
// Var = c * D * (2 I0)^(D-1) * (2 I2) with I0 = int_0^1 (1-s)^2 = 181/462,
// I2 = int_0^1 (1-s)^2 t^2 = 535/18018, c = E[g_k^2] (1/2 in 2D, 2/3 in 3D).
// The output's variance is this times the scale squared.
constexpr double kPerlin2RawVariance = 96835.0 / 2081079.0;       // 0.046531...
constexpr double kPerlin3RawVariance = 35054270.0 / 480729249.0;  // 0.072918...
constexpr double kPerlin2Variance = kPerlin2RawVariance * kPerlin2Scale * kPerlin2Scale;
constexpr double kPerlin3Variance = kPerlin3RawVariance * kPerlin3Scale * kPerlin3Scale;

// ---- Footprints (core/footprint.hpp).
// The widest footprint kept, in noise units: 2^32, the lattice's period
// (core/lattice.hpp). A pixel that wide covers every lattice cell, so
// filtering leaves nothing but the mean; wider, NaN or infinite footprints
// are stored as this one. Squared (2^64) it is still a normal float.
constexpr double kFootprintMaxWidth = 4294967296.0;
// Standard deviation, in pixels, of the Gaussian pixel filter the filtering
// noises apply through the footprint: its amplitude response is
// exp(-2 pi^2 sigma^2 k^2) = 0.29 at the Nyquist frequency (1/2 cycle per
// pixel) and 0.0072 at 1 cycle per pixel.
constexpr double kPixelFilterSigma = 0.5;
// 2 pi / 3: Smith's trigonometric roots of a symmetric 3x3 matrix's characteristic
// cubic (footprint<3>::eigenvalues; the GLSL footprint width of wavelet noise).
constexpr double kTwoPiOver3 = 2.0943951023931954923;

// ---- Poisson sampling (core/rng.hpp).
// Means below kPoissonInversionLimit use sequential inversion (expected
// mean + 1 steps); larger means use Hoermann's PTRS transformed rejection
// ("The transformed rejection method for generating Poisson random
// variables", Insurance: Mathematics and Economics 12, 1993), whose
// acceptance rate exceeds 0.88 for every mean >= 10.
constexpr double kPoissonInversionLimit = 12.0;
constexpr double kPoissonMaxMean = 1e9;                // beyond it, uint32 counts could overflow
constexpr double kPtrsB0 = 0.931, kPtrsB1 = 2.53;      // b = B0 + B1 sqrt(mu)
constexpr double kPtrsA0 = -0.059, kPtrsA1 = 0.02483;  // a = A0 + A1 b
constexpr double kPtrsAlpha0 = 1.1239, kPtrsAlpha1 = 1.1328, kPtrsAlphaB = 3.4;
constexpr double kPtrsVr0 = 0.9277, kPtrsVr1 = 3.6224, kPtrsVrB = 2.0;
constexpr double kPtrsKOffset = 0.43;
constexpr double kPtrsUsAccept = 0.07, kPtrsUsReject = 0.013;
// Stirling's series for ln(n!) = (n + 1/2) ln n - n + ln(2 pi)/2 + sum_k c_k / n^(2k-1),
// c_k = B_2k / (2k (2k - 1)); used for n > kLogFactorialTable, where the
// first omitted term is below 1.1e-15 absolute (2.3e-17 relative) at n = 21.
constexpr double kHalfLog2Pi = 0.91893853320467274178;
constexpr double kStirling[4] = {1.0 / 12.0, -1.0 / 360.0, 1.0 / 1260.0, -1.0 / 1680.0};
constexpr int kLogFactorialTable = 20;

// ---- Wavelet noise (Cook & DeRose 2005; include/hush/wavelet.hpp, wavelet/tile.hpp,
// core/bspline.hpp). The basis is the uniform quadratic B-spline B(u), centred (support
// [-3/2, 3/2]): the density of a sum of three independent uniforms on [-1/2, 1/2]. Every
// kernel of the noise is such a density (core/bspline.hpp derives their polynomial
// pieces from the widths below, so no polynomial coefficient is typed anywhere).
constexpr int kBsplineUniforms = 3;  // B = box * box * box (quadratic B-spline)
// Coefficient i of a band sits at y = i; the three taps of y start at the cell
// floor(y - kWaveletCellOffset), at distances f + kWaveletCellOffset - j (f the fraction).
constexpr double kWaveletCellOffset = 0.5;
// Refinement (Cook & DeRose eq. 10, 13): B(x/2 - 1/4) = sum_k p_k B(x - k), k = -1 ... 2,
// p_k = binom(3, k + 1) / 4: the half-resolution basis in terms of the full-resolution one.
constexpr int kWaveletRefineFirst = -1;
constexpr double kWaveletRefine[4] = {0.25, 0.75, 0.75, 0.25};
// The analysis (least-squares downsampling) filter a_d is infinite; hush keeps
// |d| <= kWaveletAnalysisRadius, where |a_d| < 2e-18 (it decays as 0.656^|d|), and
// periodises it to the tile (wavelet/tile.hpp derives it from the B-spline Gram matrix).
constexpr int kWaveletAnalysisRadius = 100;
// Tile sizes: even (the half-resolution tile must have a whole number of coefficients,
// paper footnote 4) and at least 16 (the widest evaluation kernel spans 9 coefficients;
// the even/odd correction adds a copy shifted by about half a tile, which must lie beyond
// that reach). At most 2^22 coefficients (16 MiB as float; the build holds two double
// copies).
constexpr int kWaveletMinTile = 16;
constexpr int kWaveletMaxTile2 = 2048;
constexpr int kWaveletMaxTile3 = 128;
// The 3D tile's padded rows (wavelet_tile::coefficients, its only layout): every x row
// extended by its first 3 coefficients, so that the taps x0, x0 + 1, x0 + 2 of any
// cell x0 < n and one float more are one unaligned 4-float load, without a wrap.
constexpr int kWaveletRowPad = 3;
// Bands: frequencies 2^b, b in [kWaveletMinBand, kWaveletMaxBand], at most
// kWaveletMaxBands of them in one noise.
constexpr int kWaveletMaxBands = 32;
constexpr int kWaveletMinBand = -32;
constexpr int kWaveletMaxBand = 32;
// Projection onto a surface (paper sec. 3.7, eq. 32): the band is averaged along the
// normal with the B-spline at half its resolution, i.e. stretched by this factor.
constexpr double kWaveletProjectionStretch = 2.0;
// Tile variants (sec. 4.3): a cell's permutation is ((h >> 16) * D!) >> 16 of its hash h
// (uniform to 1 part in 2^16), its reflections the low D bits of h.
constexpr unsigned kWaveletVariantShift = 16;
// Basis widening (paper sec. 4.1): a band whose coefficient spacing spans c pixels is
// widened by s = sqrt(1 + max(0, c^2 - c0^2)) with c0 = kWaveletWidenStart (the paper's
// j = -2), so that from c0 on its variance grows like that of B convolved with the
// pixel filter (hush's Gaussian of sigma = kPixelFilterSigma pixels).
constexpr double kWaveletWidenStart = 0.5;
// Widening stops growing at c = kWaveletWidenEnd pixels, where the band has faded out.
constexpr double kWaveletWidenEnd = 2.0;
// Exact projection along a normal that is not axis-aligned: the line integral is split
// where the integrand's polynomial pieces change and each piece is integrated by
// 5-point Gauss-Legendre quadrature (exact for polynomials of degree <= 9; the
// integrand has degree <= 8). Nodes on [-1, 1] and weights, 20 digits.
constexpr int kGaussLegendreOrder = 5;
// Knots of that line integral: B2's 4, plus per axis a and knot family (at most 4
// with widening) the crossings of 6 |u_a| + 1 planes: at most 4 + 4 (6 sqrt(3) + 3) = 57.
constexpr int kWaveletMaxKnots = 128;
constexpr double kGaussLegendreNode[5] = {-0.90617984593866399280, -0.53846931010568309104, 0.0,
                                          0.53846931010568309104, 0.90617984593866399280};
constexpr double kGaussLegendreWeight[5] = {0.23692688505618908751, 0.47862867049936646804,
                                            0.56888888888888888889, 0.47862867049936646804,
                                            0.23692688505618908751};
// erf(x) on the GPU (GLSL has no erf): Abramowitz & Stegun 7.1.26,
// erf(x) = 1 - (a1 t + ... + a5 t^5) exp(-x^2), t = 1 / (1 + p x), x >= 0; |error| <= 1.5e-7.
constexpr double kErfP = 0.3275911;
constexpr double kErfA[5] = {0.254829592, -0.284496736, 1.421413741, -1.453152027, 1.061405429};
constexpr double kInvSqrt2Pi = 0.39894228040143267794;  // 1 / sqrt(2 pi): the normal density
// ---- Coherent noise (Kass & Pesare 2011, "Coherent Noise for Non-Photorealistic
// Rendering"; include/hush/coherent.hpp, docs/coherent.md).
// White noise: w = kCoherentWhiteScale * (2 (h >> kCoherentWhiteShift) + 1 - 2^24) for a
// 32-bit hash h: the odd multiples of 2^-24 in (-1, 1), times sqrt(3); mean exactly 0,
// variance 1 - 2^-48 (a discrete uniform over 2^24 values), never denormal.
constexpr unsigned kCoherentWhiteShift = 8;
constexpr double kCoherentWhiteScale = 1.7320508075688772935 * 0x1p-24;  // sqrt(3) * 2^-24
constexpr double kCoherentWhiteCentre = 16777215.0;                      // 2^24 - 1
// Pixel hash of a field: hash32(hash32(frame_key, y) ^ x * kCoherentPixelPrime). The odd
// multiplier (the 32-bit xxHash prime 4) scatters the columns, so two rows' keys can never
// line up a run of pixels (a plain xor of x would repeat shifted row segments).
constexpr unsigned kCoherentPixelPrime = 0x27D4EB2FU;
// Fields per channel, each with its own stream: the input w, the refill fields of the
// stationary filter (x and y; separate ones for the backward pass of the symmetric filter),
// and the band-pass input's lattice offsets.
constexpr unsigned kCoherentFieldInput = 0;
constexpr unsigned kCoherentFieldRefillX = 1;
constexpr unsigned kCoherentFieldRefillY = 2;
constexpr unsigned kCoherentFieldBackRefillX = 3;
constexpr unsigned kCoherentFieldBackRefillY = 4;
constexpr unsigned kCoherentFields = 5;
// Parameter defaults and limits. alpha = 0.98 is the paper's (sec. 4). epsilon is relative:
// the previous depth must lie within epsilon * e of the expected depth e (2% accepts bilinear
// interpolation of depth across a pixel of a plane tilted up to ~60 degrees and rejects a
// surface 2% farther; the same tolerance as the coherence metrics, docs/coherence.md).
constexpr double kCoherentDefaultAlpha = 0.98;
constexpr double kCoherentDefaultEpsilon = 0.02;
constexpr double kCoherentDefaultBandpassPixels = 4.0;  // band-pass input: Perlin cell, pixels
constexpr double kCoherentMaxBandpassPixels = 1024.0;
constexpr double kCoherentMaxSmoothing = 2.0;     // output Gaussian sigma, pixels
constexpr double kCoherentSmoothingRadius = 3.0;  // kernel radius in sigmas
constexpr int kCoherentMaxChannels = 4;
constexpr unsigned kCoherentMaxSide = 16384;  // frame side limit (keeps pixel indices in int32)

// ---- Poisson counts by table (core/poisson_table.hpp): thresholds of the CDF,
// built once per mean on the CPU, compared with one uniform word per draw.
// The mean is capped so that a table stays small (about mean + 7 sqrt(mean)
// + 20 thresholds: 11000 at the cap).
constexpr double kPoissonTableMaxMean = 1e4;

// ---- Float exp and sin/cos (detail/elementary.hpp): polynomials hush owns, so
// that scalar code, every SIMD target and GLSL evaluate the same operations
// (std::exp and Highway's Exp differ in their last bits). Coefficients are
// Chebyshev fits (mpmath.chebyfit, 40 digits), printed to 20 digits.
// exp(x), x <= 0: x = n ln2 + r with n = floor(x log2(e) + 1/2) and
// |r| <= ln2 / 2 (Cody-Waite: n ln2_hi is exact for |n| < 2^15), then
// e^r = P(r) of degree 6 (relative error 2.5e-9, below float rounding), and
// 2^n from the exponent bits. Below kExpFloor the result is 0 (no denormals).
constexpr double kLog2E = 1.4426950408889634074;
constexpr double kLn2Hi = 0.693359375;              // 355/512: 9 significant bits
constexpr double kLn2Lo = -2.12194440054690583e-4;  // ln 2 - kLn2Hi
constexpr double kExpFloor = -87.0;                 // e^-87 = 1.6e-38, just above FLT_MIN
constexpr int kExpDegree = 6;
constexpr double kExpPoly[kExpDegree + 1] = {1.0,
                                             1.0000000377162138425,
                                             0.50000000471177576744,
                                             0.16666415514653275427,
                                             0.041666352896775156786,
                                             0.008375126398153335682,
                                             0.0013941108433972674608};
// sin(2 pi t) and cos(2 pi t) for t in turns: t = q/4 + r with q = floor(4t + 1/2)
// (quarter turns, exact; t - floor(t) first when |t| >= 2^22) and |r| <= 1/8,
// then with z = r^2
//   sin(2 pi r) = r S(z), S of degree 3 (relative error 3.4e-9),
//   cos(2 pi r) = C(z),   C of degree 4 (absolute error 4.8e-11),
// rotated by the quadrant q mod 4.
constexpr int kSinDegree = 3;
constexpr double kSinPoly[kSinDegree + 1] = {6.2831852878129467414, -41.341662570547954912,
                                             81.592542871301543294, -75.401612702747458455};
constexpr int kCosDegree = 4;
constexpr double kCosPoly[kCosDegree + 1] = {0.99999999995248941669, -19.739208650130595513,
                                             64.939316135709049629, -85.442844673081659515,
                                             59.220168958296096218};
// Above this |t| (2^22) sincos_turns first reduces t - floor(t): 4t + 1/2 is
// exact below it, and a float above it has at most one fractional bit.
constexpr double kTurnsReduceLimit = 4194304.0;
constexpr double kTwoPi = 6.283185307179586476925;
constexpr double kPi = 3.141592653589793238463;

// ---- Gabor noise (Lagae, Lefebvre, Drettakis, Dutre 2009; gabor/kernel.hpp,
// gabor.hpp). Kernels are truncated where their envelope e^{-pi a^2 |x|^2}
// falls to t (the `truncation` parameter): radius r = sqrt(ln(1/t) / pi) / a.
// Instead of cutting there (a jump of t K, which the paper accepts), the
// kernel is multiplied by a smoothstep taper over the last part of its
// support, s = |x|^2 / r^2 in [kGaborTaperStart, 1]: C1 everywhere, equal to
// the Gabor kernel for |x| <= r sqrt(kGaborTaperStart), within K t^0.8 of it
// beyond.
constexpr double kGaborTaperStart = 0.8;
constexpr double kGaborDefaultTruncation = 0.05;  // the paper's value
constexpr double kGaborMinTruncation = 1e-9, kGaborMaxTruncation = 0.5;
constexpr double kGaborMinBandwidth = 1e-6, kGaborMaxBandwidth = 1e6;
constexpr double kGaborMaxFrequency = 1e6;
// Above this many cycles per cell the oscillatory part of the kernel's radial
// transforms (energy, truncation error, envelope transform) is its leading
// asymptotic term instead of a quadrature whose panels grow with the
// frequency: the term left out is below 2e-13 of the result there
// (gabor/kernel.hpp, docs/gabor.md "Cost of the kernel's statistics").
constexpr double kGaborAsymptoticCycles = 1024.0;
// Isotropic and hybrid noise's power spectrum at xi integrates the
// frequency vectors Phi only where a blob (+-Phi) is within this many cycles
// per cell of xi (H's Gaussian core is <= 1.5 wide): what is left out, both
// blobs in H's k^-3.5 tail, is ~1.7 W^-6 = 2.5e-11 of the isotropic ring's
// peak and pointwise below (1.7 W^-3.5)^2 = 6.6e-13 of H(0)^2 (gabor.hpp
// isotropic_mean, hybrid_window_2d, cap_mean; docs/gabor.md "Cost of the
// spectra");
// gabor_spectrum tabulates H up to this.
constexpr double kGaborSpectrumWindowCycles = 64.0;
// Hybrid noise's power_spectrum takes up to ~5e6 values of H per call, each
// a quadrature of up to ~500 nodes: it tabulates H once per call instead
// (detail::chebyshev_table) up to the largest k needed but at most
// kGaborSpectrumWindowCycles (<= 64 * 19 + 1 = 1217 quadratures), on panels
// this wide (cycles per cell; H oscillates at <= 1 cycle per unit k) with this
// many Chebyshev points each: measured within 1e-15 of H(0) (t = 1e-9 ... 0.5,
// 2D and 3D: tests/gabor/gabor_kernel_test.cpp); beyond, H's asymptotic term, as
// gabor_spectrum.
constexpr double kGaborTransformTablePanel = 1.0;
constexpr int kGaborTransformTableNodes = 20;
// N' (mean number of kernels overlapping a point): the papers use 16 ... 128.
// The cap keeps every Poisson table within kGaborMaxThresholds entries (the
// GLSL uniform arrays).
constexpr double kGaborMaxImpulses = 256.0;
// The largest magnitude a parameter that scales a noise's output may take (band weights, the
// Gaussian scale, table values): every noise also evaluates in float, and 1e30 leaves float's
// 3.4e38 room for a sum of 32 bands and its normalisation.
constexpr double kMaxOutputScale = 1e30;
// Band weights of a sum of bands (fractal, wavelet): |w| <= 1e30 keeps every weight, the sums of
// w^2 and |w| of up to 32 bands and the bound sum |w| max |n| finite in float; the largest
// |w| >= 1e-30 keeps it a normal float and the normalisation 1 / sqrt(sigma^2 sum w^2) finite.
constexpr double kMaxBandWeight = kMaxOutputScale;
constexpr double kMinLargestBandWeight = 1.0 / kMaxOutputScale;
// The fewest kernels per point a Poisson table of 32-bit thresholds represents: below about
// 1e-10 per cell not one impulse can occur, the noise is 0 and its normalisation infinite.
constexpr double kGaborMinImpulses = 1e-6;
constexpr int kGaborMaxThresholds = 192;
// Impulse marks from the cell stream's words, cut into fields: an 8-bit
// field m is the value (2m + 1) 2^-9 in (0, 1), a 16-bit field (2m + 1) 2^-17;
// both exact in float and GLSL, symmetric about 1/2. One impulse takes:
//   2D: word 0 = [x:8 | y:8 | weight:8 | orientation:8] (high to low bits),
//       hybrid: word 1 = [frequency:16 | unused:16];
//   3D: word 0 = [x:8 | y:8 | z:8 | weight:8], isotropic and hybrid:
//       word 1 = [polar cosine:16 | azimuth:16], hybrid: word 2 = [frequency:16 | -].
// Positions on a lattice of 256 steps per cell change the process only at
// frequencies of 256 cycles per kernel radius, where the kernel's spectrum is
// below e^-2000; weights w = 2u - 1 have E[w] = 0 and E[w^2] = (1 - 2^-16) / 3.
// One hash per impulse instead of four (docs/gabor.md).
constexpr unsigned kGaborByteBits = 8;
constexpr unsigned kGaborByteMask = 0xFFU;
constexpr double kGaborByteScale = 1.0 / 512.0;  // 2^-9
constexpr unsigned kGaborHalfBits = 16;
constexpr unsigned kGaborHalfMask = 0xFFFFU;
constexpr double kGaborHalfScale = 1.0 / 131072.0;  // 2^-17
// Streams of the per-cell hush::rng: solid (2D and 3D) and surface noise.
constexpr unsigned kGaborSolidStream = 0;
constexpr unsigned kGaborSurfaceStream = 1;
// Surface noise (paper sec. 4.3): a 3D process whose impulses within a slab of
// half-thickness h = rho / sqrt 2 around the tangent plane contribute the 2D
// kernel of their projection; cells of size rho sqrt(3/2) hold the whole
// slab-and-disk cylinder (radius rho, half-height h) in the 3 x 3 x 3
// neighbourhood. This h minimises the impulses examined per sample.
constexpr double kGaborSurfaceSlab = 0.70710678118654752440;  // h / rho = 1 / sqrt 2
constexpr double kGaborSurfaceCell = 1.2247448713915890491;   // cell / rho = sqrt(3/2)
// GLSL filtering (hush/glsl/gabor_glsl.hpp): the footprint's eigenvectors by
// cyclic Jacobi in float, at most this many sweeps (a 3 x 3 symmetric matrix
// converges to float precision in 4 or 5), stopping once the off-diagonal
// energy is below kGaborGlslJacobiTolerance times the diagonal's.
constexpr unsigned kGaborGlslJacobiSweeps = 6;
constexpr double kGaborGlslJacobiTolerance = 1e-12;

// ---- NPR Gabor noise (Benard, Lagae, Vangorp, Lefebvre, Drettakis, Thollot
// 2010; npr_gabor.hpp). Parameters are in screen pixels: frequency F0 in
// cycles per pixel up to Nyquist, bandwidth a in 1/pixel (kernel radius
// r = sqrt(ln(1/t) / pi) / a: from 0.047 px at a = 10, t = 0.5, to 257 px at
// a = 0.01, t = 1e-9), N' up to Gabor noise's cap.
constexpr double kNprGaborMaxFrequency = 0.5;
constexpr double kNprGaborMinBandwidth = 0.01, kNprGaborMaxBandwidth = 10.0;
constexpr double kNprGaborDefaultFrequency = 0.125;      // 8-pixel period
constexpr double kNprGaborDefaultBandwidth = 0.08;       // r = 12.2 px for t = 0.05
constexpr double kNprGaborDefaultImpulses = 16.0;        // N' (the paper: 16 ... 128)
constexpr double kNprGaborDefaultDepthTolerance = 0.02;  // relative depth difference
constexpr double kNprGaborMaxDepthTolerance = 1.0;
// N is clamped here (2M <= 2^41 points per triangle). Not a work bound (stage 1
// walks only the subtrees near the image, npr_gabor/tree.hpp) but the
// input's: float screen positions have a 1-pixel ulp at 2^24 = 1.7e7 px, and a
// triangle of 2^40 points at the default density (0.034 / px^2) already has
// legs of 8e6 px, where the vertices are placed to half a pixel: beyond, the
// input cannot place the points it asks for. Indices J < 2^41 keep
// npr_tree_child's index + 4 stride below 2^46, far from overflowing 64 bits.
constexpr double kNprGaborMaxPoints = 1099511627776.0;  // 2^40
// Triangles crossing the near plane (a vertex at depth <= 0; docs/npr-gabor.md "Skipped
// triangles"): stage 1 clips the point tree's nodes at the depth w_near = this fraction of
// the triangle's largest vertex depth (the input has no near plane; a renderer's is far
// larger, e.g. 0.05 with a scene 10-100 deep). Nodes entirely behind it are dropped, nodes
// crossing it are culled by their clipped part's projection (bounded: every depth there is
// >= w_near > 0).
constexpr double kNprGaborNearFraction = 1.0 / 1024.0;
// The per-triangle count N = lambda A assumes little perspective within a triangle: its points'
// screen density varies as the cube of the depth ratio r = far / near of its vertices. Above
// r = 4 the count per node (params::local_density's) takes over, blended in squared weight
// with t = log(r / 4) / log(8 / 4) clamped to [0, 1], so no triangle switches at once (no
// pop), and the per-triangle part's records near the image stay within 2 lambda 8^3 per
// pixel (the per-triangle count grows without bound as a vertex nears depth 0).
constexpr double kNprGaborPerNodeRatioLow = 4.0;
constexpr double kNprGaborPerNodeRatioHigh = 8.0;
constexpr unsigned kNprGaborMaxTriangles = 1u << 28;
constexpr unsigned kNprGaborMaxImageSide = 32768;
// Each point takes 2 words of its triangle's stream (hush::rng, stream
// kNprGaborStream): [u:16 | v:16] (barycentric), [weight:16 | orientation:16].
constexpr unsigned kNprGaborWordsPerPoint = 2;
constexpr unsigned kNprGaborStream = 2;
// The hierarchical point sequence (npr_gabor/tree.hpp): a node takes 3
// words of its own stream (point, value, child order); its children's order is
// one of the 24 permutations of {0, 1, 2, 3}, entry p holding in bits 2d, 2d + 1
// the geometric child (0, 1, 2: the corner triangle at corner 0, 1, 2; 3: the
// middle one) at slot d (lexicographic order of the permutations).
constexpr unsigned kNprGaborWordsPerNode = 3;
constexpr unsigned kNprGaborChildOrders = 24;
constexpr unsigned kNprGaborChildOrder[kNprGaborChildOrders] = {
    0xE4, 0xB4, 0xD8, 0x78, 0x9C, 0x6C, 0xE1, 0xB1, 0xC9, 0x39, 0x8D, 0x2D,
    0xD2, 0x72, 0xC6, 0x36, 0x4E, 0x1E, 0x93, 0x63, 0x87, 0x27, 0x4B, 0x1B};
// Step in F r (cycles per kernel radius) between the exact kernel energies a
// non-constant frequency's normalisation interpolates (npr_gabor.hpp): the
// energy depends on F only through F r for a given truncation; 1/64 keeps the
// linear interpolation within 1e-3 relative for t in [1e-9, 0.5].
constexpr double kNprGaborEnergyStep = 1.0 / 64.0;

// ---- Styles (npr_gabor/style.hpp; Benard et al. 2010 sec. 4): the smooth step's width
// in noise standard deviations (8 sigma: every pixel in the soft band), the
// graphite style's fine-layer weight and the watercolour overlay's gain.
constexpr double kStyleMaxWidth = 8.0;
constexpr double kStyleMaxGrain = 8.0;
constexpr double kStyleMaxGain = 4.0;

// ---- Anisotropic noise (Goldberg, Zwicker & Durand 2008; anisotropic/steerable.hpp,
// anisotropic/subband_fit.hpp, anisotropic.hpp; derivations in docs/anisotropic.md).
constexpr double kLn2 = 0.69314718055994530942;
// Orientations K of the steerable filter bank (the paper uses 4 to 8; one
// orientation has no angular selectivity) and scales (octaves of the bank).
constexpr int kAnisoMinOrientations = 2;
constexpr int kAnisoMaxOrientations = 8;
constexpr int kAnisoMaxScales = 12;
// Subband tiles: power-of-two sizes (the FFT's), at least 16 texels (so the
// band's lowest frequency, 1/16 cycle per texel, is one DFT bin), at most
// 2048 (8 orientations of 2048^2 floats are 128 MiB).
constexpr int kAnisoMinTileSize = 16;
constexpr int kAnisoMaxTileSize = 2048;
// Centre frequency of the tiles' subband, in cycles per texel: the band spans
// [1/16, 1/4], so at its top bilinear lookups still pass sinc^2(1/4) = 0.81 of
// the amplitude and the first interpolation image (at 3/4) carries below 1%
// of the power (docs/anisotropic.md, "Tiles").
constexpr double kAnisoTileBand = 0.125;
// The 3-radial-point rule (paper sec. 5): the target is read at log2 offsets
// -1/2, 0, +1/2 octave from a subband's centre and averaged with the weights
// of the subband's radial profile there, cos^2(pi/4) : 1 : cos^2(pi/4),
// normalised to 1/4, 1/2, 1/4.
constexpr double kAnisoThreePointOffset = 0.5;
constexpr double kAnisoThreePointSide = 0.25;
constexpr double kAnisoThreePointCentre = 0.5;
// A filtering weight exp(-x) with x above this is set to exactly 0 (and its
// subband is skipped): exp(-17) = 4.1e-8 < 2^-24, below float resolution.
constexpr double kAnisoWeightCutoff = 17.0;
// Least-squares quadrature (anisotropic/subband_fit.hpp): midpoint nodes per octave of
// radius, and angular nodes per orientation over a half turn (filters and
// targets are even: D(-w) = D(w)).
constexpr int kAnisoRadialNodesPerOctave = 16;
constexpr int kAnisoAngularNodesPerOrientation = 12;

// Float approximations used by the weights (detail/approx_math.hpp), written
// out so that scalar and SIMD code evaluate the same polynomial in the same
// order (bit-identical under HUSH_STRICT_FP):
//  - 2^r on [-1/2, 1/2]: Taylor series of exp(r ln 2) to degree 7
//    (truncation 5.3e-9 relative);
//  - log2 m on [sqrt(1/2), sqrt(2)]: (2 / ln 2) atanh(z), z = (m-1)/(m+1),
//    |z| <= 0.1716, odd series to z^9 (truncation 3e-10);
//  - sin(pi z) on [-1/2, 1/2]: Taylor series to degree 13 (truncation 6.6e-10).
// The coefficients are computed here at compile time from pi and ln 2.
struct aniso_series {
  double exp2[8];   // (ln 2)^k / k!, k = 0 ... 7
  double log2[5];   // (2 / ln 2) / (2k + 1), k = 0 ... 4
  double sinpi[7];  // (-1)^k pi^(2k+1) / (2k+1)!, k = 0 ... 6
  constexpr aniso_series() : exp2{}, log2{}, sinpi{} {
    double t = 1.0;
    for (int k = 0; k < 8; ++k) {
      exp2[k] = t;
      t = t * kLn2 / double(k + 1);
    }
    for (int k = 0; k < 5; ++k) log2[k] = (2.0 / kLn2) / double(2 * k + 1);
    double s = kPi;
    for (int k = 0; k < 7; ++k) {
      sinpi[k] = s;
      s = -s * kPi * kPi / double((2 * k + 2) * (2 * k + 3));
    }
  }
};
constexpr aniso_series kAnisoSeries{};
constexpr double kSqrt2 = 1.41421356237309504880;

}  // namespace constants
}  // namespace detail
}  // namespace hush

#endif  // HUSH_DETAIL_CONSTANTS_HPP

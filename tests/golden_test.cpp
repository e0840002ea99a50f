// Golden values: noise fields are a function of (parameters, seed) that must
// never change silently (HARD_CASES row 10: other libraries' fields changed
// with the compiler, the standard library or an argument evaluation order).
// If a change here is intended, it changes every user's images: say so in the
// changelog and regenerate these values deliberately.
//
// Integer quantities (hash bits, gradient indices) are compared bit for bit.
// Float values are compared within 2^-40 of the double reference values, far
// below any real change of the field (which moves values by ~0.1) and above
// the last-ulp differences FMA contraction can make (-march=native builds).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>

#include "hush/hush.hpp"

namespace {

const double kPoints[6][3] = {{0.5, 0.25, 0.125},         {-1.75, 3.3, -0.6},
                              {1000.1, -2000.7, 33.3},    {-0.01, -0.02, -0.03},
                              {123456.78, 0.5, -98765.4}, {7.77, -7.77, 0.77}};
const std::uint32_t kSeeds[3] = {0, 7, 0xdeadbeefU};
const double kTolerance = std::ldexp(1.0, -40);

// FNV-1a over the gradient indices of the 64 x 64 cells around the origin
// (3D: the cells (i, j, i ^ j)), for one seed.
std::uint32_t gradient_index_digest(std::uint32_t seed, int dim) {
  const std::uint32_t key = hush::seed_key(seed);
  std::uint32_t h = 2166136261U;
  for (int j = -32; j < 32; ++j)
    for (int i = -32; i < 32; ++i) {
      const auto ui = static_cast<std::uint32_t>(i), uj = static_cast<std::uint32_t>(j);
      const std::uint32_t g =
          dim == 2 ? hush::detail::perlin2_grad_index(hush::lattice_hash(key, ui, uj))
                   : hush::detail::perlin3_grad_index(hush::lattice_hash(key, ui, uj, ui ^ uj));
      h = (h ^ g) * 16777619U;
    }
  return h;
}

}  // namespace

TEST_CASE("golden: gradient index digests per seed are bit-exact") {
  const std::uint32_t expected[3][2] = {
      {0xb9ec76eeU, 0x9e5d6e1eU}, {0x3d9d70aeU, 0x0385f8e2U}, {0xe2ac35f7U, 0x98265dccU}};
  for (int s = 0; s < 3; ++s) {
    CHECK(gradient_index_digest(kSeeds[s], 2) == expected[s][0]);
    CHECK(gradient_index_digest(kSeeds[s], 3) == expected[s][1]);
  }
}

TEST_CASE("golden: perlin values per seed never change") {
  const double expected2[3][6] = {
      {-0.56785578621883459, 0.088158946801917354, 0.23007574896020624, 0.030091160178665588,
       -0.27356358416819399, 0.058654693672558801},
      {0.29865594029607595, -0.10345300316328988, -0.45844358391102574, -0.028290647885211073,
       0.68772898265375726, 0.21767822420972191},
      {-0.38486428522817545, 0.38995119839758047, 0.097798274030495347, 0.030088007593422228,
       0.47122138883895565, 0.51501601849943823}};
  const double expected3[3][6] = {
      {0.016726623131214167, 0.0022804060839864788, 0.077295160448643582, -0.048053375862149285,
       -0.3129430635609835, -0.29578036616048703},
      {0.42966271610350659, -0.38419022676067283, 0.26338926495855436, -0.038589246357566248,
       0.14683568956516524, 0.17222253858977488},
      {0.19349215699884034, 0.21233492694709341, 0.28091576143773672, -0.04797774337138045,
       -0.14176671913782382, 0.4121936604846187}};
  for (int s = 0; s < 3; ++s) {
    const hush::perlin<2> p2(kSeeds[s]);
    const hush::perlin<3> p3(kSeeds[s]);
    for (int i = 0; i < 6; ++i) {
      const auto& q = kPoints[i];
      CHECK(std::fabs(p2(hush::dvec2{q[0], q[1]}) - expected2[s][i]) <= kTolerance);
      CHECK(std::fabs(p3(hush::dvec3{q[0], q[1], q[2]}) - expected3[s][i]) <= kTolerance);
      // The float path shares every integer step; its values stay within its
      // error budget of the same golden values.
      CHECK(std::fabs(p3.value<float>(hush::dvec3{q[0], q[1], q[2]}) - expected3[s][i]) <=
            std::ldexp(1.0, -16));
    }
  }
}

TEST_CASE("golden: fractal values never change") {
  const double fbm[6] = {-0.36183141238449518, 2.270839317008611,  -1.8775005808210812,
                         0.78757705773043718,  0.9528721675298053, 0.69176701512389005};
  const double turbulence[6] = {0.33685366170937081, 0.35562261575572607, 0.29482414781371696,
                                0.21179584249116851, 0.17168688769980026, 0.12284994883455021};
  hush::fractal<hush::perlin<3>>::params prm;
  prm.seed = 7;
  prm.octaves = 6;
  const hush::fractal<hush::perlin<3>> f(prm);
  prm.kind = hush::fractal_kind::turbulence;
  prm.norm = hush::normalization::unit_range;
  prm.octaves = 4;
  prm.gain = 0.6;
  const hush::fractal<hush::perlin<3>> t(prm);
  for (int i = 0; i < 6; ++i) {
    const hush::dvec3 q{kPoints[i][0], kPoints[i][1], kPoints[i][2]};
    CHECK(std::fabs(f(q) - fbm[i]) <= kTolerance);
    CHECK(std::fabs(t(q) - turbulence[i]) <= kTolerance);
  }
}

TEST_CASE("golden: gabor impulses (counts and words) and values per seed never change") {
  // 2D isotropic and 3D anisotropic (orientation 0.5, elevation 0.25) Gabor noise with
  // default parameters (hush/gabor.hpp), double reference at kPoints; the digest is FNV-1a
  // over every impulse's first word and every cell's count in the 64 x 64 cells around the
  // origin (2D): the integer path every backend shares.
  const double expected2[3][6] = {
      {-0.28228456698211613, -0.81610778401543893, -0.060509466274218743, 0.031307075744370041,
       0.94585347394170971, -0.061228365984015751},
      {-0.64290219714890506, 0.66056384794242795, 1.3925877833458502, -0.74298229514373682,
       -0.90147856394376258, 0.18166348623591277},
      {0.727802698099277, 0.11254047115339647, -1.5116161741423304, 0.96754900993090731,
       1.8927134120035212, 1.1082285929263258}};
  const double expected3[3][6] = {
      {-1.028186258293649, 0.47908276376735287, 0.5985153731895938, 0.26750715610199394,
       -0.36617722302508071, -1.1781066857852662},
      {0.18621799453942631, 0.11999458683306655, -0.35282818550583217, -0.39988740414200519,
       0.40516299541508094, -0.63659183597762903},
      {1.124411396712736, -1.049488254703868, 0.20622582996108141, 0.01648335889284205,
       -0.78027568995556573, -0.70130110971023518}};
  const std::uint32_t digests[3] = {0xc4a31b84U, 0xa06e31c4U, 0xd99c4676U};
  for (int s = 0; s < 3; ++s) {
    hush::gabor<2>::params p2;
    p2.seed = kSeeds[s];
    hush::gabor<3>::params p3;
    p3.seed = kSeeds[s];
    p3.kind = hush::gabor_kind::anisotropic;
    p3.orientation = 0.5;
    p3.elevation = 0.25;
    const hush::gabor<2> g2(p2);
    const hush::gabor<3> g3(p3);
    for (int i = 0; i < 6; ++i) {
      CHECK(std::fabs(g2.value<double>(hush::dvec2{kPoints[i][0], kPoints[i][1]}) -
                      expected2[s][i]) <= kTolerance);
      CHECK(std::fabs(g3.value<double>(hush::dvec3{kPoints[i][0], kPoints[i][1], kPoints[i][2]}) -
                      expected3[s][i]) <= kTolerance);
    }
    std::uint32_t h = 2166136261U;
    for (int j = -32; j < 32; ++j)
      for (int i = -32; i < 32; ++i) {
        const std::uint32_t cell[2] = {static_cast<std::uint32_t>(i),
                                       static_cast<std::uint32_t>(j)};
        std::uint32_t n = 0;
        g2.for_each_impulse(cell, [&](const std::uint32_t* w) {
          h = (h ^ w[0]) * 16777619U;
          ++n;
        });
        h = (h ^ n) * 16777619U;
      }
    CHECK(h == digests[s]);
  }
}

TEST_CASE("golden: wavelet values (2D 3 bands, 3D, 3D projected) per seed never change") {
  // hush/wavelet.hpp with default tiles (128^2, 64^3, even/odd fix): 2D with weights
  // 1, 1/2, 1/4; 3D one band, as a point and projected along the normal (1, 2, 0.5) (exact
  // projection, normalised with detail::wavelet_oblique_variance_ratio); double reference at
  // kPoints. The tiles' Gaussian coefficients, analysis filter and offsets all feed these values.
  const double expected[3][3][6] = {
      {{1.1540995954971707, 0.3359358689123424, -0.9828492018446296,
        0.8323476199055663, 0.7094023553928317, 0.6175101489444771},
       {-0.004497904777361251, 0.8131230491695801, 0.5639320750130475,
        0.5121867625309626, 0.911894072095335, -0.07300422572588579},
       {-0.30536163946424266, 0.40475345477448826, 0.6815655252309991,
        -1.1389700865779255, -0.5813846939951159, -0.4540855462130692}},
      {{0.7184476202269156, 0.6961391293183797, 0.19502704013129135,
        0.08734224660372429, -1.8488960031203658, -2.3474314337090885},
       {-0.5886823904314432, -1.062572558680498, -1.087643030407672,
        -0.12548354464763325, 1.3443690980827177, -0.3911283281250551},
       {-0.6757892262774989, -1.053933159057684, -1.16867798720841,
        0.29262832305007086, 1.8031128705520576, 0.1437827498776331}},
      {{-0.5515207054018074, 0.6259941833826608, 0.22290086154937244,
        -0.5764635882641177, 0.5900670682350494, -1.4155505828601698},
       {-1.1855906330307924, -0.17412268592777824, 1.0183379954403156,
        -0.2921658644297784, -0.33177761866232497, 0.5426564347095201},
       {-0.8029368161554672, 0.6061233668163792, 1.6871415748605567,
        -0.5332016469403064, -1.0129554471915037, 0.23223465578859104}}};
  for (int s = 0; s < 3; ++s) {
    hush::wavelet<2>::params p2;
    p2.seed = kSeeds[s];
    p2.weights = {1, 0.5, 0.25};
    hush::wavelet<3>::params p3;
    p3.seed = kSeeds[s];
    const hush::wavelet<2> w2(p2);
    const hush::wavelet<3> w3(p3);
    const hush::footprint<3> point{};
    for (int i = 0; i < 6; ++i) {
      const hush::dvec3 q{kPoints[i][0], kPoints[i][1], kPoints[i][2]};
      CHECK(std::fabs(w2.value<double>(hush::dvec2{q[0], q[1]}) - expected[s][0][i]) <=
            kTolerance);
      CHECK(std::fabs(w3.value<double>(q) - expected[s][1][i]) <= kTolerance);
      CHECK(std::fabs(w3.sample(q, hush::dvec3{1, 2, 0.5}, point) - expected[s][2][i]) <=
            kTolerance);
    }
  }
}

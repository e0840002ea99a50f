// hush — anisotropic noise experiments (see figures.hpp).
#include "figures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <set>
#include <utility>

namespace hush_tools::aniso {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- Small helpers.

// Bilinear lookup of a periodic n x n image at texel position (u, v) (texel (x, y) at (x, y)).
double bilinear(const std::vector<double>& img, std::size_t n, double u, double v) {
  const double fu = std::floor(u), fv = std::floor(v);
  const double tu = u - fu, tv = v - fv;
  const auto wrap = [n](double c) {
    const double m = std::fmod(c, static_cast<double>(n));
    return static_cast<std::size_t>(m < 0 ? m + static_cast<double>(n) : m) % n;
  };
  const std::size_t x0 = wrap(fu), y0 = wrap(fv), x1 = (x0 + 1) % n, y1 = (y0 + 1) % n;
  const double a = img[y0 * n + x0] + tu * (img[y0 * n + x1] - img[y0 * n + x0]);
  const double b = img[y1 * n + x0] + tu * (img[y1 * n + x1] - img[y1 * n + x0]);
  return a + tv * (b - a);
}

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / static_cast<double>(v.size());
}
double cv_of(const std::vector<double>& v) {
  const double m = mean_of(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return v.size() < 2 ? 0 : std::sqrt(s / static_cast<double>(v.size() - 1)) / m;
}

hush::anisotropic make_noise(int k, int scales, int base, int octaves, double frequency,
                             hush::weight_rule filtering, hush::weight_rule compensation,
                             std::uint32_t seed, int tile = 256) {
  hush::anisotropic::params p;
  p.seed = seed;
  p.orientations = k;
  p.scales = scales;
  p.base_scale = base;
  p.octaves = octaves;
  p.frequency = frequency;
  p.tile_size = tile;
  p.filtering = filtering;
  p.compensation = compensation;
  return hush::anisotropic(p);
}

// ---- Meshes as piecewise-linear maps: a uv grid of n x n cells, two triangles per cell
// in examples/scene's order ((i,j), (i+1,j), (i,j+1)) and ((i+1,j), (i+1,j+1), (i,j+1)).
struct grid_mesh {
  int n = 0;
  std::vector<hush::dvec3> pos;         // (n + 1)^2 vertices, vertex (i, j) at j (n + 1) + i
  std::vector<hush::surface_map> maps;  // 2 n^2 triangles
  std::array<int, 3> corners(int i, int j, int tri) const {
    const auto at = [this](int a, int b) { return b * (n + 1) + a; };
    return tri == 0 ? std::array<int, 3>{at(i, j), at(i + 1, j), at(i, j + 1)}
                    : std::array<int, 3>{at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
  }
  hush::dvec2 uv(int v) const {
    const int i = v % (n + 1), j = v / (n + 1);
    return {static_cast<double>(i) / n, static_cast<double>(j) / n};
  }
  void build_maps() {
    maps.clear();
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int t = 0; t < 2; ++t) {
          const auto c = corners(i, j, t);
          maps.push_back(hush::surface_map::from_triangle(pos[c[0]], pos[c[1]], pos[c[2]], uv(c[0]),
                                                          uv(c[1]), uv(c[2])));
        }
  }
  // The triangle containing uv (cells by uv; the lower triangle when fu + fv < 1).
  const hush::surface_map& map_at(const hush::dvec2& p) const {
    const double un = p.x * n, vn = p.y * n;
    const int i = std::clamp(static_cast<int>(std::floor(un)), 0, n - 1);
    const int j = std::clamp(static_cast<int>(std::floor(vn)), 0, n - 1);
    const int t = (un - i) + (vn - j) < 1.0 ? 0 : 1;
    const int k = 2 * (j * n + i) + t;
    return maps[static_cast<std::size_t>(k)];
  }
};

// The trapezoid: bottom width 2 (y = 0), top 0.5 (y = 1); uv (u, v) sits at
// x = (u - 1/2) w(v), y = v.
double trapezoid_width(double y) { return 2.0 - 1.5 * y; }
grid_mesh trapezoid_mesh(int n) {
  grid_mesh m;
  m.n = n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
      m.pos.push_back({(u - 0.5) * trapezoid_width(v), v, 0.0});
    }
  m.build_maps();
  return m;
}
hush::dvec2 trapezoid_uv(double x, double y) { return {x / trapezoid_width(y) + 0.5, y}; }

// The sphere (examples/scene make_sphere's vertices): uv (lon / 2 pi, colat / pi).
hush::dvec3 sphere_point(double u, double v) {
  const double phi = 2 * kPi * u, theta = kPi * v;
  return {std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
}
struct sphere_mesh {
  int slices = 64, stacks = 32;
  std::vector<hush::surface_map> maps;  // per cell and triangle
  sphere_mesh() {
    for (int j = 0; j < stacks; ++j)
      for (int i = 0; i < slices; ++i)
        for (int t = 0; t < 2; ++t) {
          const int a[2][3][2] = {{{0, 0}, {1, 0}, {0, 1}}, {{1, 0}, {1, 1}, {0, 1}}};
          hush::dvec3 p[3];
          hush::dvec2 uv[3];
          for (int c = 0; c < 3; ++c) {
            uv[c] = {static_cast<double>(i + a[t][c][0]) / slices,
                     static_cast<double>(j + a[t][c][1]) / stacks};
            p[c] = sphere_point(uv[c].x, uv[c].y);
          }
          maps.push_back(hush::surface_map::from_triangle(p[0], p[1], p[2], uv[0], uv[1], uv[2]));
        }
  }
  const hush::surface_map& map_at(const hush::dvec2& uv) const {
    const double un = uv.x * slices, vn = uv.y * stacks;
    const int i = std::clamp(static_cast<int>(std::floor(un)), 0, slices - 1);
    const int j = std::clamp(static_cast<int>(std::floor(vn)), 0, stacks - 1);
    const int t = (un - i) + (vn - j) < 1.0 ? 0 : 1;
    const int k = 2 * (j * slices + i) + t;
    return maps[static_cast<std::size_t>(k)];
  }
};

// Radial-frequency statistics over windows of a noise seen three ways: without
// compensation, with the centre rule, with least squares. make(seed, rule) builds the
// noise; surface(noise, compensate, centre) is the noise around a window centre, in local
// surface coordinates. Each window's frequency is the mean over `seeds` noises (the
// estimate of one window of random noise varies by a few percent).
template <class Make, class Surface>
distortion_result measure(const std::string& name, double target,
                          const std::vector<std::array<double, 2>>& centres, double size, int seeds,
                          Make make, Surface surface) {
  std::vector<double> a(centres.size(), 0.0), b(centres.size(), 0.0), c(centres.size(), 0.0);
  for (int seed = 0; seed < seeds; ++seed) {
    const hush::anisotropic centre =
        make(static_cast<std::uint32_t>(seed), hush::weight_rule::centre);
    const hush::anisotropic lsq =
        make(static_cast<std::uint32_t>(seed), hush::weight_rule::least_squares);
    for (std::size_t w = 0; w < centres.size(); ++w) {
      a[w] += radial_frequency(surface(centre, false, centres[w]), 0, 0, size) / seeds;
      b[w] += radial_frequency(surface(centre, true, centres[w]), 0, 0, size) / seeds;
      c[w] += radial_frequency(surface(lsq, true, centres[w]), 0, 0, size) / seeds;
    }
  }
  distortion_result r;
  r.surface = name;
  r.target = target;
  r.windows = centres.size();
  r.mean_none = mean_of(a);
  r.cv_none = cv_of(a);
  r.mean_centre = mean_of(b);
  r.cv_centre = cv_of(b);
  r.mean_lsq = mean_of(c);
  r.cv_lsq = cv_of(c);
  return r;
}

}  // namespace

// ---- Figure 8.

std::vector<resampling_result> figure8(const resampling_setup& st) {
  const std::size_t n = st.texture;
  hush::rng r(st.seed, 8);
  struct wave {
    int kx, ky;
    double phase;
  };
  std::vector<wave> waves;
  std::set<std::pair<int, int>> seen;
  while (static_cast<int>(waves.size()) < st.cosines) {
    // Uniform over the annulus 1/16 ... 0.45 cycles per texel (by area), rounded to the
    // integer wave vectors of the periodic image.
    const double rad = std::sqrt(r.uniform<double>(1.0 / 256, 0.45 * 0.45));
    const double ang = r.uniform<double>(0, kPi);
    const int kx = static_cast<int>(std::lround(rad * std::cos(ang) * double(n)));
    const int ky = static_cast<int>(std::lround(rad * std::sin(ang) * double(n)));
    if ((kx == 0 && ky == 0) || !seen.insert({kx, ky}).second || !seen.insert({-kx, -ky}).second)
      continue;
    waves.push_back({kx, ky, r.uniform<double>(0, 2 * kPi)});
  }
  const double amp = std::sqrt(2.0 / st.cosines);
  std::vector<double> tex(n * n, 0.0);
  for (std::size_t y = 0; y < n; ++y)
    for (std::size_t x = 0; x < n; ++x)
      for (const wave& w : waves)
        tex[y * n + x] +=
            amp * std::cos(2 * kPi * (w.kx * double(x) + w.ky * double(y)) / double(n) + w.phase);
  // The pixel filter in texture space: H(xi) = exp(-2 pi^2 sigma^2 |A^T xi|^2).
  const double sigma = hush::detail::constants::kPixelFilterSigma;
  auto h = [&](const hush::dvec2& xi) {
    const double a = st.a00 * xi.x + st.a10 * xi.y, b = st.a01 * xi.x + st.a11 * xi.y;
    return std::exp(-2 * kPi * kPi * sigma * sigma * (a * a + b * b));
  };
  auto position = [&](std::size_t x, std::size_t y) {
    const double px = double(x) + 0.5, py = double(y) + 0.5;
    return hush::dvec2{st.a00 * px + st.a01 * py + st.c0, st.a10 * px + st.a11 * py + st.c1};
  };
  const std::size_t m = st.output;
  std::vector<resampling_result> out;
  resampling_result ref{"gaussian reference", 0, image(m, m)};
  for (std::size_t y = 0; y < m; ++y)
    for (std::size_t x = 0; x < m; ++x) {
      const hush::dvec2 u = position(x, y);
      double v = 0;
      for (const wave& w : waves)
        v += amp * h({w.kx / double(n), w.ky / double(n)}) *
             std::cos(2 * kPi * (w.kx * u.x + w.ky * u.y) / double(n) + w.phase);
      ref.result.at(x, y) = static_cast<float>(v);
    }
  out.push_back(ref);
  auto mse = [&](const image& a) {
    double s = 0;
    for (std::size_t q = 0; q < a.v.size(); ++q)
      s += (double(a.v[q]) - ref.result.v[q]) * (double(a.v[q]) - ref.result.v[q]);
    return s / static_cast<double>(a.v.size());
  };
  struct method {
    std::string name;
    int k;
    hush::weight_rule rule;
  };
  const method methods[] = {{"least squares, K = 8", 8, hush::weight_rule::least_squares},
                            {"least squares, K = 4", 4, hush::weight_rule::least_squares},
                            {"heuristic (centre), K = 4", 4, hush::weight_rule::centre},
                            {"heuristic (centre), K = 8", 8, hush::weight_rule::centre},
                            {"three-point, K = 4", 4, hush::weight_rule::three_point}};
  for (const method& me : methods) {
    hush::steerable_bank::params bp;
    bp.orientations = me.k;
    bp.scales = st.scales;
    bp.base_frequency = 0.25 / std::ldexp(1.0, st.scales - 1);
    const hush::steerable_bank bank(bp);
    const hush::steerable_decomposition d = hush::decompose(tex, n, bank);
    const hush::subband_fit fit(bank, true, std::sqrt(0.5));
    const std::vector<double> w = fit.fit(me.rule, h);
    resampling_result res{me.name, 0, image(m, m)};
    for (std::size_t y = 0; y < m; ++y)
      for (std::size_t x = 0; x < m; ++x) {
        const hush::dvec2 u = position(x, y);
        double v = 0;
        for (std::size_t j = 0; j < d.subbands.size(); ++j)
          if (w[j] != 0) v += w[j] * bilinear(d.subbands[j], n, u.x, u.y);
        v += w[d.subbands.size()] * bilinear(d.low, n, u.x, u.y);
        v += w[d.subbands.size() + 1] * bilinear(d.high, n, u.x, u.y);
        res.result.at(x, y) = static_cast<float>(v);
      }
    res.mse = mse(res.result);
    out.push_back(res);
  }
  resampling_result bil{"bilinear", 0, image(m, m)};
  for (std::size_t y = 0; y < m; ++y)
    for (std::size_t x = 0; x < m; ++x) {
      const hush::dvec2 u = position(x, y);
      bil.result.at(x, y) = static_cast<float>(bilinear(tex, n, u.x, u.y));
    }
  bil.mse = mse(bil.result);
  out.push_back(bil);
  return out;
}

// ---- Distortion compensation.

double radial_frequency(const surface_noise& noise, double s0, double t0, double size,
                        std::size_t n) {
  const double d = size / static_cast<double>(n);
  std::vector<double> v(n * n);
  for (std::size_t y = 0; y < n; ++y)
    for (std::size_t x = 0; x < n; ++x)
      v[y * n + x] = noise(s0 + (double(x) + 0.5 - 0.5 * double(n)) * d,
                           t0 + (double(y) + 0.5 - 0.5 * double(n)) * d);
  const double mean = mean_of(v);
  auto hann = [n](std::size_t i) {
    return 0.5 - 0.5 * std::cos(2 * kPi * (double(i) + 0.5) / double(n));
  };
  std::vector<std::complex<double>> a(n * n);
  for (std::size_t y = 0; y < n; ++y)
    for (std::size_t x = 0; x < n; ++x) a[y * n + x] = (v[y * n + x] - mean) * hann(x) * hann(y);
  hush::detail::fft2(a.data(), n, -1);
  double num = 0, den = 0;
  for (std::size_t y = 0; y < n; ++y)
    for (std::size_t x = 0; x < n; ++x) {
      if (x == 0 && y == 0) continue;
      const double r =
          std::hypot(hush::detail::bin_frequency(x, n), hush::detail::bin_frequency(y, n)) / d;
      const double p = std::norm(a[y * n + x]);
      num += r * p;
      den += p;
    }
  return den > 0 ? num / den : 0;
}

distortion_result trapezoid_distortion(std::uint32_t seed) {
  const grid_mesh mesh = trapezoid_mesh(16);
  const double f = 40;  // cycles per surface unit (compensated), per uv unit (not)
  auto make = [f, seed](std::uint32_t s, hush::weight_rule rule) {
    return make_noise(4, 4, 1, 1, f, hush::weight_rule::centre, rule, seed * 16 + s);
  };
  auto surface = [&mesh](const hush::anisotropic& a, bool compensate,
                         const std::array<double, 2>& c) -> surface_noise {
    return [&a, &mesh, compensate, c](double s, double t) {
      const hush::dvec2 uv = trapezoid_uv(c[0] + s, c[1] + t);
      if (!compensate) return static_cast<float>(a.sample(uv, hush::footprint<2>{}));
      return static_cast<float>(a.sample(uv, hush::footprint<2>{}, mesh.map_at(uv)));
    };
  };
  std::vector<std::array<double, 2>> centres;
  for (double y : {0.15, 0.35, 0.55, 0.75, 0.85})
    for (double xf : {-0.25, 0.0, 0.25}) centres.push_back({xf * trapezoid_width(y), y});
  return measure("trapezoid", f, centres, 0.14, 4, make, surface);
}

distortion_result sphere_distortion(std::uint32_t seed) {
  const sphere_mesh mesh;
  const double f = 120;
  auto make = [f, seed](std::uint32_t s, hush::weight_rule rule) {
    return make_noise(4, 6, 0, 1, f, hush::weight_rule::centre, rule, seed * 16 + s);
  };
  // Window centres at longitude 1 rad, colatitude c; local coordinates (s, t) along the
  // parallel and the meridian, mapped back onto the sphere by normalising.
  auto surface = [&mesh](const hush::anisotropic& a, bool compensate,
                         const std::array<double, 2>& c) -> surface_noise {
    const double u0 = 1.0 / (2 * kPi), v0 = c[0] / kPi;
    const hush::dvec3 p0 = sphere_point(u0, v0);
    const hush::dvec3 e_phi{-std::sin(2 * kPi * u0), 0.0, -std::cos(2 * kPi * u0)};
    const hush::dvec3 e_theta{std::cos(kPi * v0) * std::cos(2 * kPi * u0), -std::sin(kPi * v0),
                              -std::cos(kPi * v0) * std::sin(2 * kPi * u0)};
    return [&a, &mesh, compensate, p0, e_phi, e_theta](double s, double t) {
      hush::dvec3 q{p0.x + s * e_phi.x + t * e_theta.x, p0.y + s * e_phi.y + t * e_theta.y,
                    p0.z + s * e_phi.z + t * e_theta.z};
      const double l = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
      q = {q.x / l, q.y / l, q.z / l};
      double phi = std::atan2(-q.z, q.x);
      if (phi < 0) phi += 2 * kPi;
      const hush::dvec2 uv{phi / (2 * kPi), std::acos(std::clamp(q.y, -1.0, 1.0)) / kPi};
      if (!compensate) return static_cast<float>(a.sample(uv, hush::footprint<2>{}));
      return static_cast<float>(a.sample(uv, hush::footprint<2>{}, mesh.map_at(uv)));
    };
  };
  std::vector<std::array<double, 2>> centres;
  for (double c : {20.0, 35.0, 50.0, 70.0, 90.0, 110.0, 130.0, 145.0, 160.0})
    centres.push_back({c * kPi / 180, 0.0});
  return measure("sphere", f, centres, 0.1, 4, make, surface);
}

distortion_result ground_plane_distortion(std::uint32_t seed) {
  // make_plane(200, 200, 100, 100, 50): uv = 50 (x / 200 + 1/2, z / 200 + 1/2).
  const double uv_per_unit = 50.0 / 200.0;
  const hush::surface_map t = hush::surface_map::from_matrix(uv_per_unit, 0, 0, uv_per_unit);
  const double f = 2;  // cycles per world unit (compensated)
  auto make = [f, seed](std::uint32_t s, hush::weight_rule rule) {
    return make_noise(4, 5, 2, 1, f, hush::weight_rule::centre, rule, seed * 16 + s);
  };
  auto surface = [t, uv_per_unit](const hush::anisotropic& a, bool compensate,
                                  const std::array<double, 2>& c) -> surface_noise {
    return [&a, t, uv_per_unit, compensate, c](double x, double z) {
      const hush::dvec2 uv{uv_per_unit * (c[0] + x + 100), uv_per_unit * (c[1] + z + 100)};
      return static_cast<float>(compensate ? a.sample(uv, hush::footprint<2>{}, t)
                                           : a.sample(uv, hush::footprint<2>{}));
    };
  };
  std::vector<std::array<double, 2>> centres;
  for (double z : {-80.0, -30.0, 10.0, 60.0})
    for (double x : {-50.0, 0.0, 50.0}) centres.push_back({x, z});
  return measure("walkthrough ground plane", f, centres, 4.0, 4, make, surface);
}

std::vector<image> figure6(std::size_t width, std::size_t height) {
  const grid_mesh mesh = trapezoid_mesh(32);
  // Five scales, four orientations, two octaves (the paper's fig. 6).
  const double f = 8;
  const hush::anisotropic none =
      make_noise(4, 5, 1, 2, f, hush::weight_rule::centre, hush::weight_rule::centre, 11);
  const hush::anisotropic lsq =
      make_noise(4, 5, 1, 2, f, hush::weight_rule::centre, hush::weight_rule::least_squares, 11);
  std::vector<image> out;
  const double x0 = -1.05, x1 = 1.05, y0 = -0.05, y1 = 1.05;
  const double dx = (x1 - x0) / double(width), dy = (y1 - y0) / double(height);
  for (int version = 0; version < 3; ++version) {
    const hush::anisotropic& a = version == 1 ? lsq : none;
    image img(width, height);
    for (std::size_t py = 0; py < height; ++py)
      for (std::size_t px = 0; px < width; ++px) {
        const double x = x0 + (double(px) + 0.5) * dx, y = y1 - (double(py) + 0.5) * dy;
        if (y < 0 || y > 1 || std::fabs(x) > 0.5 * trapezoid_width(y)) continue;
        const hush::dvec2 uv = trapezoid_uv(x, y);
        const hush::surface_map& t = mesh.map_at(uv);
        // The pixel in texture space: the Jacobian T (dx, 0), T (0, dy).
        const auto fp = hush::footprint<2>::from_derivatives(hush::dvec2{t.m00 * dx, t.m10 * dx},
                                                             hush::dvec2{t.m01 * dy, t.m11 * dy});
        img.at(px, py) = static_cast<float>(
            version == 0 ? a.sample(uv, fp, hush::surface_map::identity()) : a.sample(uv, fp, t));
      }
    out.push_back(img);
  }
  return out;
}

// ---- The receding plane.

hush::dvec2 receding_plane::at(double x, double y) const {
  const double f = 0.5 * double(height) / std::tan(0.45);  // focal length, pixels
  const double pitch = 0.5;
  const double sx = (x - 0.5 * double(width)) / f, sy = -(y - 0.5 * double(height)) / f;
  // Camera looks along -z, pitched down: world direction of (sx, sy, -1).
  const double dy = sy * std::cos(pitch) - std::sin(pitch);
  const double dz = -sy * std::sin(pitch) - std::cos(pitch);
  const double t = 1.0 / -dy;  // height 1 above the plane
  return {scale * sx * t, scale * dz * t};
}

receding_plane make_receding_plane(std::size_t width, std::size_t height, double scale) {
  receding_plane p;
  p.width = width;
  p.height = height;
  p.scale = scale;
  p.positions.resize(width * height);
  p.footprints.resize(width * height);
  const double h = 1e-3;  // the exact map is smooth: central differences to ~1e-7 relative
  for (std::size_t y = 0; y < height; ++y)
    for (std::size_t x = 0; x < width; ++x) {
      const double cx = double(x) + 0.5, cy = double(y) + 0.5;
      const hush::dvec2 c = p.at(cx, cy);
      const hush::dvec2 ax = p.at(cx + h, cy), bx = p.at(cx - h, cy);
      const hush::dvec2 ay = p.at(cx, cy + h), by = p.at(cx, cy - h);
      p.positions[y * width + x] = {static_cast<float>(c.x), static_cast<float>(c.y)};
      p.footprints[y * width + x] = hush::footprint<2>::from_derivatives(
          hush::dvec2{(ax.x - bx.x) / (2 * h), (ax.y - bx.y) / (2 * h)},
          hush::dvec2{(ay.x - by.x) / (2 * h), (ay.y - by.y) / (2 * h)});
    }
  return p;
}

std::vector<double> supersampled(const hush::anisotropic& noise, const receding_plane& plane,
                                 const std::vector<std::size_t>& pixels) {
  const int m = 9;
  const double sigma = hush::detail::constants::kPixelFilterSigma;
  std::vector<double> out;
  for (std::size_t q : pixels) {
    const std::size_t px = q % plane.width, py = q / plane.width;
    const double cx = double(px) + 0.5, cy = double(py) + 0.5;
    double acc = 0, wsum = 0;
    for (int a_y = 0; a_y < m; ++a_y)
      for (int a_x = 0; a_x < m; ++a_x) {
        const double ox = 3 * sigma * (2.0 * (a_x + 0.5) / m - 1.0);
        const double oy = 3 * sigma * (2.0 * (a_y + 0.5) / m - 1.0);
        const double w = std::exp(-(ox * ox + oy * oy) / (2 * sigma * sigma));
        acc += w * noise(plane.at(cx + ox, cy + oy));
        wsum += w;
      }
    out.push_back(acc / wsum);
  }
  return out;
}

receding_result figure9(std::size_t width, std::size_t height) {
  const receding_plane plane = make_receding_plane(width, height, 1.0);
  const std::size_t n = width * height;
  receding_result r;
  for (int k : {4, 8}) {
    const hush::anisotropic a =
        make_noise(k, 2, 0, 2, 2.0, hush::weight_rule::centre, hush::weight_rule::centre, 21);
    image filtered(width, height), unfiltered(width, height), reference(width, height);
    hush::samples<2> s;
    s.positions = plane.positions;
    s.footprints = plane.footprints;
    hush::evaluate(a, hush::exec::simd, s, hush::span<float>(filtered.v));
    hush::evaluate(a, hush::exec::simd, hush::span<const hush::vec2>(plane.positions),
                   hush::span<float>(unfiltered.v));
    // The reference: 9 x 9 point samples per pixel over +-1.5 pixels (3 sigma), Gaussian
    // weights, through the exact perspective map.
    const int m = 9;
    const double sigma = hush::detail::constants::kPixelFilterSigma;
    std::vector<double> acc(n, 0.0);
    double wsum = 0;
    std::vector<hush::vec2> pts(n);
    std::vector<float> vals(n);
    for (int a_y = 0; a_y < m; ++a_y)
      for (int a_x = 0; a_x < m; ++a_x) {
        const double ox = 3 * sigma * (2.0 * (a_x + 0.5) / m - 1.0);
        const double oy = 3 * sigma * (2.0 * (a_y + 0.5) / m - 1.0);
        const double w = std::exp(-(ox * ox + oy * oy) / (2 * sigma * sigma));
        wsum += w;
        for (std::size_t y = 0; y < height; ++y)
          for (std::size_t x = 0; x < width; ++x) {
            const hush::dvec2 q = plane.at(double(x) + 0.5 + ox, double(y) + 0.5 + oy);
            pts[y * width + x] = {static_cast<float>(q.x), static_cast<float>(q.y)};
          }
        hush::evaluate(a, hush::exec::simd, hush::span<const hush::vec2>(pts),
                       hush::span<float>(vals));
        for (std::size_t q = 0; q < n; ++q) acc[q] += w * vals[q];
      }
    for (std::size_t q = 0; q < n; ++q) reference.v[q] = static_cast<float>(acc[q] / wsum);
    auto rms = [&](const image& im) {
      double e = 0;
      for (std::size_t q = 0; q < n; ++q)
        e += (double(im.v[q]) - reference.v[q]) * (double(im.v[q]) - reference.v[q]);
      return std::sqrt(e / double(n));
    };
    if (k == 4) {
      r.filtered4 = filtered;
      r.unfiltered4 = unfiltered;
      r.reference4 = reference;
      r.rms4 = rms(filtered);
      r.rms_unfiltered4 = rms(unfiltered);
    } else {
      r.filtered8 = filtered;
      r.reference8 = reference;
      r.rms8 = rms(filtered);
      r.rms_unfiltered8 = rms(unfiltered);
    }
  }
  return r;
}

image figure13(std::size_t size, double stretch) {
  // Octave 0 at 2 cycles per unit over 8 x 8 units; the target stretched `stretch` times
  // along the field needs texture frequencies down to 2 / stretch: two scales below.
  const hush::anisotropic a =
      make_noise(8, 5, 2, 2, 2.0, hush::weight_rule::centre, hush::weight_rule::centre, 13);
  image img(size, size);
  const double extent = 8.0, d = extent / double(size);
  std::vector<hush::vec2> pos(size * size);
  std::vector<hush::footprint<2>> fps(size * size, hush::footprint<2>::isotropic(d));
  std::vector<hush::surface_map> maps(size * size);
  for (std::size_t y = 0; y < size; ++y)
    for (std::size_t x = 0; x < size; ++x) {
      const double u = (double(x) + 0.5) * d, v = (double(y) + 0.5) * d;
      const double th = std::atan2(v - 0.5 * extent, u - 0.5 * extent) + 0.5 * kPi;
      const double c = std::cos(th), s = std::sin(th);
      // A = R diag(stretch, 1) R^T: E(A^T xi) is the isotropic band squeezed to stretch
      // times lower frequencies along theta: features stretched along the field.
      pos[y * size + x] = {static_cast<float>(u), static_cast<float>(v)};
      maps[y * size + x] =
          hush::surface_map::identity().with_target(stretch * c * c + s * s, (stretch - 1) * c * s,
                                                    (stretch - 1) * c * s, stretch * s * s + c * c);
    }
  hush::samples<2> smp;
  smp.positions = pos;
  smp.footprints = fps;
  smp.surface_maps = maps;
  hush::evaluate(a, hush::exec::simd, smp, hush::span<float>(img.v));
  return img;
}

std::vector<image> figure2(int orientations, int size, std::uint32_t seed) {
  const hush::anisotropic a = make_noise(orientations, 1, 0, 1, 1.0, hush::weight_rule::centre,
                                         hush::weight_rule::centre, seed, size);
  const auto n = static_cast<std::size_t>(size);
  std::vector<image> out(static_cast<std::size_t>(orientations) + 1, image(n, n));
  for (std::size_t y = 0; y < n; ++y)
    for (std::size_t x = 0; x < n; ++x) {
      const float* t = a.tile().texel(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y));
      for (int i = 0; i < orientations; ++i) {
        out[static_cast<std::size_t>(i)].at(x, y) = t[i];
        out.back().at(x, y) += t[i];
      }
    }
  return out;
}

}  // namespace hush_tools::aniso

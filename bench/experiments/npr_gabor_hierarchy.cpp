// Throwaway experiment for docs/npr-gabor.md "Huge triangles" (not built by CMake, not part of
// hush): the hierarchical point sequence of a triangle (midpoint subdivision, Owen-style random
// child order per node) against today's independent uniform points, on one affine triangle.
//
//   g++ -O2 -std=c++17 bench/experiments/npr_gabor_hierarchy.cpp -o /tmp/hier && /tmp/hier
//
// Measures (a) the variance of the normalised noise over a window inside the triangle and its
// autocorrelation at two lags, both sequences, N swept across a power of two (LOD weights
// eq. 4); (b) that culling subtrees off a window leaves the window's image bit for bit the
// same (the restriction property); (c) the work (nodes visited) for a huge triangle.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;
// Kernel: F0 = 1/8 cycle/px along x, a = 0.08 /px, truncation 0.05 (hush's defaults).
constexpr double kF = 0.125, kA = 0.08, kTrunc = 0.05, kImpulses = 16;
const double kR = std::sqrt(std::log(1 / kTrunc) / kPi) / kA;
const double kLambda = kImpulses / (kPi * kR * kR);

std::uint64_t mix(std::uint64_t x) {  // splitmix64 finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
double unit(std::uint64_t h) { return double(h >> 11) * 0x1.0p-53; }

double kernel(double dx, double dy) {
  const double d2 = dx * dx + dy * dy;
  if (d2 > kR * kR) return 0;
  return std::exp(-kPi * kA * kA * d2) * std::cos(2 * kPi * kF * dx);
}

struct point {
  double x, y, w;  // screen position, weight x amplitude
  std::uint64_t j;
};

// The triangle on screen: s(u, v) = o + u e1 + v e2, (u, v) in the reference triangle.
struct triangle {
  double ox, oy, e1x, e1y, e2x, e2y;
  void at(double u, double v, double& x, double& y) const {
    x = ox + u * e1x + v * e2x;
    y = oy + u * e1y + v * e2y;
  }
  double area() const { return 0.5 * std::fabs(e1x * e2y - e1y * e2x); }
};

struct window {
  double x0, y0, x1, y1;  // pixels [x0, x1) x [y0, y1)
  bool near(double x, double y) const {
    return x > x0 - kR && x < x1 + kR && y > y0 - kR && y < y1 + kR;
  }
};

// LOD (hush::npr_gabor_lod): N >= 1: M = 2^floor(log2 N), 2M points, the second M at
// alpha = sqrt(N/M - 1); N < 1: one point at sqrt(N).
struct lod {
  std::uint64_t count;
  std::uint64_t m;
  double alpha;
  explicit lod(double n) {
    if (n < 1) {
      count = 1, m = 1, alpha = std::sqrt(n);
      return;
    }
    m = std::uint64_t(1) << int(std::floor(std::log2(n)));
    count = 2 * m;
    alpha = std::sqrt(n / double(m) - 1);
  }
  double weight(std::uint64_t j) const { return j < m ? (count == 1 ? alpha : 1.0) : alpha; }
};

// A uniform point of the reference triangle from two uniforms (hush's map).
void bary(double u, double v, double& a, double& b) {
  const double s = std::sqrt(u);
  a = s * (1 - v);
  b = s * v;
}

// ---- Today: point j independent and uniform on the whole triangle.
void iid_points(const triangle& t, std::uint64_t seed, const lod& l, const window& win,
                std::vector<point>& out) {
  for (std::uint64_t j = 0; j < l.count; ++j) {
    const std::uint64_t h = mix(seed ^ mix(j));
    double a, b, x, y;
    bary(unit(mix(h)), unit(mix(h + 1)), a, b);
    t.at(a, b, x, y);
    const double amp = 2 * unit(mix(h + 2)) - 1;
    if (win.near(x, y)) out.push_back({x, y, l.weight(j) * amp, j});
  }
}

// ---- Hierarchical: node = corner (pu, pv), size s, flip f (+1 upright, -1 the middle
// child's orientation), seed, global index of its own point c and stride 4^depth. Point 0 of a
// node is its own uniform point; its local point i >= 1 is point (i - 1) / 4 of the child in
// slot (i - 1) mod 4, the slots a random permutation of the 4 children per node.
struct stats {
  std::uint64_t nodes = 0;
};

void node_bbox(const triangle& t, double pu, double pv, double s, double f, double (&bb)[4]) {
  double xs[3], ys[3];
  t.at(pu, pv, xs[0], ys[0]);
  t.at(pu + f * s, pv, xs[1], ys[1]);
  t.at(pu, pv + f * s, xs[2], ys[2]);
  bb[0] = std::min({xs[0], xs[1], xs[2]});
  bb[1] = std::min({ys[0], ys[1], ys[2]});
  bb[2] = std::max({xs[0], xs[1], xs[2]});
  bb[3] = std::max({ys[0], ys[1], ys[2]});
}

void hier(const triangle& t, std::uint64_t seed, double pu, double pv, double s, double f,
          std::uint64_t c, std::uint64_t stride, const lod& l, const window& win, bool cull,
          std::vector<point>& out, stats& st) {
  if (c >= l.count) return;
  ++st.nodes;
  const std::uint64_t h = mix(seed);
  {
    double a, b, x, y;
    bary(unit(mix(h + 1)), unit(mix(h + 2)), a, b);
    t.at(pu + f * s * a, pv + f * s * b, x, y);
    const double amp = 2 * unit(mix(h + 3)) - 1;
    if (win.near(x, y)) out.push_back({x, y, l.weight(c) * amp, c});
  }
  if (stride > (std::uint64_t(1) << 60)) return;  // index width (2M <= 2^61 here)
  // Random order of the 4 children: one of 24 permutations.
  int perm[4] = {0, 1, 2, 3};
  std::uint64_t r = mix(h + 4);
  for (int k = 3; k > 0; --k) {
    const int q = int(r % std::uint64_t(k + 1));
    r /= std::uint64_t(k + 1);
    std::swap(perm[k], perm[q]);
  }
  const double hs = s / 2;
  const double cu[4] = {pu, pu + f * hs, pu, pu + f * hs};
  const double cv[4] = {pv, pv, pv + f * hs, pv + f * hs};
  const double cf[4] = {f, f, f, -f};
  for (int d = 0; d < 4; ++d) {
    const int ch = perm[d];
    const std::uint64_t cc = c + stride * std::uint64_t(1 + d);
    if (cc >= l.count) continue;
    if (cull) {
      double bb[4];
      node_bbox(t, cu[ch], cv[ch], hs, cf[ch], bb);
      if (bb[2] < win.x0 - kR || bb[0] > win.x1 + kR || bb[3] < win.y0 - kR || bb[1] > win.y1 + kR)
        continue;
    }
    hier(t, mix(seed ^ std::uint64_t(ch + 1) * 0x632be59bd9b4e019ull), cu[ch], cv[ch], hs, cf[ch],
         cc, stride * 4, l, win, cull, out, st);
  }
}

// The window's image, normalised to unit variance (Campbell: lambda E[v^2] sum g^2).
std::vector<double> splat(const std::vector<point>& pts, const window& win) {
  const int w = int(win.x1 - win.x0), h = int(win.y1 - win.y0);
  double e = 0;  // integral of g^2 by a fine sum
  for (double y = -kR; y <= kR; y += 0.05)
    for (double x = -kR; x <= kR; x += 0.05) e += kernel(x, y) * kernel(x, y) * 0.0025;
  const double scale = 1 / std::sqrt(kLambda * (1.0 / 3.0) * e);
  std::vector<double> img(std::size_t(w) * h, 0.0);
  for (const point& p : pts)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        img[std::size_t(y) * w + x] +=
            scale * p.w * kernel(win.x0 + x + 0.5 - p.x, win.y0 + y + 0.5 - p.y);
  return img;
}

}  // namespace

int main() {
  const window win{400, 400, 464, 464};  // 64 x 64 px inside the triangle
  const int seeds = 40;
  // (a) variance and autocorrelation, N swept from 2^k to 2^(k+1).
  std::printf("(a) window 64x64, %d seeds; Var and rho(2,0), rho(4,1) (kernel's: see last row)\n",
              seeds);
  std::printf("  scale  N        iid: var  rho20   rho41   | hier: var  rho20   rho41\n");
  for (double sc : {1.0, 1.19, 1.41, 1.68, 2.0}) {
    const double leg = 1200 * sc;
    const triangle t{0, 0, leg, 0, 0, leg};
    const lod l(kLambda * t.area());
    double acc[2][3] = {{0, 0, 0}, {0, 0, 0}};
    for (int s = 0; s < seeds; ++s) {
      for (int which = 0; which < 2; ++which) {
        std::vector<point> pts;
        stats st;
        if (which == 0)
          iid_points(t, std::uint64_t(s) * 7919 + 1, l, win, pts);
        else
          hier(t, std::uint64_t(s) * 7919 + 1, 0, 0, 1, 1, 0, 1, l, win, true, pts, st);
        const std::vector<double> img = splat(pts, win);
        double v = 0, r20 = 0, r41 = 0;
        for (int y = 0; y < 64; ++y)
          for (int x = 0; x < 64; ++x) {
            const double a = img[std::size_t(y) * 64 + x];
            v += a * a;
            if (x + 2 < 64) r20 += a * img[std::size_t(y) * 64 + x + 2];
            if (x + 4 < 64 && y + 1 < 64) r41 += a * img[std::size_t(y + 1) * 64 + x + 4];
          }
        acc[which][0] += v / 4096;
        acc[which][1] += r20 / (62 * 64);
        acc[which][2] += r41 / (60 * 63);
      }
    }
    std::printf("  %.2f  %8.0f  %.4f  %+.4f %+.4f | %.4f  %+.4f %+.4f\n", sc,
                kLambda * t.area(), acc[0][0] / seeds, acc[0][1] / acc[0][0],
                acc[0][2] / acc[0][0], acc[1][0] / seeds, acc[1][1] / acc[1][0],
                acc[1][2] / acc[1][0]);
  }
  {
    double g0 = 0, g20 = 0, g41 = 0;  // kernel autocorrelation (the spectrum's transform)
    for (double y = -kR - 5; y <= kR + 5; y += 0.1)
      for (double x = -kR - 5; x <= kR + 5; x += 0.1) {
        g0 += kernel(x, y) * kernel(x, y);
        g20 += kernel(x, y) * kernel(x + 2, y);
        g41 += kernel(x, y) * kernel(x + 4, y + 1);
      }
    std::printf("  kernel autocorrelation: rho20 %+.4f rho41 %+.4f\n", g20 / g0, g41 / g0);
  }
  // (b) culling leaves the window's points (and image) unchanged, bit for bit.
  {
    const triangle t{0, 0, 3000, 0, 0, 3000};
    const lod l(kLambda * t.area());
    std::vector<point> a, b;
    stats sa, sb;
    hier(t, 99, 0, 0, 1, 1, 0, 1, l, win, false, a, sa);
    hier(t, 99, 0, 0, 1, 1, 0, 1, l, win, true, b, sb);
    auto by_j = [](const point& p, const point& q) { return p.j < q.j; };
    std::sort(a.begin(), a.end(), by_j);
    std::sort(b.begin(), b.end(), by_j);
    bool same = a.size() == b.size();
    for (std::size_t i = 0; same && i < a.size(); ++i)
      same = a[i].j == b[i].j && a[i].x == b[i].x && a[i].y == b[i].y && a[i].w == b[i].w;
    std::printf("(b) N = %.0f: window points without culling %zu (nodes %llu), with culling %zu "
                "(nodes %llu): %s\n",
                kLambda * t.area(), a.size(), (unsigned long long)sa.nodes, b.size(),
                (unsigned long long)sb.nodes, same ? "identical" : "DIFFERENT");
  }
  // (c) a huge triangle: N far above kNprGaborMaxPoints (2^22); work with culling.
  for (double leg : {1e5, 1e6, 1e7}) {
    const triangle t{0, 0, leg, 0, 0, leg};
    const lod l(kLambda * t.area());
    double var = 0;
    std::uint64_t nodes = 0, pts_n = 0;
    for (int s = 0; s < 10; ++s) {
      std::vector<point> pts;
      stats st;
      hier(t, std::uint64_t(s) + 5, 0, 0, 1, 1, 0, 1, l, win, true, pts, st);
      nodes += st.nodes;
      pts_n += pts.size();
      const std::vector<double> img = splat(pts, win);
      for (double v : img) var += v * v / 4096;
    }
    std::printf("(c) leg %.0e px, N = %.3g (clamp today: 4.19e6): var %.4f, nodes visited %.0f, "
                "points near the window %.0f (per seed)\n",
                leg, kLambda * t.area(), var / 10, double(nodes) / 10, double(pts_n) / 10);
  }
  return 0;
}

// hush — temporal-coherence metrics: flatness (see flatness.hpp).
#include "coherence/flatness.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <tuple>
#include <unsupported/Eigen/FFT>

namespace hush_tools {
namespace coherence {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

// One analysis window's contribution to its region.
struct window_stats {
  std::uint32_t object;
  double depth;         // mean depth of its pixels
  double power;         // sum of P(k) over every frequency k
  double power_moment;  // sum of |k|^2 P(k), k in cycles per pixel (signed, fftfreq)
  double variance;
  std::size_t order;  // scan order, the tie-break that keeps the sort deterministic
};

// Population coefficient of variation and max/min of `v` (size >= 2).
void spread(const std::vector<double>& v, double& cv, double& ratio) {
  double mean = 0;
  for (double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  double sq = 0;
  for (double x : v) sq += (x - mean) * (x - mean);
  cv = std::sqrt(sq / static_cast<double>(v.size())) / mean;
  const auto mm = std::minmax_element(v.begin(), v.end());
  ratio = *mm.second / *mm.first;  // +inf when a region is constant (variance 0)
}

// FFT plan, window tables and buffers, made once per sequence.
class window_analyser {
 public:
  explicit window_analyser(int size) : n_(static_cast<std::size_t>(size)) {
    hann_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i)
      hann_[i] =
          0.5 - 0.5 * std::cos(2 * kPi * (static_cast<double>(i) + 0.5) / static_cast<double>(n_));
    // Squared frequency (cycles per pixel) of half-spectrum bin k = 0 ... n/2, times the
    // number of full-spectrum bins it stands for (k and n - k; once for 0 and n/2).
    weighted_f2_.resize(n_ / 2 + 1);
    for (std::size_t k = 0; k <= n_ / 2; ++k) {
      const double f = static_cast<double>(k) / static_cast<double>(n_);
      weighted_f2_[k] = f * f * ((k == 0 || 2 * k == n_) ? 1 : 2);
    }
    a_.resize(n_ * n_);
    line_.resize(n_);
    fft_.SetFlag(Eigen::FFT<double>::HalfSpectrum);
    // The window's own spectrum |W|^2: the spectrum of constant 1 seen through it.
    const std::vector<float> ones(n_ * n_, 1.0f);
    window_stats s{};
    transform(ones.data(), 0, n_, 0.0, s);
    window_moment_ = s.power_moment / s.power;
  }

  // Second moment of the window's power spectrum, sum |k|^2 |W(k)|^2 / sum |W(k)|^2. The
  // expected periodogram of windowed stationary noise is its spectrum convolved with |W|^2,
  // and second moments of a convolution add (both are centred), so subtracting this from a
  // region's measured moment leaves the noise's own (up to wrap-around at Nyquist).
  double window_moment() const { return window_moment_; }

  // Spectrum statistics of the window whose top-left pixel is `origin` in `values` (row
  // length `stride`), its mean removed.
  void analyse(const float* values, std::size_t origin, std::size_t stride, window_stats& s) {
    double mean = 0;
    for (std::size_t y = 0; y < n_; ++y)
      for (std::size_t x = 0; x < n_; ++x) mean += values[origin + y * stride + x];
    mean /= static_cast<double>(n_ * n_);
    transform(values, origin, stride, mean, s);
  }

 private:
  // Variance of (values - mean) and the power moments of its Hann-windowed 2D DFT F:
  //   power        = sum_k |F(k)|^2                 = n^2 sum_x a(x)^2          (Parseval)
  //   power_moment = sum_k (kx^2 + ky^2) |F(k)|^2
  //                = n sum_rows sum_kx kx^2 |R(kx)|^2 + n sum_cols sum_ky ky^2 |C(ky)|^2,
  // with R, C the 1D DFTs of the rows and columns of a: the DFT along the other axis only
  // multiplies each frequency's energy by n (Parseval again). So the 2D spectrum's moments
  // take 2n real 1D FFTs (Eigen, half spectrum) instead of 2n complex ones.
  void transform(const float* values, std::size_t origin, std::size_t stride, double mean,
                 window_stats& s) {
    double sq = 0, windowed_sq = 0;
    for (std::size_t y = 0; y < n_; ++y)
      for (std::size_t x = 0; x < n_; ++x) {
        const double v = values[origin + y * stride + x] - mean;
        sq += v * v;
        const double w = v * hann_[x] * hann_[y];
        a_[y * n_ + x] = w;
        windowed_sq += w * w;
      }
    s.variance = sq / static_cast<double>(n_ * n_);
    const double n = static_cast<double>(n_);
    s.power = n * n * windowed_sq;
    double moment = 0;
    for (std::size_t y = 0; y < n_; ++y) {  // rows: the kx part
      std::copy(a_.begin() + static_cast<std::ptrdiff_t>(y * n_),
                a_.begin() + static_cast<std::ptrdiff_t>((y + 1) * n_), line_.begin());
      fft_.fwd(spectrum_, line_);
      for (std::size_t k = 0; k <= n_ / 2; ++k) moment += weighted_f2_[k] * std::norm(spectrum_[k]);
    }
    for (std::size_t x = 0; x < n_; ++x) {  // columns: the ky part
      for (std::size_t y = 0; y < n_; ++y) line_[y] = a_[y * n_ + x];
      fft_.fwd(spectrum_, line_);
      for (std::size_t k = 0; k <= n_ / 2; ++k) moment += weighted_f2_[k] * std::norm(spectrum_[k]);
    }
    s.power_moment = n * moment;
  }

  std::size_t n_;
  std::vector<double> hann_, weighted_f2_, a_, line_;
  std::vector<std::complex<double>> spectrum_;
  double window_moment_ = 0;
  Eigen::FFT<double> fft_;
};

flatness_frame measure_frame(const noise_frame& values, const scene::gbuffer& g, const options& o,
                             window_analyser& analyser, std::vector<window_stats>& windows) {
  flatness_frame f;
  const std::size_t w = static_cast<std::size_t>(g.width), n = static_cast<std::size_t>(o.window);
  const std::size_t step = static_cast<std::size_t>(o.window_stride);
  windows.clear();
  for (std::size_t y0 = 0; y0 + n <= static_cast<std::size_t>(g.height); y0 += step)
    for (std::size_t x0 = 0; x0 + n <= w; x0 += step) {
      const std::size_t origin = y0 * w + x0;
      const std::uint32_t id = g.object_id[origin];
      if (id == 0) continue;
      bool inside = true;
      double depth = 0;
      for (std::size_t y = 0; y < n && inside; ++y)
        for (std::size_t x = 0; x < n; ++x) {
          const std::size_t p = origin + y * w + x;
          if (g.object_id[p] != id) {
            inside = false;
            break;
          }
          depth += g.depth[p];
        }
      if (!inside) continue;
      window_stats s{id, depth / static_cast<double>(n * n), 0, 0, 0, windows.size()};
      analyser.analyse(values.data(), origin, w, s);
      windows.push_back(s);
    }
  f.windows = windows.size();
  std::sort(windows.begin(), windows.end(), [](const window_stats& a, const window_stats& b) {
    return std::tie(a.object, a.depth, a.order) < std::tie(b.object, b.depth, b.order);
  });

  // Quantile bins per object: as many as hold min_windows windows each, at most depth_bins;
  // bin b of an object's m windows holds ranks [b m / B, (b + 1) m / B). An object with
  // fewer than min_windows windows has no region (counted in dropped_objects).
  for (std::size_t begin = 0; begin < windows.size();) {
    std::size_t end = begin;
    while (end < windows.size() && windows[end].object == windows[begin].object) ++end;
    const std::size_t m = end - begin;
    const std::size_t bins = std::min(static_cast<std::size_t>(o.depth_bins), m / o.min_windows);
    if (bins == 0) ++f.dropped_objects;
    for (std::size_t b = 0; b < bins; ++b) {
      const std::size_t lo = begin + b * m / bins, hi = begin + (b + 1) * m / bins;
      flatness_region r;
      r.object = windows[begin].object;
      r.depth_bin = static_cast<int>(b);
      r.windows = hi - lo;
      double power = 0, power_moment = 0;
      for (std::size_t k = lo; k < hi; ++k) {
        r.mean_depth += windows[k].depth;
        r.variance += windows[k].variance;
        power += windows[k].power;
        power_moment += windows[k].power_moment;
      }
      r.mean_depth /= static_cast<double>(r.windows);
      r.variance /= static_cast<double>(r.windows);
      // The window's own second moment is subtracted (see window_analyser); a negative
      // difference (noise band-limited below the window's resolution) is clamped to 0.
      r.frequency = power > 0
                        ? std::sqrt(std::max(0.0, power_moment / power - analyser.window_moment()))
                        : kNaN;
      f.regions.push_back(r);
    }
    begin = end;
  }

  f.frequency_cv = f.frequency_ratio = f.variance_cv = f.variance_ratio = kNaN;
  if (f.regions.size() < 2) {
    f.reason = std::to_string(f.regions.size()) +
               " region(s) with >= " + std::to_string(o.min_windows) + " windows of " +
               std::to_string(o.window) + "x" + std::to_string(o.window) +
               " pixels inside one object (need 2)";
    return f;
  }
  std::vector<double> freq, var;
  for (const flatness_region& r : f.regions) {
    if (!(r.variance > 0)) {
      f.reason = "a region has constant noise (zero variance)";
      return f;
    }
    freq.push_back(r.frequency);
    var.push_back(r.variance);
  }
  spread(freq, f.frequency_cv, f.frequency_ratio);
  spread(var, f.variance_cv, f.variance_ratio);
  return f;
}

}  // namespace

flatness_metrics measure_flatness(const std::vector<noise_frame>& frames,
                                  const std::vector<scene::gbuffer>& gbuffers, const options& o) {
  validate(o);
  validate_sequence(frames, gbuffers);
  flatness_metrics m;
  window_analyser analyser(o.window);
  std::vector<window_stats> windows;
  std::vector<double> all_freq, all_var;  // every region of every frame
  std::size_t valued = 0;
  m.frequency_cv_max = m.variance_cv_max = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    flatness_frame f = measure_frame(frames[i], gbuffers[i], o, analyser, windows);
    f.frame = static_cast<int>(i);
    if (f.reason.empty()) {
      for (const flatness_region& r : f.regions) {
        all_freq.push_back(r.frequency);
        all_var.push_back(r.variance);
      }
      ++valued;
      m.frequency_cv += f.frequency_cv;
      m.frequency_ratio += f.frequency_ratio;
      m.variance_cv += f.variance_cv;
      m.variance_ratio += f.variance_ratio;
      m.frequency_cv_max = std::max(m.frequency_cv_max, f.frequency_cv);
      m.variance_cv_max = std::max(m.variance_cv_max, f.variance_cv);
    } else {
      ++m.frames_without_value;
    }
    m.frames.push_back(std::move(f));
  }
  if (valued == 0) {
    m.reason = "no frame has 2 measurable regions (see frames[].reason)";
    m.frequency_cv = m.frequency_ratio = m.variance_cv = m.variance_ratio = kNaN;
    m.frequency_cv_max = m.variance_cv_max = kNaN;
    m.pooled_frequency_cv = m.pooled_frequency_ratio = kNaN;
    m.pooled_variance_cv = m.pooled_variance_ratio = kNaN;
    return m;
  }
  spread(all_freq, m.pooled_frequency_cv, m.pooled_frequency_ratio);
  spread(all_var, m.pooled_variance_cv, m.pooled_variance_ratio);
  const double v = static_cast<double>(valued);
  m.frequency_cv /= v;
  m.frequency_ratio /= v;
  m.variance_cv /= v;
  m.variance_ratio /= v;
  return m;
}

}  // namespace coherence
}  // namespace hush_tools

// hush — the `hush` program: `hush sample wavelet` (hush/wavelet.hpp), its noise_table entry.
//
// Without --footprint and --normal the grid goes through hush::evaluate_grid; with either,
// every sample is evaluated through hush::evaluate over hush::samples (positions as floats,
// the same isotropic footprint and normal for every sample), on the chosen backend.
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "glsl_device.hpp"
#include "noises.hpp"

namespace hush_cli {
namespace {

struct wavelet_sample_options {
  double footprint = -1;  // < 0: none given
  bool has_normal = false;
  hush::vec3 normal{};
};

template <int D>
class wavelet_field final : public noise_field {
 public:
  wavelet_field(hush::wavelet<D> noise, wavelet_sample_options o)
      : noise_(std::move(noise)), o_(o) {}
  bool is_signed() const override { return true; }
  std::string unsupported_reason(backend b) const override {
    if (b == backend::glsl && !HUSH_CLI_HAVE_GLSL)
      return "the GLSL backend is not in this build (OSMesa not found)";
    if (b == backend::simd && !HUSH_CONFIG_SIMD)
      return "the SIMD backend is not in this build (Highway, libhwy-dev, was not found)";
    return "";
  }
  void sample_rows(const sample_grid& grid, std::size_t j0, std::size_t rows, std::size_t k,
                   float* out, backend b) const override {
    const hush::span<float> dst(out, grid.size[0] * rows);
    if (o_.footprint < 0 && !o_.has_normal) {
      hush::grid<D> block;  // origin: the exact double position of sample (0, j0, k)
      const hush::dvec3 org = grid.position({0, j0, k});
      for (int a = 0; a < D; ++a) {
        block.origin[a] = org[a];
        block.step[a] = grid.step[a];
      }
      block.size[0] = grid.size[0];
      block.size[1] = rows;
      if constexpr (D == 3) block.size[2] = 1;
      run(b, [&](auto policy) { hush::evaluate_grid(noise_, policy, block, dst); });
      return;
    }
    std::vector<hush::vec<float, D>> pos(dst.size());
    for (std::size_t j = 0; j < rows; ++j)
      for (std::size_t i = 0; i < grid.size[0]; ++i) {
        const hush::dvec3 p = grid.position({i, j0 + j, k});
        for (int a = 0; a < D; ++a) pos[j * grid.size[0] + i][a] = static_cast<float>(p[a]);
      }
    std::vector<hush::footprint<D>> fps;
    if (o_.footprint >= 0) fps.assign(pos.size(), hush::footprint<D>::isotropic(o_.footprint));
    std::vector<hush::vec3> nrm;
    if (o_.has_normal) nrm.assign(pos.size(), o_.normal);
    hush::samples<D> s;
    s.positions = pos;
    s.footprints = fps;
    s.normals = nrm;
    run(b, [&](auto policy) { hush::evaluate(noise_, policy, s, dst); });
  }

 private:
  template <class F>
  static void run(backend b, F&& f) {
    if (b == backend::simd) {
      f(hush::exec::simd);
      return;
    }
#if HUSH_CLI_HAVE_GLSL
    if (b == backend::glsl) {
      f(hush::exec::glsl{glsl_device()});
      return;
    }
#endif
    f(hush::exec::scalar);
  }
  hush::wavelet<D> noise_;
  wavelet_sample_options o_;
};

template <int D>
std::unique_ptr<noise_field> make_wavelet_d(const noise_setup& setup, const option_values& given,
                                            const wavelet_sample_options& so) {
  typename hush::wavelet<D>::params prm;
  prm.seed = setup.seed;
  if (const std::string* v = find_value(given, "--tile-size"))
    prm.tile_size = static_cast<int>(parse_integer("--tile-size", *v, 0, 1 << 20));
  if (const std::string* v = find_value(given, "--first-band"))
    prm.first_band = static_cast<int>(parse_integer("--first-band", *v, -1000, 1000));
  const std::string* bands = find_value(given, "--bands");
  const std::string* weights = find_value(given, "--weights");
  if (bands && weights) throw usage_error("--bands and --weights: give one of them, not both");
  if (bands) {
    const auto n =
        static_cast<std::size_t>(parse_integer("--bands", *bands, 1, hush::wavelet<D>::kMaxBands));
    prm.weights.clear();
    for (std::size_t i = 0; i < n; ++i)
      prm.weights.push_back(std::ldexp(1.0, -static_cast<int>(i)));
  }
  if (weights) {
    const std::vector<std::string> parts = split(*weights, ',');
    if (parts.size() > static_cast<std::size_t>(hush::wavelet<D>::kMaxBands))
      throw_bad_value("--weights", *weights, "1 ... 32 comma-separated finite numbers");
    prm.weights.clear();
    for (const std::string& p : parts) prm.weights.push_back(parse_finite("--weights", p));
  }
  if (const std::string* v = find_value(given, "--distribution"))
    prm.distribution = parse_choice<hush::wavelet_distribution>(
        "--distribution", *v,
        {{"gaussian", hush::wavelet_distribution::gaussian},
         {"uniform", hush::wavelet_distribution::uniform}});
  if (const std::string* v = find_value(given, "--projection"))
    prm.projection = parse_choice<hush::wavelet_projection>(
        "--projection", *v,
        {{"exact", hush::wavelet_projection::exact},
         {"approximate", hush::wavelet_projection::approximate}});
  if (const std::string* v = find_value(given, "--widen"))
    prm.widen = parse_choice<bool>("--widen", *v, {{"on", true}, {"off", false}});
  if (const std::string* v = find_value(given, "--variants"))
    prm.variant_overlap = static_cast<int>(parse_integer("--variants", *v, 0, 1 << 20));
  return std::make_unique<wavelet_field<D>>(hush::wavelet<D>(prm), so);
}

}  // namespace

std::unique_ptr<noise_field> make_wavelet_from_options(const noise_setup& setup,
                                                       const option_values& given) {
  wavelet_sample_options so;
  if (const std::string* v = find_value(given, "--footprint")) {
    so.footprint = parse_finite("--footprint", *v, "a finite width >= 0 in noise units");
    if (so.footprint < 0) throw_bad_value("--footprint", *v, "a finite width >= 0 in noise units");
  }
  if (const std::string* v = find_value(given, "--normal")) {
    if (setup.dim != 3)
      throw usage_error("--normal needs --dim 3 (noise projected onto a surface)");
    const std::vector<double> n = parse_finite_list("--normal", *v, 3);
    if (n[0] == 0 && n[1] == 0 && n[2] == 0)
      throw_bad_value("--normal", *v, "three finite numbers, not all zero");
    so.has_normal = true;
    for (int a = 0; a < 3; ++a) so.normal[a] = static_cast<float>(n[static_cast<std::size_t>(a)]);
  }
  if (setup.dim == 2) return make_wavelet_d<2>(setup, given, so);
  return make_wavelet_d<3>(setup, given, so);
}

}  // namespace hush_cli

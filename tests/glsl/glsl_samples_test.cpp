// The GLSL samples layout (compute_source.hpp, device::evaluate_samples):
// positions, footprints and normals reach the shader per sample, at the right
// index, in every batch, for plain and banded programs. Checked with the
// probe noise (tests/probe_noise.hpp), whose values are exact in float, so
// GPU and CPU must agree bit for bit.
#include <doctest/doctest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "glsl_test_util.hpp"
#include "hush/glsl/device.hpp"
#include "probe_noise.hpp"

namespace hush_test {

// A banded variant: two bands at positions q_b = (b + 1) p, each adding
// (b + 1) q_b.x, i.e. 5 p.x in all, plus S00 and the normal's z (0 without).
template <int D>
class banded_probe : public hush::sample_noise<banded_probe<D>, D> {
 public:
  static constexpr bool takes_footprint = true;
  static constexpr bool takes_normal = D == 3;
  static constexpr bool takes_surface_map = D == 2;
  template <class T>
  T value(const hush::vec<double, D>& p) const {
    return T(5) * T(p[0]);
  }
  template <class T>
  hush::value_gradient<T, D> value_and_gradient(const hush::vec<double, D>& p) const {
    hush::value_gradient<T, D> r{value<T>(p), {}};
    r.gradient[0] = T(5);
    return r;
  }
  template <class T>
  T sample_value(const hush::sample_input<D>& s) const {
    return value<T>(s.position) + T(s.fp.covariance(0, 0)) + (s.has_normal ? T(s.normal.z) : T(0)) +
           (s.has_map ? T(s.map.m01) : T(0));
  }
  template <class T>
  hush::value_gradient<T, D> sample_value_and_gradient(const hush::sample_input<D>& s) const {
    hush::value_gradient<T, D> r = value_and_gradient<T>(s.position);
    r.value = sample_value<T>(s);
    return r;
  }
};

}  // namespace hush_test

namespace hush {
namespace glsl {

// The probe's GLSL: a user-side program, written as any extension would be.
template <int D>
struct noise_program<hush_test::probe_noise<D>> {
  static constexpr int dimension = D;
  static constexpr const char* name = D == 2 ? "probe2" : "probe3";
  static std::string uniforms() { return ""; }
  static std::string value_of(const std::string& p) {
    return D == 2 ? "(" + p + ".x + " + p + ".y / 2.0)"
                  : "(" + p + ".x + " + p + ".y / 2.0 + " + p + ".z / 4.0)";
  }
  static std::string with_gradient(const std::string& v, bool gradient) {
    if (!gradient) return v;
    return D == 2 ? "vec3(" + v + ", 1.0, 0.5)" : "vec4(" + v + ", 1.0, 0.5, 0.25)";
  }
  static std::string point_call(bool gradient) { return with_gradient(value_of("p"), gradient); }
  static std::string cells_call(bool gradient) {
    return with_gradient(value_of("(vec" + std::to_string(D) + "(i0) + f)"), gradient);
  }
  static std::string sample_call(bool gradient) {
    const std::string last = std::to_string(D - 1);
    return with_gradient("(" + value_of("p") + " + (fp[0][0] + fp[1][0] / 2.0 + fp[" + last + "][" +
                             last + "] / 4.0) + (has_nrm ? 2.0 * nrm.x + 4.0 * nrm.z : -8.0) + " +
                             "(has_smap ? ((smap[0][0] + smap[1][0] / 2.0) + smap[0][1] / 4.0) + "
                             "smap[1][1] / 8.0 : 0.0))",
                         gradient);
  }
  static std::uint32_t period(const hush_test::probe_noise<D>&, int) { return 0; }
  static void set_uniforms(const detail::gl_api&, detail::gl_uint,
                           const hush_test::probe_noise<D>&) {}
};

template <int D>
struct noise_program<hush_test::banded_probe<D>> {
  static constexpr int dimension = D;
  static constexpr const char* name = D == 2 ? "banded_probe2" : "banded_probe3";
  static constexpr bool banded = true;
  static std::string uniforms() { return ""; }
  static int band_count(const hush_test::banded_probe<D>&) { return 2; }
  static std::uint32_t band_period(const hush_test::banded_probe<D>&, int, int) { return 0; }
  static vec<double, D> band_position(const hush_test::banded_probe<D>&, int band,
                                      const vec<double, D>& p) {
    vec<double, D> q;
    for (int a = 0; a < D; ++a) q[a] = p[a] * (band + 1);
    return q;
  }
  static std::string band_begin(bool) { return "  float acc = 0.0;\n"; }
  static std::string band_step(bool) {
    return "    acc += float(b + 1u) * (float(int(i0.x)) + f.x);\n";
  }
  static std::string band_result(bool gradient) {
    const std::string v =
        "(acc + fp[0][0] + (has_nrm ? nrm.z : 0.0) + (has_smap ? smap[1][0] : 0.0))";
    if (!gradient) return v;
    return D == 2 ? "vec3(" + v + ", 5.0, 0.0)" : "vec4(" + v + ", 5.0, 0.0, 0.0)";
  }
  static void set_uniforms(const detail::gl_api&, detail::gl_uint,
                           const hush_test::banded_probe<D>&) {}
};

}  // namespace glsl
}  // namespace hush

namespace {

// n samples whose every input is a small multiple of 1/8 (exact in float).
template <int D>
hush::samples<D> make_samples(std::size_t n, std::vector<hush::vec<float, D>>& pos,
                              std::vector<hush::footprint<D>>& fps, std::vector<hush::vec3>& nrm,
                              std::vector<hush::surface_map>* maps = nullptr) {
  pos.clear();
  fps.clear();
  nrm.clear();
  if (maps) {
    maps->clear();
    for (std::size_t i = 0; i < n; ++i)
      maps->push_back({float(i % 3) / 8.0f, -float(i % 5) / 8.0f, float(i % 7) / 8.0f, 0.25f});
  }
  for (std::size_t i = 0; i < n; ++i) {
    hush::vec<float, D> p;
    for (int a = 0; a < D; ++a) p[std::size_t(a)] = float(int(i % 23) - 11 + 3 * a) / 8.0f;
    pos.push_back(p);
    hush::vec<double, D> dx{}, dy{};
    dx[0] = double(i % 5) / 2.0;
    dx[1] = double(i % 2) / 2.0;
    dy[D - 1] = double(i % 3) / 2.0;
    fps.push_back(hush::footprint<D>::from_derivatives(dx, dy));
    nrm.push_back({float(i % 4) / 8.0f, -0.5f, float(i % 7) / 8.0f});
  }
  hush::samples<D> s{pos, fps,
                     D == 3 ? hush::span<const hush::vec3>(nrm) : hush::span<const hush::vec3>()};
  if (maps) s.surface_maps = *maps;
  return s;
}

template <class Noise>
void check_equal_to_scalar(const Noise& noise, const hush::samples<Noise::dimension>& s,
                           hush::glsl::device& dev) {
  constexpr int D = Noise::dimension;
  std::vector<float> cpu(s.size()), gpu(s.size());
  std::vector<hush::vec<float, D>> cg(s.size()), gg(s.size());
  hush::evaluate(noise, hush::exec::scalar, s, cpu, cg);
  hush::evaluate(noise, hush::exec::glsl{dev}, s, gpu, gg);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < s.size(); ++i) differ += (cpu[i] != gpu[i] || !(cg[i] == gg[i]));
  CHECK(differ == 0);
  hush::evaluate(noise, hush::exec::glsl{dev}, s, gpu);  // values only
  CHECK(gpu == cpu);
}

}  // namespace

TEST_CASE_TEMPLATE("glsl samples: positions, footprints and normals reach each sample exactly", Dim,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = Dim::value;
  auto& dev = hush_glsl_test::headless().device;
  std::vector<hush::vec<float, D>> pos;
  std::vector<hush::footprint<D>> fps;
  std::vector<hush::vec3> nrm;
  hush::samples<D> s = make_samples<D>(1000, pos, fps, nrm);
  const hush_test::probe_noise<D> probe;
  const hush_test::banded_probe<D> banded;
  check_equal_to_scalar(probe, s, dev);
  check_equal_to_scalar(banded, s, dev);
  // Each input alone: the absent one must read as absent (S = 0, or no normal).
  s.footprints = {};
  if (D == 3) {
    check_equal_to_scalar(probe, s, dev);
    check_equal_to_scalar(banded, s, dev);
  }
  s.footprints = fps;
  s.normals = {};
  check_equal_to_scalar(probe, s, dev);
  check_equal_to_scalar(banded, s, dev);
}

TEST_CASE("glsl samples: surface maps reach each sample exactly (binding 4)") {
  auto& dev = hush_glsl_test::headless().device;
  std::vector<hush::vec2> pos;
  std::vector<hush::footprint<2>> fps;
  std::vector<hush::vec3> nrm;
  std::vector<hush::surface_map> maps;
  hush::samples<2> s = make_samples<2>(1000, pos, fps, nrm, &maps);
  check_equal_to_scalar(hush_test::probe_noise<2>{}, s, dev);
  check_equal_to_scalar(hush_test::banded_probe<2>{}, s, dev);
  s.footprints = {};  // maps alone
  check_equal_to_scalar(hush_test::probe_noise<2>{}, s, dev);
  check_equal_to_scalar(hush_test::banded_probe<2>{}, s, dev);
}

TEST_CASE("glsl samples: batches split by the buffer limit give the same results") {
  // 96-byte buffers: 4 samples' footprints (3D: 24 bytes each) per batch, and 1 sample's
  // banded triples (2 bands x 3 axes x 3 words = 72 bytes).
  (void)hush_glsl_test::headless();  // the context current on this thread
  hush::glsl::device::options opt;
  opt.max_buffer_bytes = 96;
  hush::glsl::device small(hush_glsl_test::headless().context.loader(), opt);
  std::vector<hush::vec3> pos, nrm;
  std::vector<hush::footprint<3>> fps;
  const hush::samples<3> s = make_samples<3>(101, pos, fps, nrm);
  check_equal_to_scalar(hush_test::probe_noise<3>{}, s, small);
  check_equal_to_scalar(hush_test::banded_probe<3>{}, s, small);
  CHECK(small.dispatches() > 100);
  // A buffer too small for one sample's input is refused, not looped over forever.
  opt.max_buffer_bytes = 64;
  hush::glsl::device tiny(hush_glsl_test::headless().context.loader(), opt);
  std::vector<float> out(s.size());
  CHECK_THROWS_WITH_AS(hush::evaluate(hush_test::banded_probe<3>{}, hush::exec::glsl{tiny}, s, out),
                       doctest::Contains("max_buffer_bytes() = 64"), hush::invalid_argument);
}

// The GLSL package test's consumer: evaluates Perlin noise (2D and 3D, points and a grid) with
// hush::evaluate on hush::exec::glsl{device}, on the headless context HUSH_GL_CONTEXT picks
// (OSMesa's llvmpipe by default), and exits 0 only if every value is within the backend's
// stated tolerance of the CPU float path (hush/glsl/device.hpp): 2^-15 on llvmpipe, twice that
// on a GPU (EGL), whose float operations may err by 2 ulp.
#include <hush/glsl/headless.hpp>
#include <hush/hush.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

namespace {

// Largest |gpu - cpu| over the two arrays; NaN in either counts as infinitely far.
double worst_difference(const std::vector<float>& gpu, const std::vector<float>& cpu) {
  double worst = 0;
  for (std::size_t i = 0; i < gpu.size(); ++i) {
    const double d = std::fabs(double(gpu[i]) - double(cpu[i]));
    worst = std::isnan(d) ? INFINITY : (d > worst ? d : worst);
  }
  return worst;
}

}  // namespace

int main() {
  hush::glsl::headless_device gl;
  const double tolerance = std::ldexp(1.0, -15) * (gl.context.kind() == "egl" ? 2 : 1);
  auto exec = hush::exec::glsl{gl.device};

  const hush::perlin<2> noise2{/*seed=*/7};
  std::vector<hush::vec2> points;
  for (int i = 0; i < 257; ++i)
    points.push_back({0.37f * float(i) - 40.0f, 0.91f * float(i % 31) + 1000.25f});
  std::vector<float> gpu2(points.size()), cpu2(points.size());
  hush::evaluate(noise2, exec, points, gpu2);
  hush::evaluate(noise2, hush::exec::scalar, points, cpu2);

  const hush::perlin<3> noise3{/*seed=*/11};
  hush::grid<3> g;
  g.origin = {-3.0, 2.5, 100.0};
  g.step = {0.173, 0.219, 0.131};
  g.size = {19, 17, 13};
  std::vector<float> gpu3(g.count()), cpu3(g.count());
  hush::evaluate_grid(noise3, exec, g, gpu3);
  hush::evaluate_grid(noise3, hush::exec::scalar, g, cpu3);

  int nonzero = 0;
  for (const float v : gpu3) nonzero += v != 0.0f;
  const double d2 = worst_difference(gpu2, cpu2), d3 = worst_difference(gpu3, cpu3);
  std::printf(
      "consumer_glsl: %s on %s: perlin 2D points max |gpu - cpu| %.3g, 3D grid %.3g "
      "(tolerance %.3g)\n",
      gl.context.kind().c_str(), gl.device.renderer().c_str(), d2, d3, tolerance);
  if (!(d2 <= tolerance) || !(d3 <= tolerance) || nonzero == 0) {
    std::fprintf(stderr,
                 "consumer_glsl: GLSL values differ from the CPU beyond %.3g "
                 "(or are all zero: %d non-zero)\n",
                 tolerance, nonzero);
    return 1;
  }
  return 0;
}

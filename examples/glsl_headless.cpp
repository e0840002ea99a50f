#include <hush/hush.hpp>
#include <hush/glsl/device.hpp>
#include <hush/glsl/osmesa_context.hpp>
#include <cstdio>
#include <vector>

int main() {
  hush::glsl::osmesa_context context;                  // or any current GL >= 4.3 context
  hush::glsl::device gpu{context.loader()};            // loader: name -> GL function
  const hush::perlin<2> noise{/*seed=*/7};
  std::vector<hush::vec2> points = {{0.5f, 0.25f}, {10.75f, -3.5f}, {1000000.5f, 2.25f}};
  std::vector<float> values(points.size());
  hush::evaluate(noise, hush::exec::glsl{gpu}, points, values);  // a 430 compute shader
  for (std::size_t i = 0; i < points.size(); ++i)
    std::printf("gpu %+.6f  cpu %+.6f\n", values[i], noise(points[i]));
  std::printf("on %s\n", gpu.renderer().c_str());
}

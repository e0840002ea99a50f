// Helpers shared by the scene suites: small hand-made scenes and G-buffer comparisons.
#ifndef HUSH_TESTS_SCENE_TEST_UTIL_HPP
#define HUSH_TESTS_SCENE_TEST_UTIL_HPP

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "gbuffer.hpp"
#include "scene.hpp"

namespace hush_scene_test {

// A scene of one static mesh seen by a static camera.
inline hush_tools::scene::scene single(hush_tools::scene::mesh m, const glm::dmat4& model,
                                       const hush_tools::scene::camera_pose& pose) {
  hush_tools::scene::scene s;
  s.name = "test";
  s.objects.push_back(hush_tools::scene::object{
      "mesh", std::make_shared<const hush_tools::scene::mesh>(std::move(m)),
      [model](int) { return model; }});
  s.camera = [pose](int) { return pose; };
  return s;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Every channel bit for bit (NaN payloads included).
inline bool same_bits(const hush_tools::scene::gbuffer& a, const hush_tools::scene::gbuffer& b) {
  return a.width == b.width && a.height == b.height && same_bits(a.depth, b.depth) &&
         same_bits(a.velocity, b.velocity) && same_bits(a.forward_velocity, b.forward_velocity) &&
         same_bits(a.object_id, b.object_id) && same_bits(a.triangle_id, b.triangle_id) &&
         same_bits(a.barycentric, b.barycentric) && same_bits(a.uv, b.uv) &&
         same_bits(a.uv_jacobian, b.uv_jacobian) && same_bits(a.normal, b.normal) &&
         same_bits(a.position, b.position);
}

}  // namespace hush_scene_test

#endif  // HUSH_TESTS_SCENE_TEST_UTIL_HPP

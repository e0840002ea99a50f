// hush — test scenes: cameras, transforms and the named scenes (see scene.hpp).
#include "scene.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "hush/core/error.hpp"

namespace hush_tools {
namespace scene {
namespace {

using glm::dmat4;
using glm::dvec3;

constexpr double kDegree = glm::pi<double>() / 180.0;
const char* const kObjPrefix = "obj:";
const char* const kDensePrefix = "dense:";
constexpr long kDenseDefault = 50000, kDenseMin = 1000, kDenseMax = 10000000;

dmat4 translation(double x, double y, double z) {
  return glm::translate(dmat4(1.0), dvec3(x, y, z));
}
dmat4 rotation(double degrees, const dvec3& axis) {
  return glm::rotate(dmat4(1.0), degrees * kDegree, glm::normalize(axis));
}

object still(std::string name, mesh m, const dmat4& model) {
  return object{std::move(name), std::make_shared<const mesh>(std::move(m)),
                [model](int) { return model; }};
}

// A vertical wall (plane y = 0 turned to face +z) at depth z behind the objects.
object back_wall(double z) {
  return still("wall", make_plane(14.0f, 9.0f, 14, 9, 4.0f),
               translation(0.0, 0.0, z) * rotation(90.0, dvec3(1, 0, 0)));
}

scene translate_scene() {
  scene s{"translate",
          "a sphere translating left to right parallel to the image plane, "
          "a static wall behind",
          {},
          {}};
  s.objects.push_back(object{"sphere", std::make_shared<const mesh>(make_sphere(1.0f, 64, 32)),
                             [](int f) { return translation(-2.0 + 0.03 * f, 0.0, 0.0); }});
  s.objects.push_back(back_wall(-3.0));
  s.camera = [](int) {
    camera_pose p;
    p.eye = dvec3(0.0, 0.3, 6.0);
    p.fov_y = 0.7;
    return p;
  };
  return s;
}

scene rotate_scene() {
  scene s{"rotate", "a torus rotating in place about a tilted axis, a static wall behind", {}, {}};
  s.objects.push_back(
      object{"torus", std::make_shared<const mesh>(make_torus(1.0f, 0.4f, 96, 48)), [](int f) {
               return rotation(2.0 * f, dvec3(0.3, 1.0, 0.2)) * rotation(60.0, dvec3(1, 0, 0));
             }});
  s.objects.push_back(back_wall(-3.0));
  s.camera = [](int) {
    camera_pose p;
    p.eye = dvec3(0.0, 0.3, 5.0);
    p.fov_y = 0.7;
    return p;
  };
  return s;
}

scene zoom_scene() {
  scene s{
      "zoom", "the camera dollies towards a sphere, a box and a torus (static objects)", {}, {}};
  s.objects.push_back(still("sphere", make_sphere(0.8f, 64, 32), translation(-1.2, 0.0, 0.0)));
  s.objects.push_back(still("box", make_box(glm::vec3(0.6f, 0.6f, 0.6f)),
                            translation(1.2, 0.0, 0.0) * rotation(30.0, dvec3(0.2, 1, 0))));
  s.objects.push_back(still("torus", make_torus(0.9f, 0.3f, 72, 36),
                            translation(0.0, 0.6, -2.0) * rotation(70.0, dvec3(1, 0, 0))));
  s.objects.push_back(back_wall(-4.0));
  s.camera = [](int f) {
    camera_pose p;
    p.eye = dvec3(0.0, 0.4, std::max(8.0 - 0.05 * f, 2.5));
    p.target = dvec3(0.0, 0.2, 0.0);
    p.fov_y = 0.7;
    return p;
  };
  return s;
}

scene walkthrough_scene() {
  scene s{"walkthrough",
          "the camera walks low over a long ground plane (grazing angles) past a rotating "
          "pitcher (self-occlusion), boxes, spheres and a torus",
          {},
          {}};
  s.objects.push_back(
      // 2 x 2 unit quads out to 200 units: the far edge is the horizon, seen at grazing angles.
      still("ground", make_plane(200.0f, 200.0f, 100, 100, 50.0f), translation(0.0, 0.0, -90.0)));
  s.objects.push_back(object{"pitcher", std::make_shared<const mesh>(make_pitcher(96)), [](int f) {
                               // Half size: its rim (0.59) below the eye (0.6), so the near
                               // wall hides part of the inside, the handle part of the body.
                               return translation(0.7, 0.0, -5.0) *
                                      rotation(150.0 + 1.0 * f, dvec3(0, 1, 0)) *
                                      glm::scale(dmat4(1.0), dvec3(0.5));
                             }});
  s.objects.push_back(still("box", make_box(glm::vec3(0.4f, 0.8f, 0.4f)),
                            translation(-1.1, 0.8, -8.0) * rotation(25.0, dvec3(0, 1, 0))));
  s.objects.push_back(still("sphere", make_sphere(0.5f, 48, 24), translation(-0.6, 0.5, -2.5)));
  s.objects.push_back(still("torus", make_torus(0.7f, 0.2f, 64, 32),
                            translation(0.4, 0.9, -12.0) * rotation(90.0, dvec3(1, 0, 0))));
  s.objects.push_back(still("far box", make_box(glm::vec3(1.5f, 1.0f, 1.0f)),
                            translation(1.5, 1.0, -20.0) * rotation(-20.0, dvec3(0, 1, 0))));
  s.objects.push_back(
      still("far sphere", make_sphere(1.2f, 48, 24), translation(-2.5, 1.2, -16.0)));
  s.camera = [](int f) {
    camera_pose p;
    const double t = static_cast<double>(f);
    p.eye = dvec3(0.3 * std::sin(0.05 * t), 0.6, 4.0 - 0.08 * t);
    p.target = p.eye + dvec3(0.2 * std::sin(0.03 * t), -0.12, -1.0);
    p.fov_y = 0.9;
    return p;
  };
  return s;
}

scene dense_scene(long triangles) {
  scene s{"dense:" + std::to_string(triangles),
          "a rotating sphere and torus with about N triangles in all, over a plane",
          {},
          {}};
  // A sphere of 2 slices (stacks - 1) and a torus of 2 rings sides triangles, each
  // about half the total, slices = 2 stacks and rings = 2 sides.
  const int k =
      std::max(3, static_cast<int>(std::lround(std::sqrt(static_cast<double>(triangles) / 8.0))));
  s.objects.push_back(object{
      "sphere", std::make_shared<const mesh>(make_sphere(1.0f, 2 * k, k + 1)),
      [](int f) { return translation(-1.1, 0.0, 0.0) * rotation(1.5 * f, dvec3(0.2, 1, 0)); }});
  s.objects.push_back(object{
      "torus", std::make_shared<const mesh>(make_torus(0.8f, 0.35f, 2 * k, k)),
      [](int f) { return translation(1.2, 0.0, 0.0) * rotation(2.0 * f, dvec3(1, 0.5, 0)); }});
  s.objects.push_back(
      still("ground", make_plane(12.0f, 12.0f, 4, 4, 6.0f), translation(0.0, -1.2, 0.0)));
  s.camera = [](int) {
    camera_pose p;
    p.eye = dvec3(0.0, 0.8, 4.2);
    p.target = dvec3(0.0, -0.1, 0.0);
    p.fov_y = 0.75;
    return p;
  };
  return s;
}

scene obj_scene(const std::string& path) {
  scene s{kObjPrefix + path, "the OBJ file rotating about a tilted axis", {}, {}};
  s.objects.push_back(object{"obj", std::make_shared<const mesh>(load_obj(path)),
                             [](int f) { return rotation(2.0 * f, dvec3(0.1, 1, 0)); }});
  s.camera = [](int) {
    camera_pose p;
    p.eye = dvec3(0.0, 0.5, 3.2);
    p.fov_y = 0.8;
    return p;
  };
  return s;
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

glm::dmat4 view_matrix(const camera_pose& pose) {
  return glm::lookAt(pose.eye, pose.target, pose.up);
}

glm::dmat4 projection_matrix(const camera_pose& pose, int width, int height) {
  const double f = 1.0 / std::tan(0.5 * pose.fov_y);
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  dmat4 p(0.0);  // glm is column-major: p[column][row]
  p[0][0] = f / aspect;
  p[1][1] = f;
  p[2][2] = -1.0;  // z_ndc -> 1 as the depth -> infinity
  p[2][3] = -1.0;  // w = -z = view depth
  p[3][2] = -2.0 * pose.near_depth;
  return p;
}

std::size_t scene::triangles() const {
  std::size_t n = 0;
  for (const object& o : objects) n += o.shape->triangles();
  return n;
}

const std::vector<scene_info>& scene_list() {
  static const std::vector<scene_info> list = {
      {"translate", translate_scene().description},
      {"rotate", rotate_scene().description},
      {"zoom", zoom_scene().description},
      {"walkthrough", walkthrough_scene().description},
      {"dense",
       "a rotating sphere and torus with 50000 triangles over a plane "
       "(dense:N for about N triangles)"},
      {"obj:PATH", "the Wavefront OBJ file PATH as an object rotating about a tilted axis"},
  };
  return list;
}

scene make_scene(const std::string& name) {
  if (name == "translate") return translate_scene();
  if (name == "rotate") return rotate_scene();
  if (name == "zoom") return zoom_scene();
  if (name == "walkthrough") return walkthrough_scene();
  if (name == "dense") return dense_scene(kDenseDefault);
  if (starts_with(name, kDensePrefix)) {
    const std::string n = name.substr(std::string(kDensePrefix).size());
    long value = -1;
    if (!n.empty() && n.size() <= 9 &&
        std::all_of(n.begin(), n.end(), [](char c) { return c >= '0' && c <= '9'; }))
      value = std::stol(n);
    if (value < kDenseMin || value > kDenseMax)
      throw hush::invalid_argument("scene '" + name +
                                   "': the triangle count N of dense:N must be 1000 ... 10000000");
    return dense_scene(value);
  }
  if (starts_with(name, kObjPrefix) && name.size() > std::string(kObjPrefix).size())
    return obj_scene(name.substr(std::string(kObjPrefix).size()));
  std::string names;
  for (const scene_info& i : scene_list()) names += (names.empty() ? "" : ", ") + i.name;
  throw hush::invalid_argument("unknown scene '" + name + "'; valid: " + names + ", dense:N");
}

}  // namespace scene
}  // namespace hush_tools

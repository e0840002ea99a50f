// hush — test scenes: objects with animated transforms, an animated perspective
// camera, and the registry of named scenes (the motions of Kass & Pesare 2011,
// sec. 5, and Bénard et al. 2010, sec. 6: translation parallel to the image
// plane, rotation in place, zoom, a walkthrough).
//
// Everything is a deterministic function of the integer frame index: frame i of
// a scene is the same on every run and machine (plain double arithmetic, no
// clocks, no random numbers). Example/test infrastructure, not a core header.
#ifndef HUSH_SCENE_SCENE_HPP
#define HUSH_SCENE_SCENE_HPP

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mesh.hpp"

namespace hush_tools {
namespace scene {

// Where the camera is in one frame. Right-handed world, y up; the camera looks from
// `eye` towards `target`. Perspective with vertical field of view `fov_y`
// (radians, in (0, pi)) and a near plane at view depth `near_depth` (> 0); there is
// no far plane (the rasterizers keep everything beyond the near plane).
struct camera_pose {
  glm::dvec3 eye{0.0, 0.0, 5.0};
  glm::dvec3 target{0.0, 0.0, 0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_y = 0.8;
  double near_depth = 0.05;
};

// World -> view: camera at the origin looking down -z, y up (OpenGL's eye space).
// View depth (gbuffer::depth) of a view-space point is -z.
glm::dmat4 view_matrix(const camera_pose& pose);

// View -> clip for a `width` x `height` image: OpenGL's perspective matrix with the
// far plane at infinity, so clip w = view depth. Screen pixel of clip (X, Y, W):
// ((X / W + 1) width / 2, (1 - Y / W) height / 2), y down (gbuffer.hpp).
glm::dmat4 projection_matrix(const camera_pose& pose, int width, int height);

struct object {
  std::string name;
  std::shared_ptr<const mesh> shape;
  // Object -> world transform of frame i (an affine matrix).
  std::function<glm::dmat4(int frame)> model;
};

struct scene {
  std::string name;
  std::string description;      // one line
  std::vector<object> objects;  // gbuffer::object_id of objects[k] is k + 1
  std::function<camera_pose(int frame)> camera;

  std::size_t triangles() const;
};

// One registered scene: its name (or name pattern) and a one-line description.
struct scene_info {
  std::string name;
  std::string description;
};

// The registered scenes, in a fixed order: translate, rotate, zoom, walkthrough,
// dense, obj:PATH.
const std::vector<scene_info>& scene_list();

// The scene called `name`: a name from scene_list(), "dense:N" (the dense scene with
// about N triangles, 1000 <= N <= 10000000) or "obj:PATH" (the OBJ file PATH as a
// rotating object). Throws hush::invalid_argument for an unknown name or a bad N
// (the message lists the valid names), std::runtime_error when an OBJ cannot be read.
scene make_scene(const std::string& name);

}  // namespace scene
}  // namespace hush_tools

#endif  // HUSH_SCENE_SCENE_HPP

// hush — test scenes: a deterministic CPU rasterizer producing G-buffers.
//
// render_cpu(s, i, width, height) is frame i of scene s as the G-buffer of
// gbuffer.hpp. How it works (docs/scenes.md has the measured accuracy and speed):
//  1. Visibility. Each triangle is clipped in homogeneous clip space against the
//     near plane (view depth >= near_depth) and a guard band (|x_ndc|, |y_ndc| <= 2,
//     which only removes geometry outside the image), projected, snapped to
//     1/256 pixel and scan-converted with exact 64-bit integer edge functions at
//     pixel centres with the top-left fill rule: a pixel centre on an edge shared by
//     two triangles belongs to exactly one of them (no double coverage, no cracks).
//     The depth test keeps the largest 1/depth (the nearest surface; ties keep the
//     first triangle drawn). Back faces of closed meshes are culled.
//  2. Shading, once per covered pixel: the perspective-correct barycentrics of the
//     unclipped, unsnapped triangle at the pixel centre come from 2D homogeneous
//     rasterization (Olano & Greer 1997): f = M^-1 (x_ndc, y_ndc, 1), with M the
//     triangle's clip-space (X, Y, W) columns, is (b0, b1, b2) / depth, so
//     b = f / sum(f) and depth = 1 / sum(f) exactly, whichever vertices the near
//     plane clipped. uv, normal and object-space position are interpolated with b;
//     the uv Jacobian is the analytic derivative of b(x, y) (a ratio of affine
//     functions of the pixel position). Velocity is exact: the object-space point
//     at the pixel centre p is projected with frame i-1's object and camera
//     transforms to p_prev, and velocity = (p - p_prev, depth - depth_prev).
//     If that point was not in front of frame i-1's camera (depth_prev <= 0),
//     the velocity is NaN (no previous position exists). The forward velocity
//     is the same with frame i+1's transforms: (p_next - p, depth_next - depth).
// Arithmetic is double precision in a fixed order on one thread, so the output is
// the same bits on every run. Example/test infrastructure, not a core header.
#ifndef HUSH_SCENE_RASTER_CPU_HPP
#define HUSH_SCENE_RASTER_CPU_HPP

#include <cstdint>
#include <vector>

#include "gbuffer.hpp"
#include "scene.hpp"

namespace hush_tools {
namespace scene {

// Largest width and height the rasterizers accept (keeps the 1/256-pixel fixed-point
// edge functions inside 64 bits with the guard band).
constexpr int kMaxImageSize = 16384;

struct raster_options {
  // Cull the back faces of meshes marked `closed` (they are never visible, so the
  // G-buffer is the same either way; culling halves the triangles to scan).
  bool cull_back_faces = true;
  // When set: resized to width * height and filled with, per pixel, the number of
  // triangle fragments that covered its centre before the depth test (tests use it
  // to check the fill rule: exactly 1 everywhere on a closed tessellated surface).
  std::vector<std::uint32_t>* coverage = nullptr;
};

// Frame `frame` (>= 0) of `s`, `width` x `height` pixels (1 ... kMaxImageSize).
// Throws hush::invalid_argument for out-of-range arguments.
gbuffer render_cpu(const scene& s, int frame, int width, int height);
gbuffer render_cpu(const scene& s, int frame, int width, int height, const raster_options& options);

// The same into `out`, reusing its storage (every value of every channel is written):
// rendering a sequence this way skips reallocating and page-faulting ~21 floats per
// pixel each frame.
void render_cpu(const scene& s, int frame, int width, int height, const raster_options& options,
                gbuffer& out);

// Throws hush::invalid_argument unless frame >= 0 and 1 <= width, height <= kMaxImageSize
// (every rasterizer checks its arguments with this).
void check_render_arguments(int frame, int width, int height);

// Throws hush::invalid_argument unless `pose` has a finite near_depth > 0 and fov_y in
// (0, pi), and every object of `s` has a valid mesh (validate) and a transform.
void check_scene(const scene& s, const camera_pose& pose);

// An empty G-buffer of the given size holding the background values of gbuffer.hpp.
gbuffer make_background(int width, int height);

}  // namespace scene
}  // namespace hush_tools

#endif  // HUSH_SCENE_RASTER_CPU_HPP

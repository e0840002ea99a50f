// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// One frame of per-pixel scene data: what hush's scene-driven noises (NPR
// Gabor, coherent noise) and the temporal-coherence metrics read. Produced by
// the CPU rasterizer (examples/scene/raster_cpu.hpp) and the OSMesa one
// (raster_gl.hpp); test/example infrastructure, not part of the core headers.
//
// Conventions (every producer and consumer relies on them):
//  - width x height pixels, row-major, row 0 at the TOP of the image, pixel
//    (x, y) has its centre at (x + 0.5, y + 0.5) in screen pixels, x right,
//    y down. Channel c of pixel (x, y) is at [(y * width + x) * C + c].
//  - object_id 0 = background (no surface). Every other channel is defined
//    only where object_id != 0; background pixels hold the values below.
//  - depth: linear view depth, the distance from the camera plane along the
//    view axis, in world units (> 0). Background: +infinity.
//  - velocity (3 channels): the motion of the surface point seen in this
//    pixel from frame i-1 to frame i: (dx, dy) in screen pixels per frame,
//    dz the change of its linear depth per frame. So the point seen at pixel
//    centre p in frame i was at p - (dx, dy), with depth depth - dz, in frame
//    i-1 (backward reprojection, Kass & Pesare 2011 sec. 3). Frame 0 uses
//    frame 0's transforms for i-1 (velocity 0). Background: 0. If the point
//    was not in front of frame i-1's camera (no previous screen position),
//    all three are NaN: treat such pixels as disoccluded.
//  - forward_velocity (3 channels): the same motion towards frame i+1: the
//    point seen at pixel centre p in frame i is at p + (dx, dy), with depth
//    depth + dz, in frame i+1 (what the backward pass of time-symmetric
//    coherent noise reprojects with). Background: 0; NaN when the point is not
//    in front of frame i+1's camera. Scenes are functions of the frame index,
//    so frame i+1 always exists. Optional: empty when a producer does not make
//    it (every other channel is always sized for width * height).
//  - triangle_id: index of the triangle in its object's mesh. Background:
//    0xFFFFFFFF.
//  - barycentric (3): perspective-correct weights of the triangle's vertices
//    0, 1, 2 at the pixel centre; sum to 1. Background: 0.
//  - uv (2): perspective-correct texture coordinates. Background: 0.
//  - uv_jacobian (4): d(u, v)/d(x, y) in uv units per pixel, stored
//    du/dx, du/dy, dv/dx, dv/dy (the screen-to-texture footprint). Background: 0.
//  - normal (3): unit world-space shading normal. Background: 0.
//  - position (3): object-space position of the surface point (for solid
//    texturing attached to the object). Background: 0.
#ifndef HUSH_SCENE_GBUFFER_HPP
#define HUSH_SCENE_GBUFFER_HPP

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hush/core/frame.hpp"

namespace hush_tools {
namespace scene {

struct gbuffer {
  int width = 0;
  int height = 0;
  std::vector<float> depth;                // 1 channel
  std::vector<float> velocity;             // 3 channels: dx, dy (pixels/frame), dz (depth/frame)
  std::vector<float> forward_velocity;     // 3 channels: to frame i+1, same units
  std::vector<std::uint32_t> object_id;    // 1 channel, 0 = background
  std::vector<std::uint32_t> triangle_id;  // 1 channel
  std::vector<float> barycentric;          // 3 channels
  std::vector<float> uv;                   // 2 channels
  std::vector<float> uv_jacobian;          // 4 channels: du/dx, du/dy, dv/dx, dv/dy
  std::vector<float> normal;               // 3 channels
  std::vector<float> position;             // 3 channels, object space

  std::size_t pixels() const { return static_cast<std::size_t>(width) * height; }
  bool covered(std::size_t pixel) const { return object_id[pixel] != 0; }
};

// The views of `g` a scene-driven noise reads (hush::frame, include/hush/core/frame.hpp):
// depth, velocity, forward velocity (when present), object and triangle ids, uv and its
// screen Jacobian. Valid while
// `g` lives and is not resized.
inline hush::frame as_frame(const gbuffer& g) {
  const std::size_t w = static_cast<std::size_t>(g.width), h = static_cast<std::size_t>(g.height);
  hush::frame f;
  f.depth = {g.depth.data(), w, h};
  f.velocity = {reinterpret_cast<const hush::vec3*>(g.velocity.data()), w, h};
  if (!g.forward_velocity.empty())
    f.forward_velocity = {reinterpret_cast<const hush::vec3*>(g.forward_velocity.data()), w, h};
  f.object_id = {g.object_id.data(), w, h};
  f.triangle_id = {g.triangle_id.data(), w, h};
  f.uv = {reinterpret_cast<const hush::vec2*>(g.uv.data()), w, h};
  f.uv_jacobian = {reinterpret_cast<const hush::vec4*>(g.uv_jacobian.data()), w, h};
  return f;
}

}  // namespace scene
}  // namespace hush_tools

#endif  // HUSH_SCENE_GBUFFER_HPP

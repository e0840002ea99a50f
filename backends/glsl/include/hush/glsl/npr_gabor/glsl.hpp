// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GLSL sources of NPR Gabor noise (include/hush/npr_gabor.hpp) on the GPU, all
// #version 430 core: stage 1's compute passes (each triangle's point sequence, level by
// level, to the records) and stage 2's point-sprite program (vertex, geometry and fragment
// stages that splat the records). hush/glsl/npr_gabor/renderer.hpp runs them and states
// their contract; `hush glsl-export` writes them (hush/glsl/export.hpp).
#ifndef HUSH_GLSL_NPR_GABOR_GLSL_HPP
#define HUSH_GLSL_NPR_GABOR_GLSL_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "hush/detail/constants.hpp"
#include "hush/glsl/dialect.hpp"
#include "hush/glsl/generator.hpp"
#include "hush/glsl/library.hpp"
#include "hush/npr_gabor.hpp"

namespace hush {
namespace glsl {

// The geometry shader's output per input point: one quad.
constexpr int kNprGaborSpriteVertices = 4;
// Components per emitted vertex: gl_Position (4) and the record index (1).
constexpr int kNprGaborSpriteComponents = 5;
// Bytes of one record in the storage buffer (4 vec4s, std430).
constexpr std::size_t kNprGaborRecordBytes = 64;

namespace detail {

// The three stages. Records (binding 0): box = (x0, y0, x1, y1); kern = (cx, cy, 1/r, weight)
// with (cx, cy) = (x0 + 1/2, y0 + 1/2) - position (the first pixel centre's offset, pixels);
// freq = (F_x r, F_y r, -, -) (the kernel's phase per radius, the CPU's float phi); plane =
// (1/z at the first pixel centre, d(1/z)/dx, d(1/z)/dy, -); ids = (object, triangle, -, -).
constexpr const char* kNprGaborRecord = R"glsl(
struct hush_npr_splat {
  ivec4 box;
  vec4 kern;
  vec4 freq;
  vec4 plane;
};
)glsl";
constexpr const char* kNprGaborRecords = R"glsl(
layout(std430, binding = 0) readonly buffer hush_npr_splats_b { hush_npr_splat hush_npr_splats[]; };
uniform uvec2 hush_size;  // frame width, height
)glsl";

constexpr const char* kNprGaborVertex = R"glsl(
#ifdef VULKAN
#define HUSH_VERTEX_INDEX gl_VertexIndex  // both count from the draw's first vertex
#else
#define HUSH_VERTEX_INDEX gl_VertexID
#endif
layout(location = 0) flat out uint hush_v_splat;
void main() {
  hush_v_splat = uint(HUSH_VERTEX_INDEX);
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
)glsl";

// One quad over the record's pixels: window x in [x0, x1 + 1] holds the centres x0 + 1/2 ...
// x1 + 1/2 well inside (no edge ties); window y is image y (the read-back keeps row order).
constexpr const char* kNprGaborGeometry = R"glsl(
layout(points) in;
layout(triangle_strip, max_vertices = HUSH_NPR_SPRITE_VERTICES) out;
layout(location = 0) flat in uint hush_v_splat[];
layout(location = 0) flat out uint hush_g_splat;
void main() {
  uint i = hush_v_splat[0];
  ivec4 b = hush_npr_splats[i].box;
  if (b.x > b.z || b.y > b.w) return;  // a GPU-made record whose kernel misses the image
  vec2 lo = vec2(b.xy) / vec2(hush_size) * 2.0 - 1.0;
  vec2 hi = vec2(b.zw + 1) / vec2(hush_size) * 2.0 - 1.0;
  hush_g_splat = i; gl_Position = vec4(lo.x, lo.y, 0.0, 1.0); EmitVertex();
  hush_g_splat = i; gl_Position = vec4(hi.x, lo.y, 0.0, 1.0); EmitVertex();
  hush_g_splat = i; gl_Position = vec4(lo.x, hi.y, 0.0, 1.0); EmitVertex();
  hush_g_splat = i; gl_Position = vec4(hi.x, hi.y, 0.0, 1.0); EmitVertex();
  EndPrimitive();
}
)glsl";

// npr_gabor_visibility and the kernel of npr_gabor_splat_scalar<float>, per fragment.
constexpr const char* kNprGaborFragment = R"glsl(
layout(location = 0) flat in uint hush_g_splat;
layout(location = 0) out float hush_npr_out;
uniform uint hush_flags;      // 1 object test, 2 triangle test, 4 depth test, 8 soft
uniform float hush_tolerance;
uniform float hush_neg_a;     // -ln(1/t)
uniform float hush_taper_k;   // 1 / (1 - taper start)
layout(std430, binding = 4) readonly buffer hush_npr_ids_b { uvec4 hush_npr_ids[]; };
// The G-buffer: textures read with texelFetch, texel (x, y) = pixel (x, y) (hush/glsl/
// npr_gabor/frame.hpp: depth R32F, object and triangle ids R32UI); only the tested ones are read.
layout(binding = 0) uniform sampler2D hush_npr_depth_tex;
layout(binding = 1) uniform usampler2D hush_npr_object_tex;
layout(binding = 2) uniform usampler2D hush_npr_triangle_tex;
void main() {
  hush_npr_splat s = hush_npr_splats[hush_g_splat];
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (any(lessThan(p, s.box.xy)) || any(greaterThan(p, s.box.zw))) discard;
  vec2 k = vec2(p - s.box.xy);  // pixels from the first pixel: small integers, exact
  hush_gabor_axis ax = hush_gabor_axis_factors((s.kern.x + k.x) * s.kern.z, hush_neg_a, s.freq.x);
  hush_gabor_axis ay = hush_gabor_axis_factors((s.kern.y + k.y) * s.kern.z, hush_neg_a, s.freq.y);
  if (!(ax.d2 + ay.d2 < 1.0)) discard;
  uvec2 ids = hush_npr_ids[hush_g_splat].xy;  // (object, triangle id, J low, J high)
  if ((hush_flags & 1u) != 0u && texelFetch(hush_npr_object_tex, p, 0).x != ids.x) discard;
  if ((hush_flags & 2u) != 0u && texelFetch(hush_npr_triangle_tex, p, 0).x != ids.y) discard;
  float vis = 1.0;
  if ((hush_flags & 4u) != 0u) {
    precise float zp = texelFetch(hush_npr_depth_tex, p, 0).x;
    uint bits = floatBitsToUint(zp);
    // Not in front (<= 0, -0, negative), infinite or NaN: fails (exponent bits, so no
    // fast-math folding of NaN compares can change it).
    if (zp == 0.0 || (bits & 0x80000000u) != 0u || (bits & 0x7F800000u) == 0x7F800000u) discard;
    precise float plane = s.plane.x + s.plane.y * k.x + s.plane.z * k.y;
    precise float rel = abs(zp * plane - 1.0);
    bool soft = (hush_flags & 8u) != 0u;
    if (!(rel <= (soft ? 2.0 * hush_tolerance : hush_tolerance))) discard;
    if (soft && rel > hush_tolerance) vis = 2.0 - rel / hush_tolerance;
  }
  hush_npr_out = vis * hush_gabor_pair(ax, hush_gabor_row_of(s.kern.w, ay), hush_taper_k);
}
)glsl";

// ---- Stage 1 on the GPU: the hierarchical point sequence (hush/npr_gabor/tree.hpp)
// walked level by level in compute passes (npr_gabor_stage1_source(pass)).
// Inputs, uploaded once per frame: vertices (screen x, y, depth, -) and triangles (5 words:
// three vertex indices, triangle id, object id); the per-object kernel table (entry
// min(object, hush_table_last); the last entry is the params' constants). Every value read
// from the table was computed on the CPU in double by npr_gabor::kernel_of_object.
// A node (64 bytes): its seed, triangle, J (64 bits), its three screen corners and depths
// (perspective-correct midpoints of its parent's: npr_gabor_tree.hpp's corners projected;
// corners relative to the triangle's origin, hush_npr_origin), and
// `info`, written by the expand pass: bit 0 its own point reaches the frame, bit 1 + d its
// child at slot d is a node of the next level.
// J as uvec2 (low, high word): counts reach 2^41 (kNprGaborMaxPoints 2^40, 2M points), past
// float's 2^24; two 32-bit words add and compare exactly with uaddCarry and shifts, where
// doubles would need fp64, slow (1/32 - 1/64 rate) or missing on many GPUs.
constexpr const char* kNprGaborStage1Common = R"glsl(
struct hush_npr_kernel {
  vec4 freq;  // (F_x r, F_y r, |F| r, 1/r)  (isotropic: F = (F0, 0))
  vec4 size;  // (r, lambda_T, weight factor, -)
};
struct hush_npr_lod {
  // (log2 count + 1, 0 where the triangle has no points; log2 M, the first M points' weight
  // (bits); the others' weight (bits)): counts and M are powers of two (npr_gabor_lod).
  uvec4 lod;
  vec4 plane;   // (1/z at vertex k, d(1/z)/dx, d(1/z)/dy, k): k 0, or the deepest vertex near w_near
  // A count per node (npr_gabor's blend > 0: local density, depth ratio above 4, crossing the
  // near plane): (blend, the root's count n, w_near (0: not crossing), the root's weight sqrt(f)).
  vec4 walk;
};
struct hush_npr_node {
  uvec4 key;  // (seed, triangle, J low, J high)
  vec4 s01;   // corners 0 and 1 (screen, relative to hush_npr_origin)
  vec4 s2z;   // corner 2, depths of corners 0 and 1
  float z2;   // depth of corner 2
  uint info;  // bit 0: its own point has a record; bit 1 + d: its child at slot d is kept
  uint pad0;  // local density: its own point's LOD weight sqrt(f) (bits), set by the expand pass
  uint pad1;
};
layout(std430, binding = 0) readonly buffer hush_npr_vertices_b { vec4 hush_npr_vertices[]; };
layout(std430, binding = 1) readonly buffer hush_npr_triangles_b { uint hush_npr_triangles[]; };
layout(std430, binding = 2) readonly buffer hush_npr_table_b { hush_npr_kernel hush_npr_table[]; };
uniform uint hush_tris;        // triangles
uniform uint hush_table_last;  // the constants' entry
uniform uint hush_group_base;  // first work group of this dispatch
uniform uvec2 hush_size;       // frame width, height
uniform uint hush_key;         // seed_key(seed)
// Nodes of this level: the host's count, or with hush_nodes_host = 0xFFFFFFFF the GPU's, from
// the walk's plan (kNprGaborPlan; the level's slot bound as this block: counts (nodes, first
// record, records, -), the scan's items at depths 0 - 3).
uniform uint hush_nodes_host;
layout(std140, binding = 0) uniform hush_npr_plan_slot { uvec4 hush_plan_counts; uvec4 hush_plan_items; };
#define hush_nodes (hush_nodes_host != 0xFFFFFFFFu ? hush_nodes_host : hush_plan_counts.x)
uniform uint hush_level;       // the level: its nodes' stride is 4^level
uniform uint hush_local;       // 1: params::local_density (a count per node)
// Homogeneous node corners (triangles crossing the near plane): (z (s - origin), z) per corner in
// s01.xy, s01.zw, s2z.xy and the depths, as the screen corners' layout.
const uint hush_npr_child_order[HUSH_NPR_ORDERS] = uint[HUSH_NPR_ORDERS](HUSH_NPR_ORDER_TABLE);
uint hush_npr_item() {
  return (hush_group_base + gl_WorkGroupID.x) * uint(HUSH_NPR_GROUP) + gl_LocalInvocationID.x;
}
// 64-bit helpers: a + b; v << s (s < 64); a < 2^e (e < 64).
uvec2 hush_u64_add(uvec2 a, uvec2 b) {
  uint c;
  uint lo = uaddCarry(a.x, b.x, c);
  return uvec2(lo, a.y + b.y + c);
}
uvec2 hush_u64_shl(uint v, uint s) {
  return s == 0u ? uvec2(v, 0u) : s < 32u ? uvec2(v << s, v >> (32u - s)) : uvec2(0u, v << (s - 32u));
}
bool hush_u64_below_pow2(uvec2 a, uint e) {
  return e < 32u ? a.y == 0u && (a.x >> e) == 0u : (a.y >> (e - 32u)) == 0u;
}
// Triangle t's vertex 0, its edges to vertices 1 and 2, the depths; false where the CPU's
// stage 1 skips it before the area (a depth 0 or not finite, a non-finite position): the
// exponent bits decide, which no NaN-folding compiler can change. A negative depth (a vertex
// behind the camera) passes: the LOD pass skips triangles entirely behind and clips the others.
bool hush_npr_bad(float z) {
  return z == 0.0 || hush_is_nonfinite(z);
}
bool hush_npr_triangle(uint t, out vec2 s0, out vec2 e1, out vec2 e2, out vec3 z) {
  vec4 v0 = hush_npr_vertices[hush_npr_triangles[5u * t]];
  vec4 v1 = hush_npr_vertices[hush_npr_triangles[5u * t + 1u]];
  vec4 v2 = hush_npr_vertices[hush_npr_triangles[5u * t + 2u]];
  s0 = v0.xy;
  e1 = v1.xy - v0.xy;
  e2 = v2.xy - v0.xy;
  z = vec3(v0.z, v1.z, v2.z);
  return !(hush_npr_bad(v0.z) || hush_npr_bad(v1.z) || hush_npr_bad(v2.z) ||
           hush_is_nonfinite(v0.x) || hush_is_nonfinite(v0.y) || hush_is_nonfinite(v1.x) ||
           hush_is_nonfinite(v1.y) || hush_is_nonfinite(v2.x) || hush_is_nonfinite(v2.y));
}
hush_npr_kernel hush_npr_kernel_of(uint object) {
  return hush_npr_table[min(object, hush_table_last)];
}
// The origin of triangle t's node corners: its vertex 0 clamped into the frame. Each level
// rounds its corners at their size relative to it: at most the triangle's extent, and near the
// frame, where a huge triangle's points are kept, about the ancestor's extent (absolute screen
// coordinates would round at the frame's size for small triangles, coordinates relative to
// vertex 0 at the whole triangle's for huge ones).
vec2 hush_npr_origin(uint t) {
  return clamp(hush_npr_vertices[hush_npr_triangles[5u * t]].xy, vec2(0.0), vec2(hush_size));
}
// npr_gabor's triangle_key: hash32(hash32(seed_key(seed), object), triangle), the root's seed.
uint hush_npr_triangle_key(uint t) {
  return hush_hash32(hush_hash32(hush_key, hush_npr_triangles[5u * t + 4u]),
                     hush_npr_triangles[5u * t + 3u]);
}
// The node's own point (npr_gabor_tree.hpp: word 0 of its stream, local barycentrics
// (1 - sqrt u, sqrt u (1 - v), sqrt u v) of its corners) on the screen: origin + corner 0 + d
// with d = sum l_i z_i (s_i - s_0) / sum l_i z_i (the projection of the object-space point,
// rounded at the node's size); its pixel range p0 ... p1. The point relative to the origin is
// base + d: base corner 0, or with homogeneous corners (homog) base = sum l_i h_i.xy / sum l_i
// h_i.w (its projection) and d = 0.
void hush_npr_own_point(hush_npr_node nd, bool homog, vec2 origin, uint stream, float r,
                        out vec2 base, out vec2 d, out vec2 p0, out vec2 p1) {
  uint w0 = hush_stream_word(stream, 0u);
  float su = sqrt(hush_gabor_half(w0, 0u)), v = hush_gabor_half(w0, 1u);
  if (homog) {
    vec3 b = vec3(1.0 - su, su * (1.0 - v), su * v);
    base = (b.x * nd.s01.xy + b.y * nd.s01.zw + b.z * nd.s2z.xy) / dot(b, vec3(nd.s2z.zw, nd.z2));
    d = vec2(0.0);
  } else {
    vec3 l = vec3(1.0 - su, su * (1.0 - v), su * v) * vec3(nd.s2z.zw, nd.z2);
    base = nd.s01.xy;
    d = (l.y * (nd.s01.zw - nd.s01.xy) + l.z * (nd.s2z.xy - nd.s01.xy)) / (l.x + l.y + l.z);
  }
  vec2 at = origin + (base + d);
  p0 = max(ceil(at - r - 0.5), vec2(0.0));
  p1 = min(floor(at + r - 0.5), vec2(hush_size) - 1.0);
}
// The child at `slot` (npr_gabor_tree.hpp's npr_tree_child): geometric child c from the order
// word's permutation, seed hash32(seed, c), index j; corner i of child c < 3 is corner c
// (i == c) or the midpoint of corners c and i, of the middle child the midpoint opposite
// corner i; perspective-correct: screen (z_a s_a + z_b s_b) / (z_a + z_b), depth (z_a + z_b) / 2;
// homogeneous corners (homog): (h_a + h_b) / 2.
hush_npr_node hush_npr_child(hush_npr_node p, bool homog, uint order, uint slot, uvec2 j) {
  uint hi, lo;
  umulExtended(order, uint(HUSH_NPR_ORDERS), hi, lo);
  uint c = (hush_npr_child_order[hi] >> (2u * slot)) & 3u;
  vec2 s[3] = vec2[3](p.s01.xy, p.s01.zw, p.s2z.xy);
  float z[3] = float[3](p.s2z.z, p.s2z.w, p.z2);
  vec2 cs[3];
  float cz[3];
  for (uint i = 0u; i < 3u; ++i) {
    uint a = c < 3u ? c : (i + 1u) % 3u, b = c < 3u ? i : (i + 2u) % 3u;
    if (a == b) {
      cs[i] = s[a];
      cz[i] = z[a];
    } else if (homog) {
      cs[i] = 0.5 * (s[a] + s[b]);
      cz[i] = 0.5 * (z[a] + z[b]);
    } else {
      cs[i] = (z[a] * s[a] + z[b] * s[b]) / (z[a] + z[b]);
      cz[i] = 0.5 * (z[a] + z[b]);
    }
  }
  hush_npr_node n;
  n.key = uvec4(hush_hash32(p.key.x, c), p.key.y, j);
  n.s01 = vec4(cs[0], cs[1]);
  n.s2z = vec4(cs[2], cz[0], cz[1]);
  n.z2 = cz[2];
  n.info = 0u;
  n.pad0 = n.pad1 = 0u;
  return n;
}
// Whether the node's screen triangle (bounding box) grown by r meets the frame. Conservative
// by HUSH_NPR_CULL_MARGIN pixels more: a node kept in excess only costs its visit (its points
// have empty pixel ranges), while one dropped that the CPU keeps would lose points; the margin
// exceeds the corners' float error (a few 2^-24 of the sum of the ancestors' extents).
bool hush_npr_box_meets_image(vec2 lo, vec2 hi, vec2 origin, float r) {
  vec2 g = vec2(r) + HUSH_NPR_CULL_MARGIN + HUSH_NPR_CULL_RELATIVE * max(abs(lo), abs(hi));
  return !(any(lessThan(hi + g, -origin)) || any(greaterThan(lo - g, vec2(hush_size) - origin)));
}
bool hush_npr_meets_image(hush_npr_node n, vec2 origin, float r) {
  vec2 lo = min(min(n.s01.xy, n.s01.zw), n.s2z.xy), hi = max(max(n.s01.xy, n.s01.zw), n.s2z.xy);
  return hush_npr_box_meets_image(lo, hi, origin, r);
}
// A node of homogeneous corners h_i (relative to the origin) against the near plane
// (npr_gabor's clip_near): its part at depth >= w_near projected, c[0 ... m - 1] (m = 0:
// behind, 3 or 4), the convex polygon of the corners in front and the edges' crossings of
// w_near (depth and clip xy are affine along an edge); whole: every corner in front. Its
// count n = lambda A (A: the edges' cross product for 3 corners, else the shoelace, as the CPU)
// and whether its bounding box grown by r (hush_npr_box_meets_image's margins) meets the frame.
// precise: a child's count is computed when it is kept and again when it is visited.
int hush_npr_clip(hush_npr_node nd, float w_near, float lambda, vec2 origin, float r,
                  out bool whole, out float n, out bool meets) {
  vec3 h[3] = vec3[3](vec3(nd.s01.xy, nd.s2z.z), vec3(nd.s01.zw, nd.s2z.w), vec3(nd.s2z.xy, nd.z2));
  precise float d[3];
  for (uint i = 0u; i < 3u; ++i) d[i] = h[i].z - w_near;
  whole = d[0] >= 0.0 && d[1] >= 0.0 && d[2] >= 0.0;
  precise vec2 c[4];
  int m = 0;
  for (uint i = 0u; i < 3u; ++i) {
    uint j = (i + 1u) % 3u;
    if (d[i] >= 0.0) c[m++] = h[i].xy / h[i].z;
    if ((d[i] < 0.0) != (d[j] < 0.0)) {
      precise float u = d[i] / (d[i] - d[j]);
      precise vec3 b = h[i] + u * (h[j] - h[i]);
      c[m++] = b.xy / b.z;
    }
  }
  n = 0.0;
  meets = false;
  if (m == 0) return 0;
  precise float a = 0.0;
  if (m == 3) {
    a = (c[1].x - c[0].x) * (c[2].y - c[0].y) - (c[1].y - c[0].y) * (c[2].x - c[0].x);
  } else {
    for (int i = 0; i < m; ++i) a += c[i].x * c[(i + 1) % m].y - c[(i + 1) % m].x * c[i].y;
  }
  n = lambda * 0.5 * abs(a);
  vec2 lo = c[0], hi = c[0];
  for (int i = 1; i < m; ++i) {
    lo = min(lo, c[i]);
    hi = max(hi, c[i]);
  }
  meets = hush_npr_box_meets_image(lo, hi, origin, r);
  return m;
}
// The paper's LOD weight of point J (npr_gabor_lod::weight; 0 at and past the count).
float hush_npr_lod_weight(hush_npr_lod l, uvec2 j) {
  if (l.lod.x == 0u || !hush_u64_below_pow2(j, l.lod.x - 1u)) return 0.0;
  return uintBitsToFloat(hush_u64_below_pow2(j, l.lod.y) ? l.lod.z : l.lod.w);
}
// params::local_density (docs/npr-gabor.md "Local density"): a node's expected count
// n = lambda A, A the area of its screen corners (float, relative to the origin: the CPU's
// projected corners in double), and its own point's squared weight f = n h(n),
// npr_gabor_lod::local_square: the hat h = max(0, 1 - |log4 n|), 1 below n = 1 at the root
// (coarsest) and above it at the finest level. precise: the expand pass computes a child's
// count when it decides to keep it and again when it visits it, and both must be one value.
float hush_npr_node_count(hush_npr_node nd, float lambda) {
  precise vec2 e1 = nd.s01.zw - nd.s01.xy, e2 = nd.s2z.xy - nd.s01.xy;
  precise float c = e1.x * e2.y - e1.y * e2.x;
  precise float n = lambda * 0.5 * abs(c);
  return n;
}
float hush_npr_local_square(float n, bool coarsest, bool finest) {
  if (!(n > 0.0)) return 0.0;
  n = min(n, HUSH_NPR_MAX_POINTS);
  float l = 0.5 * log2(n);
  float h = 1.0 - abs(l);
  if ((coarsest && l <= 0.0) || (finest && l >= 0.0)) h = 1.0;
  return h > 0.0 ? n * h : 0.0;
}
)glsl";

// Pass 0, one invocation per triangle: its point count and LOD weights (npr_gabor_lod::of,
// thinning), in float, and its plane of 1/z; count 0 for every triangle stage 1 skips; the
// scan input (0 records, 1 root node where it has points).
constexpr const char* kNprGaborLods = R"glsl(
layout(local_size_x = HUSH_NPR_GROUP) in;
layout(std430, binding = 3) writeonly buffer hush_npr_lods_b { hush_npr_lod hush_npr_lods[]; };
layout(std430, binding = 4) writeonly buffer hush_npr_flags_b { uvec2 hush_npr_flags[]; };
uniform uint hush_opts;  // 1 cull back faces, 2 thinning, 4 front faces clockwise
void main() {
  uint t = hush_npr_item();
  if (t >= hush_tris) return;
  hush_npr_lod o;
  o.lod = uvec4(0u);
  o.plane = vec4(0.0);
  o.walk = vec4(0.0);
  hush_npr_flags[t] = uvec2(0u);
  vec2 s0, e1, e2;
  vec3 z;
  if (!hush_npr_triangle(t, s0, e1, e2, z)) { hush_npr_lods[t] = o; return; }
  // Twice the signed area, y down: front faces are negative; with a vertex behind the camera
  // the projected triangle is turned over (the homogeneous orientation z0 z1 z2 cross; its
  // sign from the depths' signs, exact where the float product could underflow).
  float cross = e1.x * e2.y - e1.y * e2.x;
  bool turned = ((z.x < 0.0) != (z.y < 0.0)) != (z.z < 0.0);
  float facing = turned ? -cross : cross;
  bool front = (hush_opts & 4u) != 0u ? facing > 0.0 : facing < 0.0;
  if ((hush_opts & 1u) != 0u && !front) { hush_npr_lods[t] = o; return; }
  if (cross == 0.0 || hush_is_nonfinite(cross)) { hush_npr_lods[t] = o; return; }
  float zfar = max(max(z.x, z.y), z.z), nearest = min(min(z.x, z.y), z.z);
  if (!(zfar > 0.0)) { hush_npr_lods[t] = o; return; }  // entirely behind the camera
  // npr_gabor's blend, the share of the count per node (exact decisions: the factors are powers
  // of two): 1 with local density or crossing the near plane (w_near = zfar / 1024), else
  // log(zfar / (4 near)) / log(8 / 4) clamped to [0, 1] for zfar > 4 near, 0 below.
  bool crossing = nearest < HUSH_NPR_NEAR_FRACTION * zfar;
  float w_near = crossing ? HUSH_NPR_NEAR_FRACTION * zfar : 0.0, blend = 1.0;
  if (hush_local == 0u && !crossing)
    blend = zfar > HUSH_NPR_RATIO_LOW * nearest
                ? clamp(log2(zfar / (nearest * HUSH_NPR_RATIO_LOW)) * HUSH_NPR_RATIO_SCALE, 0.0, 1.0)
                : 0.0;
  hush_npr_kernel k = hush_npr_kernel_of(hush_npr_triangles[5u * t + 4u]);
  float r = k.size.x;
  float n;
  if (crossing) {
    // The root clipped: its part in front culls it, its count is the triangle's n (the bound
    // on every node's), as on the CPU.
    vec2 o2 = hush_npr_origin(t);
    hush_npr_node root;
    root.s01 = vec4(z.x * (s0 - o2), z.y * (s0 + e1 - o2));
    root.s2z = vec4(z.z * (s0 + e2 - o2), z.x, z.y);
    root.z2 = z.z;
    bool whole, meets;
    if (hush_npr_clip(root, w_near, k.size.y, o2, r, whole, n, meets) == 0 || !meets) {
      hush_npr_lods[t] = o;
      return;
    }
  } else {
    vec2 lo = s0 + min(min(e1, e2), vec2(0.0)), hi = s0 + max(max(e1, e2), vec2(0.0));
    if (hi.x + r < 0.0 || lo.x - r > float(hush_size.x) || hi.y + r < 0.0 ||
        lo.y - r > float(hush_size.y)) { hush_npr_lods[t] = o; return; }
    n = k.size.y * 0.5 * abs(cross);
  }
  if (!(n > 0.0)) { hush_npr_lods[t] = o; return; }
  n = min(n, HUSH_NPR_MAX_POINTS);
  float w1 = 1.0, w2 = 0.0, sq = 1.0;  // sq: the first M points' squared weight
  uint first = 0u, count = 0u;  // log2 M, log2 of the count
  if (n < 1.0) {
    sq = n;
    w1 = sqrt(n);
    if ((hush_opts & 2u) != 0u) {
      // npr_gabor::thinning_uniform: the stream's last two words, 27 + 26 bits.
      uint key = hush_stream_key(hush_npr_triangle_key(t), HUSH_NPR_STREAM);
      float u = float(hush_stream_word(key, ~1u) >> 5u) * HUSH_NPR_2M27 +
                float(hush_stream_word(key, ~0u) >> 6u) * HUSH_NPR_2M53;
      float g = n <= 0.5 ? max(0.0, 1.0 - u / (2.0 * n)) : 1.0 - 2.0 * (1.0 - n) * u;
      sq = g;
      w1 = sqrt(g);
      // No point; a count per node still walks the children of n > 1/4.
      if (!(w1 > 0.0) && !(blend > 0.0 && n > 0.25)) { hush_npr_lods[t] = o; return; }
    }
  } else {
    // M = 2^floor(log2 N) from the exponent bits (N >= 1 is normal): exact, as frexp.
    first = (floatBitsToUint(n) >> 23u) - 127u;
    w2 = sqrt(n / uintBitsToFloat((first + 127u) << 23u) - 1.0);  // alpha(N), eq. 4; exact N / M
    count = w2 > 0.0 ? first + 1u : first;
  }
  if (blend > 0.0) {
    // A count per node (npr_gabor::local_walk): the root's squared weight f = local_square(n,
    // coarsest) (n < 1: n or thinned, w1 above; crossing: 0), blended for blend < 1 with the
    // paper's (w1^2, the root being point 0 of the per-triangle LOD); the root's n for the
    // expand pass. Crossing, the per-triangle LOD has no points (the CPU's of(0)); with local
    // density it is not used (blend 1).
    // Unblended the weight is sqrt(local_square) or w1 itself (n < 1: sqrt(n) or thinned).
    float lw = crossing ? 0.0 : n >= 1.0 ? sqrt(hush_npr_local_square(n, true, false)) : w1;
    if (blend < 1.0) {
      float f = n >= 1.0 ? hush_npr_local_square(n, true, false) : sq;
      lw = sqrt(blend * f + (1.0 - blend) * sq);
    }
    o.walk = vec4(blend, n, w_near, lw);
    if (crossing) first = count = 0u;
  }
  // The plane: 1/z = 1/z_k + qx (x - s_k.x) + qy (y - s_k.y), k vertex 0, or crossing the near
  // plane the deepest vertex (a vertex behind the camera may project far off the frame).
  float d1 = 1.0 / z.y - 1.0 / z.x, d2 = 1.0 / z.z - 1.0 / z.x, inv = 1.0 / cross;
  uint kv = !crossing ? 0u : zfar == z.x ? 0u : zfar == z.y ? 1u : 2u;
  o.lod = uvec4(crossing ? 1u : count + 1u, first, floatBitsToUint(w1), floatBitsToUint(w2));
  o.plane = vec4(1.0 / z[kv], (d1 * e2.y - d2 * e1.y) * inv, (d2 * e1.x - d1 * e2.x) * inv,
                 float(kv));
  hush_npr_lods[t] = o;
  hush_npr_flags[t] = uvec2(0u, 1u);
}
)glsl";

// Pass 1, the exclusive prefix sum of uvec2 items (hush_items of them) in place, in blocks of
// 4 HUSH_NPR_SCAN items per work group: hush_add 0 scans each block (each invocation sums 4
// items, a Hillis-Steele scan in shared memory adds the 256 sums) and writes the block's total
// to hush_scan_sums[block]; hush_add 1 adds the scanned totals back. The host recurses on the
// totals (1024 ^ depth items), so any count scans in a few dispatches, deterministically.
constexpr const char* kNprGaborScan = R"glsl(
layout(local_size_x = HUSH_NPR_SCAN) in;
layout(std430, binding = 0) buffer hush_scan_data_b { uvec2 hush_scan_data[]; };
layout(std430, binding = 1) buffer hush_scan_sums_b { uvec2 hush_scan_sums[]; };
uniform uint hush_items_host, hush_add, hush_depth;  // items: 0xFFFFFFFF the plan's, at hush_depth
#define hush_items (hush_items_host != 0xFFFFFFFFu ? hush_items_host : hush_plan_items[hush_depth])
shared uvec2 hush_part[HUSH_NPR_SCAN];
void main() {
  uint g = hush_group_base + gl_WorkGroupID.x, i = gl_LocalInvocationID.x;
  uint base = (g * uint(HUSH_NPR_SCAN) + i) * 4u;
  if (hush_add != 0u) {
    uvec2 s = hush_scan_sums[g];
    for (uint k = 0u; k < 4u; ++k)
      if (base + k < hush_items) hush_scan_data[base + k] += s;
    return;
  }
  uvec2 v[4];
  uvec2 sum = uvec2(0u);
  for (uint k = 0u; k < 4u; ++k) {
    v[k] = base + k < hush_items ? hush_scan_data[base + k] : uvec2(0u);
    sum += v[k];
  }
  hush_part[i] = sum;
  barrier();
  for (uint d = 1u; d < uint(HUSH_NPR_SCAN); d <<= 1u) {
    uvec2 add = i >= d ? hush_part[i - d] : uvec2(0u);
    barrier();
    hush_part[i] += add;
    barrier();
  }
  uvec2 at = i == 0u ? uvec2(0u) : hush_part[i - 1u];
  for (uint k = 0u; k < 4u; ++k) {
    if (base + k < hush_items) hush_scan_data[base + k] = at;
    at += v[k];
  }
  if (i == uint(HUSH_NPR_SCAN) - 1u) hush_scan_sums[g] = hush_part[i];
}
)glsl";

// Pass 2, one invocation per triangle: the root node of each triangle with points, at its
// scanned offset (level 0 in triangle order).
constexpr const char* kNprGaborRoots = R"glsl(
layout(local_size_x = HUSH_NPR_GROUP) in;
layout(std430, binding = 3) readonly buffer hush_npr_lods_b { hush_npr_lod hush_npr_lods[]; };
layout(std430, binding = 4) readonly buffer hush_npr_flags_b { uvec2 hush_npr_offsets[]; };
layout(std430, binding = 6) writeonly buffer hush_npr_next_b { hush_npr_node hush_npr_next[]; };
void main() {
  uint t = hush_npr_item();
  if (t >= hush_tris || hush_npr_lods[t].lod.x == 0u) return;
  vec4 v0 = hush_npr_vertices[hush_npr_triangles[5u * t]];
  vec4 v1 = hush_npr_vertices[hush_npr_triangles[5u * t + 1u]];
  vec4 v2 = hush_npr_vertices[hush_npr_triangles[5u * t + 2u]];
  vec2 o = hush_npr_origin(t);
  hush_npr_node n;
  n.key = uvec4(hush_npr_triangle_key(t), t, 0u, 0u);
  n.s01 = vec4(v0.xy - o, v1.xy - o);
  n.s2z = vec4(v2.xy - o, v0.z, v1.z);
  n.z2 = v2.z;
  if (hush_npr_lods[t].walk.z > 0.0) {  // crossing the near plane: homogeneous corners
    n.s01 *= vec4(v0.zz, v1.zz);
    n.s2z.xy *= v2.z;
  }
  n.info = 0u;
  n.pad0 = n.pad1 = 0u;
  hush_npr_next[hush_npr_offsets[t].y] = n;
}
)glsl";

// Pass 3, one invocation per node of the level: whether its own point has a record (its pixel
// range is not empty) and which children are kept (index below the count, screen triangle
// grown by r meeting the frame); the scan input (records, children).
constexpr const char* kNprGaborExpand = R"glsl(
layout(local_size_x = HUSH_NPR_GROUP) in;
layout(std430, binding = 3) readonly buffer hush_npr_lods_b { hush_npr_lod hush_npr_lods[]; };
layout(std430, binding = 4) writeonly buffer hush_npr_flags_b { uvec2 hush_npr_flags[]; };
layout(std430, binding = 5) buffer hush_npr_level_b { hush_npr_node hush_npr_level[]; };
void main() {
  uint i = hush_npr_item();
  if (i >= hush_nodes) return;
  hush_npr_node nd = hush_npr_level[i];
  uint t = nd.key.y;
  hush_npr_lod l = hush_npr_lods[t];
  uint count = l.lod.x - 1u;  // log2 of the triangle's count
  float r = hush_npr_kernel_of(hush_npr_triangles[5u * t + 4u]).size.x;
  vec2 origin = hush_npr_origin(t);
  uint stream = hush_stream_key(nd.key.x, HUSH_NPR_STREAM);
  // A count per node (npr_gabor::local_walk; blend > 0): the node's count n (the root's from
  // the LOD pass) and its weight sqrt(f), kept in pad0 for the records pass; a record where
  // f > 0; children only below a node of n > 1/4 (or, blended with the paper's LOD, of a
  // child index below its count), above the finest level, each kept if its own n > 1/4 (or its
  // index is below the count). Crossing the near plane (homogeneous corners): a node's n is its
  // clipped part's, a crossing node has f = 0, a child behind w_near is dropped.
  float blend = l.walk.x, w_near = l.walk.z;
  bool local = blend > 0.0, paper = blend < 1.0, homog = w_near > 0.0;
  bool finest = hush_level == uint(HUSH_NPR_FINEST);
  float lambda = hush_npr_kernel_of(hush_npr_triangles[5u * t + 4u]).size.y, n = 0.0, lw = 0.0;
  if (local) {
    if (hush_level == 0u) {
      n = l.walk.y;
      lw = l.walk.w;
    } else {
      bool crossing = false;
      if (homog) {
        bool whole, meets;
        hush_npr_clip(nd, w_near, lambda, origin, r, whole, n, meets);
        crossing = !whole;
      } else {
        n = hush_npr_node_count(nd, lambda);
      }
      float f = crossing ? 0.0 : hush_npr_local_square(n, false, finest);
      if (paper) {
        float wp = hush_npr_lod_weight(l, nd.key.zw);
        f = blend * f + (1.0 - blend) * (wp * wp);
      }
      lw = sqrt(f);
    }
  }
  uint info = 0u, kids = 0u;
  if (!local || lw > 0.0) {
    vec2 base, d, p0, p1;
    hush_npr_own_point(nd, homog, origin, stream, r, base, d, p0, p1);
    info = any(greaterThan(p0, p1)) ? 0u : 1u;
  }
  uint order = hush_stream_word(stream, 2u);
  // The first child's index below the count (the paper's part of a blended walk).
  uvec2 j0 = hush_u64_add(nd.key.zw, hush_u64_shl(1u, 2u * hush_level));
  bool descend = !finest && (n > 0.25 || (paper && hush_u64_below_pow2(j0, count)));
  for (uint slot = 0u; slot < 4u; ++slot) {
    // index + stride (1 + slot) grows with slot: the first one past the count ends.
    uvec2 j = hush_u64_add(nd.key.zw, hush_u64_shl(1u + slot, 2u * hush_level));
    if (local ? !descend : !hush_u64_below_pow2(j, count)) break;
    hush_npr_node c = hush_npr_child(nd, homog, order, slot, j);
    bool keep;
    if (!local) {
      keep = hush_npr_meets_image(c, origin, r);
    } else {
      bool by_index = paper && hush_u64_below_pow2(j, count);
      if (homog) {
        bool whole, meets;
        float nc;
        keep = hush_npr_clip(c, w_near, lambda, origin, r, whole, nc, meets) > 0 &&
               (nc > 0.25 || by_index) && meets;
      } else {
        keep = (hush_npr_node_count(c, lambda) > 0.25 || by_index) &&
               hush_npr_meets_image(c, origin, r);
      }
    }
    if (keep) {
      info |= 2u << slot;
      ++kids;
    }
  }
  hush_npr_level[i].info = info;
  hush_npr_level[i].pad0 = floatBitsToUint(lw);
  hush_npr_flags[i] = uvec2(info & 1u, kids);
}
)glsl";

// Pass 4, one invocation per node of the level: its kept children at their scanned offsets in
// the next level's list (parent order, then slot order).
constexpr const char* kNprGaborChildren = R"glsl(
layout(local_size_x = HUSH_NPR_GROUP) in;
layout(std430, binding = 3) readonly buffer hush_npr_lods_b { hush_npr_lod hush_npr_lods[]; };
layout(std430, binding = 4) readonly buffer hush_npr_flags_b { uvec2 hush_npr_offsets[]; };
layout(std430, binding = 5) readonly buffer hush_npr_level_b { hush_npr_node hush_npr_level[]; };
layout(std430, binding = 6) writeonly buffer hush_npr_next_b { hush_npr_node hush_npr_next[]; };
void main() {
  uint i = hush_npr_item();
  if (i >= hush_nodes) return;
  hush_npr_node nd = hush_npr_level[i];
  if ((nd.info >> 1u) == 0u) return;
  uint at = hush_npr_offsets[i].y;
  uint order = hush_stream_word(hush_stream_key(nd.key.x, HUSH_NPR_STREAM), 2u);
  for (uint slot = 0u; slot < 4u; ++slot) {
    if ((nd.info & (2u << slot)) == 0u) continue;
    uvec2 j = hush_u64_add(nd.key.zw, hush_u64_shl(1u + slot, 2u * hush_level));
    if (at >= uint(hush_npr_next.length())) return;  // beyond the level's capacity: the plan flags it
    hush_npr_next[at++] = hush_npr_child(nd, hush_npr_lods[nd.key.y].walk.z > 0.0, order, slot, j);
  }
}
)glsl";

// Pass 5, one invocation per node of a level: its own point's record, if it has one and its
// frame-wide index (the level's first record + its scanned offset) falls in the batch
// [hush_base, hush_base + hush_batch): written at index - hush_base, with the ids (object,
// triangle id, J low, J high).
constexpr const char* kNprGaborRecordsPass = R"glsl(
layout(local_size_x = HUSH_NPR_GROUP) in;
layout(std430, binding = 3) readonly buffer hush_npr_lods_b { hush_npr_lod hush_npr_lods[]; };
layout(std430, binding = 4) readonly buffer hush_npr_flags_b { uvec2 hush_npr_offsets[]; };
layout(std430, binding = 5) readonly buffer hush_npr_level_b { hush_npr_node hush_npr_level[]; };
layout(std430, binding = 6) writeonly buffer hush_npr_out_b { hush_npr_splat hush_npr_out[]; };
layout(std430, binding = 7) writeonly buffer hush_npr_ids_b { uvec4 hush_npr_out_ids[]; };
uniform uint hush_isotropic;  // 1: each point's own angle
uniform uint hush_first_host;  // the level's first record in the frame (0xFFFFFFFF: the plan's)
#define hush_first (hush_first_host != 0xFFFFFFFFu ? hush_first_host : hush_plan_counts.y)
uniform uint hush_base, hush_batch;
void main() {
  uint i = hush_npr_item();
  if (i >= hush_nodes) return;
  hush_npr_node nd = hush_npr_level[i];
  if ((nd.info & 1u) == 0u) return;
  uint k = hush_first + hush_npr_offsets[i].x - hush_base;  // wraps above 2^31 when before
  if (k >= hush_batch) return;
  uint t = nd.key.y;
  hush_npr_lod l = hush_npr_lods[t];
  uint object = hush_npr_triangles[5u * t + 4u];
  hush_npr_kernel kn = hush_npr_kernel_of(object);
  uint stream = hush_stream_key(nd.key.x, HUSH_NPR_STREAM);
  vec2 origin = hush_npr_origin(t), base, d, p0, p1;
  hush_npr_own_point(nd, l.walk.z > 0.0, origin, stream, kn.size.x, base, d, p0, p1);
  hush_npr_splat o;
  o.box = ivec4(p0, p1);
  if (any(greaterThan(p0, p1))) o.box = ivec4(1, 1, 0, 0);
  // The first pixel centre's offset from the point, rounded at |p0 - origin| (within r + 1 of
  // the node) and at the node's size.
  o.kern.xy = ((p0 + 0.5 - origin) - base) - d;
  uint w1 = hush_stream_word(stream, 1u);
  float amplitude = 2.0 * hush_gabor_half(w1, 0u) - 1.0;
  float lw = l.walk.x > 0.0 ? uintBitsToFloat(nd.pad0)
                              : uintBitsToFloat(hush_u64_below_pow2(nd.key.zw, l.lod.y) ? l.lod.z
                                                                                      : l.lod.w);
  vec2 f = kn.freq.xy;
  if (hush_isotropic != 0u) {
    vec2 sc = hush_sincos_turns(hush_gabor_half(w1, 1u));
    f = kn.freq.z * vec2(sc.y, sc.x);
  }
  o.kern.zw = vec2(kn.freq.w, lw * amplitude * kn.size.z);
  o.freq = vec4(f, 0.0, 0.0);
  vec2 q = p0 + 0.5 - hush_npr_vertices[hush_npr_triangles[5u * t + uint(l.plane.w)]].xy;
  o.plane = vec4(l.plane.x + l.plane.y * q.x + l.plane.z * q.y, l.plane.y, l.plane.z, 0.0);
  hush_npr_out[k] = o;
  hush_npr_out_ids[k] = uvec4(object, hush_npr_triangles[5u * t + 3u], nd.key.zw);
}
)glsl";

// The walk's plan, one invocation after each scan (npr_gabor_gl_render: no read-back): from the
// scan's total (binding 0, first uvec2) it writes the next level's slot of the plan buffer
// (binding 1, uints; slot s at s * hush_plan_stride): (nodes, first record, records, nodes
// needed), the scan's items at depths 0 - 3 (words 4 - 7), the node passes' indirect dispatch
// commands (words 8 + 3 s, HUSH_PLAN_MAX_GROUPS groups of HUSH_NPR_GROUP per slice s) and the
// scan's (words 32 + 3 d, depth d); the level's own records (word 2 of its slot); in slot 0 the
// records so far (word 1), a count of levels clamped to their capacity (word 0) and, per level
// k, the most nodes it ever needed (word 8 + k); the draws' commands (hush_plan_draws: count,
// 1, 0, 0 per batch of hush_plan_batch records). A level needing more nodes than its buffers
// hold (hush_plan_cap) keeps the first hush_plan_cap (the children pass writes no further).
constexpr const char* kNprGaborPlan = R"glsl(
layout(local_size_x = 1) in;
layout(std430, binding = 0) readonly buffer hush_plan_total_b { uvec2 hush_plan_total[]; };
layout(std430, binding = 1) buffer hush_plan_b { uint hush_plan[]; };
uniform uint hush_plan_level;   // the level whose scan ended; 0xFFFFFFFF: the triangles' (roots)
uniform uint hush_plan_cap;     // nodes the next level's buffers hold
uniform uint hush_plan_stride;  // words per slot
uniform uint hush_plan_slices;  // indirect dispatches per node pass of the next level
uniform uint hush_plan_batch, hush_plan_batches, hush_plan_draws;
uint hush_plan_groups(uint n, uint size) { return n / size + (n % size != 0u ? 1u : 0u); }
void main() {
  uint s = hush_plan_stride, to = 1u, first = 0u;
  uvec2 total = hush_plan_total[0];
  if (hush_plan_level != 0xFFFFFFFFu) {
    uint from = 1u + hush_plan_level;
    to = from + 1u;
    if (hush_plan[from * s] == 0u) total = uvec2(0u);
    hush_plan[from * s + 2u] = total.x;
    first = hush_plan[from * s + 1u] + total.x;
  }
  uint needed = total.y, n = min(needed, hush_plan_cap), b = to * s;
  if (needed > hush_plan_cap) hush_plan[0] += 1u;
  if (to - 1u < HUSH_PLAN_LEVELS) hush_plan[8u + to - 1u] = max(hush_plan[8u + to - 1u], needed);
  hush_plan[b] = n;
  hush_plan[b + 1u] = first;
  hush_plan[b + 2u] = 0u;
  hush_plan[b + 3u] = needed;
  uint items = n;
  for (uint d = 0u; d < 4u; ++d) {
    uint groups = hush_plan_groups(items, uint(HUSH_PLAN_SCAN_BLOCK));
    hush_plan[b + 4u + d] = items;
    hush_plan[b + 32u + 3u * d] = groups;
    hush_plan[b + 33u + 3u * d] = 1u;
    hush_plan[b + 34u + 3u * d] = 1u;
    items = groups;
  }
  uint groups = hush_plan_groups(n, uint(HUSH_NPR_GROUP));
  for (uint i = 0u; i < hush_plan_slices; ++i) {
    uint lo = i * uint(HUSH_PLAN_MAX_GROUPS);
    hush_plan[b + 8u + 3u * i] = groups > lo ? min(groups - lo, uint(HUSH_PLAN_MAX_GROUPS)) : 0u;
    hush_plan[b + 9u + 3u * i] = 1u;
    hush_plan[b + 10u + 3u * i] = 1u;
  }
  hush_plan[1] = first;
  for (uint i = 0u; i < hush_plan_batches; ++i) {
    uint lo = i * hush_plan_batch, w = hush_plan_draws + 4u * i;
    hush_plan[w] = first > lo ? min(first - lo, hush_plan_batch) : 0u;
    hush_plan[w + 1u] = 1u;
    hush_plan[w + 2u] = 0u;
    hush_plan[w + 3u] = 0u;
  }
}
)glsl";

}  // namespace detail

// The compute passes of stage 1 on the GPU (#version 430 core): 0 LOD per triangle, 1 the
// prefix sum, 2 the roots, 3 expand a level, 4 its children, 5 its records; for hush
// glsl-export and tests.
constexpr int kNprGaborStage1Passes = 6;
// Work-group sizes (within GL 4.3's minimum of 1024 invocations per group); the scan's block
// is 4 items per invocation.
constexpr int kNprGaborGroupSize = 64;
constexpr int kNprGaborScanSize = 256;
constexpr std::size_t kNprGaborScanBlock = std::size_t{4} * kNprGaborScanSize;
// Bytes of one node of the walk and of one triangle's LOD (std430).
constexpr std::size_t kNprGaborNodeBytes = 64, kNprGaborLodBytes = 48;
// The walk's cull margin in pixels (absolute, and relative to the corners' coordinates):
// above the corners' float error, see hush_npr_meets_image.
constexpr double kNprGaborCullMargin = 1.0, kNprGaborCullRelative = 0x1p-16;
// The short name of stage 1's pass (0 ... kNprGaborStage1Passes - 1): its exported file is
// hush_npr_gabor_<name>.comp, its Vulkan uniform block hush_npr_gabor_<name>_params.
inline const char* npr_gabor_stage1_name(int pass) {
  static const char* const names[kNprGaborStage1Passes] = {"lods",   "scan",     "roots",
                                                           "expand", "children", "records"};
  return names[std::min(std::max(pass, 0), kNprGaborStage1Passes - 1)];
}
// The compute shader of stage 1's pass (#version 430 core; Vulkan too, hush/glsl/dialect.hpp).
inline std::string npr_gabor_stage1_source(int pass) {
  namespace c = hush::detail::constants;
  static const char* const names[kNprGaborStage1Passes] = {
      "counts and LOD weights per triangle", "prefix sum", "root nodes", "expand a level",
      "the next level's nodes", "one record per point"};
  static const char* const bodies[kNprGaborStage1Passes] = {
      detail::kNprGaborLods,   detail::kNprGaborScan,     detail::kNprGaborRoots,
      detail::kNprGaborExpand, detail::kNprGaborChildren, detail::kNprGaborRecordsPass};
  const int p = std::min(std::max(pass, 0), kNprGaborStage1Passes - 1);
  auto f32 = [](double v) {
    return glsl_literal(glsl_constant::type::f32, detail::float_bits(static_cast<float>(v)));
  };
  std::string table;
  for (unsigned i = 0; i < c::kNprGaborChildOrders; ++i)
    table += (i ? ", " : "") + std::to_string(c::kNprGaborChildOrder[i]) + "u";
  const std::string source =
      std::string("#version 430 core\n// hush " HUSH_VERSION_STRING " NPR Gabor stage 1: ") +
      names[p] + " (hush/glsl/npr_gabor/glsl.hpp).\n#define HUSH_NPR_GROUP " +
      std::to_string(kNprGaborGroupSize) + "\n#define HUSH_NPR_SCAN " +
      std::to_string(kNprGaborScanSize) + "\n#define HUSH_NPR_STREAM " +
      std::to_string(c::kNprGaborStream) + "u\n#define HUSH_NPR_MAX_POINTS " +
      f32(c::kNprGaborMaxPoints) + "\n#define HUSH_NPR_2M27 " + f32(0x1p-27) +
      "\n#define HUSH_NPR_2M53 " + f32(0x1p-53) + "\n#define HUSH_NPR_ORDERS " +
      std::to_string(c::kNprGaborChildOrders) + "\n#define HUSH_NPR_ORDER_TABLE " + table +
      "\n#define HUSH_NPR_CULL_MARGIN " + f32(kNprGaborCullMargin) +
      "\n#define HUSH_NPR_CULL_RELATIVE " + f32(kNprGaborCullRelative) +
      "\n#define HUSH_NPR_FINEST " + std::to_string(npr_gabor::max_depth()) + "u" +
      "\n#define HUSH_NPR_NEAR_FRACTION " + f32(c::kNprGaborNearFraction) +
      "\n#define HUSH_NPR_RATIO_LOW " + f32(c::kNprGaborPerNodeRatioLow) +
      "\n#define HUSH_NPR_RATIO_SCALE " +
      f32(1.0 / std::log2(c::kNprGaborPerNodeRatioHigh / c::kNprGaborPerNodeRatioLow)) + "\n" +
      library() + detail::kNprGaborRecord + detail::kNprGaborStage1Common + bodies[p];
  return dual_dialect(source,
                      std::string("hush_npr_gabor_") + npr_gabor_stage1_name(p) + "_params");
}
// The GPU-resident walk (hush/glsl/npr_gabor/frame.hpp): its levels 0 ... npr_gabor::max_depth()
// (the finest keeps no children), and the work groups per indirect dispatch (GL 4.3's minimum
// GL_MAX_COMPUTE_WORK_GROUP_COUNT).
constexpr std::size_t kNprGaborPlanLevels = 22;
constexpr std::size_t kNprGaborMaxGroups = 65535;
static_assert(kNprGaborPlanLevels == std::size_t{npr_gabor::max_depth()} + 1,
              "the resident walk has a slot per level");
// The walk's plan pass (kNprGaborPlan; #version 430 core; Vulkan too, hush/glsl/dialect.hpp):
// kNprGaborPlanLevels + 1 slots of needed counts in slot 0, dispatches of at most
// kNprGaborMaxGroups groups. Exported as hush_npr_gabor_plan.comp.
inline std::string npr_gabor_plan_source() {
  return dual_dialect(
      std::string("#version 430 core\n// hush " HUSH_VERSION_STRING
                  " NPR Gabor stage 1: the walk's plan (hush/glsl/npr_gabor/glsl.hpp).\n"
                  "#define HUSH_NPR_GROUP ") +
          std::to_string(kNprGaborGroupSize) + "\n#define HUSH_PLAN_SCAN_BLOCK " +
          std::to_string(kNprGaborScanBlock) + "\n#define HUSH_PLAN_MAX_GROUPS " +
          std::to_string(kNprGaborMaxGroups) + "u\n#define HUSH_PLAN_LEVELS " +
          std::to_string(kNprGaborPlanLevels + 1) + "u\n" + detail::kNprGaborPlan,
      "hush_npr_gabor_plan_params");
}
// The sources of the three stages (#version 430 core; Vulkan too, hush/glsl/dialect.hpp), for
// hush glsl-export and tests. Under Vulkan the geometry stage's uniform block
// hush_npr_gabor_splat_params is a prefix of the fragment stage's (hush_size first): one
// buffer at kVulkanParamsBinding serves both.
inline std::string npr_gabor_vertex_source() {
  return std::string("#version 430 core\n// hush " HUSH_VERSION_STRING
                     " NPR Gabor splats: vertex stage (hush/glsl/npr_gabor/glsl.hpp).\n") +
         detail::kNprGaborVertex;
}
inline std::string npr_gabor_geometry_source() {
  return dual_dialect(
      std::string("#version 430 core\n// hush " HUSH_VERSION_STRING
                  " NPR Gabor splats: geometry stage, one quad per record.\n#define "
                  "HUSH_NPR_SPRITE_VERTICES ") +
          std::to_string(kNprGaborSpriteVertices) + "\n" + detail::kNprGaborRecord +
          detail::kNprGaborRecords + detail::kNprGaborGeometry,
      "hush_npr_gabor_splat_params");
}
inline std::string npr_gabor_fragment_source() {
  return dual_dialect(std::string("#version 430 core\n// hush " HUSH_VERSION_STRING
                                  " NPR Gabor splats: fragment stage, tests and kernel.\n") +
                          library() + detail::kNprGaborRecord + detail::kNprGaborRecords +
                          detail::kNprGaborFragment,
                      "hush_npr_gabor_splat_params");
}

namespace detail {

// The files `hush glsl-export` writes for NPR Gabor noise (hush/glsl/export.hpp), as
// (file name, text): the splat program's three stages, then stage 1's passes in order and
// the resident walk's plan pass.
inline std::vector<std::pair<std::string, std::string>> npr_gabor_exports() {
  std::vector<std::pair<std::string, std::string>> files = {
      {"hush_npr_gabor_splat.vert", npr_gabor_vertex_source()},
      {"hush_npr_gabor_splat.geom", npr_gabor_geometry_source()},
      {"hush_npr_gabor_splat.frag", npr_gabor_fragment_source()}};
  for (int i = 0; i < kNprGaborStage1Passes; ++i)
    files.emplace_back(std::string("hush_npr_gabor_") + npr_gabor_stage1_name(i) + ".comp",
                       npr_gabor_stage1_source(i));
  files.emplace_back("hush_npr_gabor_plan.comp", npr_gabor_plan_source());
  return files;
}

}  // namespace detail

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_NPR_GABOR_GLSL_HPP

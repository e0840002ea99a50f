// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// NPR Gabor noise (include/hush/npr_gabor.hpp) on the GPU, the paper's way (Benard et al.
// 2010, sec. 3.4 and 5): stage 1 (the points) in compute passes, stage 2 (the splatting) as
// point sprites. Include this header to use hush::exec::glsl{device} with
// hush::npr_gabor::render and ::splat:
//
//   hush::glsl::headless_device gpu;                // or a device on the application's context
//   noise.render(hush::exec::glsl{gpu.device}, frame, triangles, out);
//
// Stage 1 (render): where every parameter source is constant or per object, the triangle list
// (vertices: screen x, y, depth; triangles: indices, id, object) and a per-object kernel table
// (npr_gabor::kernel_of_object, double, rounded once) go to storage buffers and compute passes
// walk each triangle's hierarchical point sequence (hush/npr_gabor/tree.hpp) level by
// level, as the CPU walks it depth first: per triangle its count and LOD weights in float
// (npr_gabor_lod, the thinning, the plane of 1/z) and its root node (level 0, at a scanned
// offset); per level one pass decides for each node whether its own point reaches the frame
// and which children to keep (index below the count, or with a count per node -- params::
// local_density, a triangle crossing the near plane or of depth ratio above 4 -- the node's
// own count n = lambda A above 1/4, its weight sqrt(n h(n)) per node as on the CPU, blended
// with the per-triangle LOD's for ratios 4 - 8; a crossing triangle's nodes carry homogeneous
// corners (z (s - o), z), clipped at w_near = far / 1024; screen triangle grown by r, or the
// clipped part's projection, meeting the frame), a multi-level prefix sum gives every record and child its offset, a second pass
// writes the children as the next level's list. The host reads back each level's two totals
// (8 bytes) to size the next level; nothing is dropped (a level beyond one storage block runs
// stage 1 on the CPU instead). Then one pass per level writes the records at their scanned
// offsets, batch by batch: level by level, each in its list's order, the same order every run
// (no atomics), hence the same image. J (up to 2^41) is a uvec2; node corners are carried down
// as perspective-correct midpoints in float (homogeneous: plain midpoints). Per-pixel or
// per-vertex sources, buffers beyond one storage block, or more than 2^32 - 1 records: stage 1
// on the CPU (make_splats), automatically. Float instead of double changes positions, weights and planes within the
// tolerance derived in tests/glsl/glsl_gabor_test.cpp (npr_tolerance_of); where float and
// double N straddle a power of two the second M points (weight <= sqrt(2 nu), nu N's relative
// float error) exist on one side only; with params::local_density, likewise a node whose float
// and double counts straddle a cut of the hat (1/4, 4): its record (weight <= sqrt((1 +
// 1/ln 4) nu_P n + n 2^-21), nu_P its count's relative error) exists on one side only; near the
// near plane also a node with a corner within its float depth error of w_near (crossing, weight
// 0, on one side). The homogeneous corners' float error: docs/npr-gabor.md "Triangles crossing
// the near plane", GPU.
//
// Stage 2: the records (made on the GPU or uploaded from the CPU's stage 1; shader storage
// buffers, 64 + 16 bytes each) are drawn as GL_POINTS, one vertex per record, in record order. A
// geometry shader turns each into one screen-aligned quad covering the record's pixel range x0 ...
// x1 + 1, y0 ... y1 + 1 (its kernel's disc, clamped to the image), a fragment shader runs the
// visibility tests against the G-buffer (object id, triangle id, depth with its tolerance, soft
// depth; SSBOs uploaded by frame_upload.hpp) and evaluates the tapered Gabor kernel with the
// library's float functions (the CPU's float operations, hush/glsl/gabor_glsl.hpp), and additive
// blending (GL_ONE, GL_ONE) sums the fragments into a GL_R32F framebuffer texture, read back into
// `out`. The normalisation is the CPU's: the weights in the records.
//
// The GL geometry-output limit: one input point emits one quad, 4 vertices of 5 components
// (gl_Position and the record index), a fixed max_vertices = 4 that no GL can refuse
// (GL_MAX_GEOMETRY_OUTPUT_VERTICES >= 256 and GL_MAX_GEOMETRY_TOTAL_OUTPUT_COMPONENTS >= 1024
// are the GL 3.2 minimums); a kernel's size never changes the vertex count, only the quad's
// size. npr_gabor_gl_limits() queries the limits; the renderer checks them once anyway.
// Records beyond one storage block (GL_MAX_SHADER_STORAGE_BLOCK_SIZE / 64) are drawn in
// several draws, in order. Frames up to GL_MAX_TEXTURE_SIZE, GL_MAX_VIEWPORT_DIMS and
// GL_MAX_RENDERBUFFER_SIZE (hush::invalid_argument naming the frame size otherwise).
//
// Agreement with the CPU (tests/glsl/glsl_gabor_test.cpp, "npr"): GL blends the fragments of
// one draw in primitive order, so every pixel sums the same kernels in the CPU's record order;
// what differs is each kernel's float value: the offsets are formed relative to the record's
// first pixel (in double on the CPU, then rounded: no large coordinate reaches the GPU, which
// has no fp64), and GLSL may fuse multiply-adds. Per pixel p reached by kernels i with weights
// w_i, the image is within S(p) (2 K + 2^-24 n(p)) of the double reference, S(p) = sum |w_i|,
//   K = 2^-21 (1 + 2 pi F0 r) + 2 2^-21 (2 A + 2 pi F0 r + 2 / (1 - s0)) [+ 4 2^-24 / tolerance]
// (A = ln(1/t), s0 the taper start): the kernel's float budget of gabor_kernel.hpp; the
// offsets' rounding (<= 2^-21 in units of r per axis) times the kernel's slope (envelope,
// harmonic, taper) on both axes; with the soft test, the fade's rounding. 2 K for GPUs whose
// float ops err by 2 ulp; n(p) 2^-24 S(p) the sums' rounding. The visibility decisions are the
// CPU's except at ties: the depth test's relative difference is formed in float (the plane relative
// to the first pixel), so a fragment whose relative depth difference is within 2^-18 of the
// tolerance (or of twice it, soft) may be decided the other way; object and triangle tests compare
// integers (exact).
//
// Depths: a pixel's depth must be positive and finite, as on the CPU; a denormal depth reads as
// 0 (fails) on GPUs that flush denormals, where the CPU passes it to the plane comparison. The
// same holds for vertex depths in GPU stage 1: a triangle with a denormal vertex depth emits
// nothing there.
//
// Throws std::runtime_error for GL errors (and when the context lacks storage blocks in the
// geometry or fragment stage: GL 4.3 requires them only in compute shaders; every desktop
// driver has them). Leaves the current program, vertex array, framebuffers, viewport, blend and
// the enables it touches (blend, depth, stencil, scissor, cull face) as it found them; rebinds
// the indexed storage-buffer bindings 0 to 7 (as hush::glsl::device does).
#ifndef HUSH_GLSL_NPR_GABOR_HPP
#define HUSH_GLSL_NPR_GABOR_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "hush/detail/constants.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/device.hpp"
#include "hush/glsl/frame_upload.hpp"
#include "hush/glsl/library.hpp"
#include "hush/npr_gabor.hpp"
#include "hush/npr_gabor/splat.hpp"

namespace hush {
namespace glsl {

// The geometry shader's output per input point: one quad.
constexpr int kNprGaborSpriteVertices = 4;
// Components per emitted vertex: gl_Position (4) and the record index (1).
constexpr int kNprGaborSpriteComponents = 5;
// Bytes of one record in the storage buffer (4 vec4s, std430).
constexpr std::size_t kNprGaborRecordBytes = 64;

// The GL limits the renderer depends on, as the context reports them.
struct npr_gabor_limits {
  int max_geometry_output_vertices = 0;    // GL_MAX_GEOMETRY_OUTPUT_VERTICES
  int max_geometry_output_components = 0;  // GL_MAX_GEOMETRY_TOTAL_OUTPUT_COMPONENTS
  int max_geometry_storage_blocks = 0;     // GL_MAX_GEOMETRY_SHADER_STORAGE_BLOCKS
  int max_fragment_storage_blocks = 0;     // GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS
  int max_frame_side =
      0;  // min(GL_MAX_TEXTURE_SIZE, GL_MAX_VIEWPORT_DIMS, GL_MAX_RENDERBUFFER_SIZE)
  // Whether one quad per input point fits the geometry-output limits.
  bool sprites_fit() const {
    return kNprGaborSpriteVertices <= max_geometry_output_vertices &&
           kNprGaborSpriteVertices * kNprGaborSpriteComponents <= max_geometry_output_components;
  }
};

namespace detail {

// GL enums of the raster path (Khronos gl.xml).
constexpr gl_enum kGlFramebuffer = 0x8D40;
constexpr gl_enum kGlColorAttachment0 = 0x8CE0;
constexpr gl_enum kGlFramebufferComplete = 0x8CD5;
constexpr gl_enum kGlDrawFramebufferBinding = 0x8CA6;
constexpr gl_enum kGlReadFramebufferBinding = 0x8CAA;
constexpr gl_enum kGlDrawFramebuffer = 0x8CA9;
constexpr gl_enum kGlReadFramebuffer = 0x8CA8;
constexpr gl_enum kGlR32f = 0x822E;
constexpr gl_enum kGlRed = 0x1903;
constexpr gl_enum kGlPoints = 0x0000;
constexpr gl_enum kGlBlend = 0x0BE2;
constexpr gl_enum kGlOne = 1;
constexpr gl_enum kGlFuncAdd = 0x8006;
constexpr gl_enum kGlDepthTest = 0x0B71;
constexpr gl_enum kGlScissorTest = 0x0C11;
constexpr gl_enum kGlCullFace = 0x0B44;
constexpr gl_enum kGlStencilTest = 0x0B90;
constexpr gl_bitfield kGlColorBufferBit = 0x4000;
constexpr gl_enum kGlViewport = 0x0BA2;
constexpr gl_enum kGlMaxGeometryOutputVertices = 0x8DE0;
constexpr gl_enum kGlMaxGeometryTotalOutputComponents = 0x8DE1;
constexpr gl_enum kGlMaxGeometryShaderStorageBlocks = 0x90D7;
constexpr gl_enum kGlMaxFragmentShaderStorageBlocks = 0x90DA;
constexpr gl_enum kGlMaxViewportDims = 0x0D3A;
constexpr gl_enum kGlMaxRenderbufferSize = 0x84E8;
constexpr gl_enum kGlPackAlignment = 0x0D05;
constexpr gl_enum kGlVertexArrayBinding = 0x85B5;
constexpr gl_enum kGlNearest = 0x2600;
constexpr gl_enum kGlBlendSrcRgb = 0x80C9;
constexpr gl_enum kGlBlendDstRgb = 0x80C8;
constexpr gl_enum kGlBlendSrcAlpha = 0x80CB;
constexpr gl_enum kGlBlendDstAlpha = 0x80CA;
constexpr gl_enum kGlBlendEquationRgb = 0x8009;
constexpr gl_enum kGlBlendEquationAlpha = 0x883D;

// The entry points of the raster path (GL 3.x core), loaded from the device's loader.
struct gl_raster_api {
  void(HUSH_GLAPI* GenFramebuffers)(gl_sizei, gl_uint*) = nullptr;
  void(HUSH_GLAPI* DeleteFramebuffers)(gl_sizei, const gl_uint*) = nullptr;
  void(HUSH_GLAPI* BindFramebuffer)(gl_enum, gl_uint) = nullptr;
  void(HUSH_GLAPI* FramebufferTexture2D)(gl_enum, gl_enum, gl_enum, gl_uint, gl_int) = nullptr;
  gl_enum(HUSH_GLAPI* CheckFramebufferStatus)(gl_enum) = nullptr;
  void(HUSH_GLAPI* GenVertexArrays)(gl_sizei, gl_uint*) = nullptr;
  void(HUSH_GLAPI* DeleteVertexArrays)(gl_sizei, const gl_uint*) = nullptr;
  void(HUSH_GLAPI* BindVertexArray)(gl_uint) = nullptr;
  void(HUSH_GLAPI* DrawArrays)(gl_enum, gl_int, gl_sizei) = nullptr;
  void(HUSH_GLAPI* Viewport)(gl_int, gl_int, gl_sizei, gl_sizei) = nullptr;
  void(HUSH_GLAPI* Enable)(gl_enum) = nullptr;
  void(HUSH_GLAPI* Disable)(gl_enum) = nullptr;
  unsigned char(HUSH_GLAPI* IsEnabled)(gl_enum) = nullptr;
  void(HUSH_GLAPI* BlendFuncSeparate)(gl_enum, gl_enum, gl_enum, gl_enum) = nullptr;
  void(HUSH_GLAPI* BlendEquationSeparate)(gl_enum, gl_enum) = nullptr;
  void(HUSH_GLAPI* ClearColor)(float, float, float, float) = nullptr;
  void(HUSH_GLAPI* Clear)(gl_bitfield) = nullptr;
  void(HUSH_GLAPI* ReadPixels)(gl_int, gl_int, gl_sizei, gl_sizei, gl_enum, gl_enum,
                               void*) = nullptr;

  explicit gl_raster_api(loader_fn loader) {
    gl_api::load(loader, GenFramebuffers, "glGenFramebuffers");
    gl_api::load(loader, DeleteFramebuffers, "glDeleteFramebuffers");
    gl_api::load(loader, BindFramebuffer, "glBindFramebuffer");
    gl_api::load(loader, FramebufferTexture2D, "glFramebufferTexture2D");
    gl_api::load(loader, CheckFramebufferStatus, "glCheckFramebufferStatus");
    gl_api::load(loader, GenVertexArrays, "glGenVertexArrays");
    gl_api::load(loader, DeleteVertexArrays, "glDeleteVertexArrays");
    gl_api::load(loader, BindVertexArray, "glBindVertexArray");
    gl_api::load(loader, DrawArrays, "glDrawArrays");
    gl_api::load(loader, Viewport, "glViewport");
    gl_api::load(loader, Enable, "glEnable");
    gl_api::load(loader, Disable, "glDisable");
    gl_api::load(loader, IsEnabled, "glIsEnabled");
    gl_api::load(loader, BlendFuncSeparate, "glBlendFuncSeparate");
    gl_api::load(loader, BlendEquationSeparate, "glBlendEquationSeparate");
    gl_api::load(loader, ClearColor, "glClearColor");
    gl_api::load(loader, Clear, "glClear");
    gl_api::load(loader, ReadPixels, "glReadPixels");
  }
};

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
flat out uint hush_v_splat;
void main() {
  hush_v_splat = uint(gl_VertexID);
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
)glsl";

// One quad over the record's pixels: window x in [x0, x1 + 1] holds the centres x0 + 1/2 ...
// x1 + 1/2 well inside (no edge ties); window y is image y (the read-back keeps row order).
constexpr const char* kNprGaborGeometry = R"glsl(
layout(points) in;
layout(triangle_strip, max_vertices = HUSH_NPR_SPRITE_VERTICES) out;
flat in uint hush_v_splat[];
flat out uint hush_g_splat;
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
flat in uint hush_g_splat;
layout(location = 0) out float hush_npr_out;
uniform uint hush_flags;      // 1 object test, 2 triangle test, 4 depth test, 8 soft
uniform float hush_tolerance;
uniform float hush_neg_a;     // -ln(1/t)
uniform float hush_taper_k;   // 1 / (1 - taper start)
layout(std430, binding = 4) readonly buffer hush_npr_ids_b { uvec4 hush_npr_ids[]; };
layout(std430, binding = 1) readonly buffer hush_npr_depth_b { float hush_npr_depth[]; };
layout(std430, binding = 2) readonly buffer hush_npr_object_b { uint hush_npr_object[]; };
layout(std430, binding = 3) readonly buffer hush_npr_triangle_b { uint hush_npr_triangle[]; };
void main() {
  hush_npr_splat s = hush_npr_splats[hush_g_splat];
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (any(lessThan(p, s.box.xy)) || any(greaterThan(p, s.box.zw))) discard;
  vec2 k = vec2(p - s.box.xy);  // pixels from the first pixel: small integers, exact
  hush_gabor_axis ax = hush_gabor_axis_factors((s.kern.x + k.x) * s.kern.z, hush_neg_a, s.freq.x);
  hush_gabor_axis ay = hush_gabor_axis_factors((s.kern.y + k.y) * s.kern.z, hush_neg_a, s.freq.y);
  if (!(ax.d2 + ay.d2 < 1.0)) discard;
  uint n = uint(p.y) * hush_size.x + uint(p.x);
  uvec2 ids = hush_npr_ids[hush_g_splat].xy;  // (object, triangle id, J low, J high)
  if ((hush_flags & 1u) != 0u && hush_npr_object[n] != ids.x) discard;
  if ((hush_flags & 2u) != 0u && hush_npr_triangle[n] != ids.y) discard;
  float vis = 1.0;
  if ((hush_flags & 4u) != 0u) {
    precise float zp = hush_npr_depth[n];
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
// (perspective-correct midpoints of its parent's: npr_gabor/tree.hpp's corners projected;
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
uniform uint hush_nodes;       // nodes of this level
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
// The node's own point (npr_gabor/tree.hpp: word 0 of its stream, local barycentrics
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
// The child at `slot` (npr_gabor/tree.hpp's npr_tree_child): geometric child c from the order
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
uniform uint hush_opts;  // 1 cull back faces, 2 thinning
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
  if ((hush_opts & 1u) != 0u && !(facing < 0.0)) { hush_npr_lods[t] = o; return; }
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
uniform uint hush_items, hush_add;
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
uniform uint hush_first;      // the level's first record in the frame
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
  return std::string("#version 430 core\n// hush " HUSH_VERSION_STRING " NPR Gabor stage 1: ") +
         names[p] + " (hush/glsl/npr_gabor.hpp).\n#define HUSH_NPR_GROUP " +
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
         library() +
         detail::kNprGaborRecord + detail::kNprGaborStage1Common + bodies[p];
}
// The sources of the three stages (#version 430 core), for hush glsl-export and tests.
inline std::string npr_gabor_vertex_source() {
  return std::string("#version 430 core\n// hush " HUSH_VERSION_STRING
                     " NPR Gabor splats: vertex stage (hush/glsl/npr_gabor.hpp).\n") +
         detail::kNprGaborVertex;
}
inline std::string npr_gabor_geometry_source() {
  return std::string("#version 430 core\n// hush " HUSH_VERSION_STRING
                     " NPR Gabor splats: geometry stage, one quad per record.\n#define "
                     "HUSH_NPR_SPRITE_VERTICES ") +
         std::to_string(kNprGaborSpriteVertices) + "\n" + detail::kNprGaborRecord +
         detail::kNprGaborRecords + detail::kNprGaborGeometry;
}
inline std::string npr_gabor_fragment_source() {
  return std::string("#version 430 core\n// hush " HUSH_VERSION_STRING
                     " NPR Gabor splats: fragment stage, tests and kernel.\n") +
         library() + detail::kNprGaborRecord + detail::kNprGaborRecords + detail::kNprGaborFragment;
}

// The limits of the context current on this thread (see npr_gabor_limits).
inline npr_gabor_limits npr_gabor_gl_limits(const detail::gl_api& gl) {
  npr_gabor_limits l;
  gl.GetIntegerv(detail::kGlMaxGeometryOutputVertices, &l.max_geometry_output_vertices);
  gl.GetIntegerv(detail::kGlMaxGeometryTotalOutputComponents, &l.max_geometry_output_components);
  gl.GetIntegerv(detail::kGlMaxGeometryShaderStorageBlocks, &l.max_geometry_storage_blocks);
  gl.GetIntegerv(detail::kGlMaxFragmentShaderStorageBlocks, &l.max_fragment_storage_blocks);
  detail::gl_int tex = 0, rb = 0, vp[2] = {0, 0};
  gl.GetIntegerv(detail::kGlMaxTextureSize, &tex);
  gl.GetIntegerv(detail::kGlMaxRenderbufferSize, &rb);
  gl.GetIntegerv(detail::kGlMaxViewportDims, vp);
  l.max_frame_side = std::min({tex, rb, vp[0], vp[1]});
  gl.check("hush::glsl::npr_gabor: querying limits");
  return l;
}

// One record as the shaders read it (std430, 64 bytes): the pixel range; the first pixel
// centre's offset from the point (cx, cy) = (x0 + 1/2, y0 + 1/2) - position, 1/r and the
// weight; (F_x r, F_y r); the plane of 1/z at the first pixel centre and its slopes.
struct npr_gabor_gpu_record {
  std::int32_t box[4];  // x0, y0, x1, y1 (x0 > x1: empty, drawn as nothing)
  float kern[4];        // cx, cy, 1/r, weight
  float freq[4];        // F_x r, F_y r, -, -
  float plane[4];       // 1/z at (x0 + 1/2, y0 + 1/2), d(1/z)/dx, d(1/z)/dy, -
  // The CPU record's form: offsets and the plane formed in double and rounded once.
  static npr_gabor_gpu_record of(const npr_gabor_splat& r) {
    const double fx0 = static_cast<double>(r.x0) + 0.5, fy0 = static_cast<double>(r.y0) + 0.5;
    return {{r.x0, r.y0, r.x1, r.y1},
            {static_cast<float>(fx0 - r.x), static_cast<float>(fy0 - r.y),
             static_cast<float>(1.0 / r.radius), static_cast<float>(r.weight)},
            {static_cast<float>(r.fx * r.radius), static_cast<float>(r.fy * r.radius), 0.0f, 0.0f},
            {static_cast<float>(r.q0 + r.qx * fx0 + r.qy * fy0), static_cast<float>(r.qx),
             static_cast<float>(r.qy), 0.0f}};
  }
};
static_assert(sizeof(npr_gabor_gpu_record) == kNprGaborRecordBytes, "std430 record layout");

namespace detail {

// The GPU side of NPR Gabor splatting on one device: program, framebuffer, buffers.
class npr_gabor_gpu {
 public:
  explicit npr_gabor_gpu(glsl::device& dev)
      : dev_(dev), gl_(dev.gl()), gr_(dev.gl().loader), frame_(gl_, dev.max_buffer_bytes()) {
    limits_ = npr_gabor_gl_limits(gl_);
    if (!limits_.sprites_fit() || limits_.max_geometry_storage_blocks < 1 ||
        limits_.max_fragment_storage_blocks < 5)
      throw std::runtime_error(
          "hush::glsl::npr_gabor: the context lacks what the splatting needs (a quad of 4 "
          "vertices from the geometry stage, 1 storage block there and 5 in the fragment stage)");
    program_ = link_program(gl_, {{kGlVertexShader, npr_gabor_vertex_source()},
                                  {kGlGeometryShader, npr_gabor_geometry_source()},
                                  {kGlFragmentShader, npr_gabor_fragment_source()}});
    for (int i = 0; i < kNprGaborStage1Passes; ++i)
      stage1_[i] = link_program(gl_, {{kGlComputeShader, npr_gabor_stage1_source(i)}});
    gl_.GenBuffers(2, buffers_);
    gl_.GenBuffers(kStage1Buffers, stage1_buffers_);
    gl_.GenTextures(1, &texture_);
    gr_.GenFramebuffers(1, &fbo_);
    gr_.GenVertexArrays(1, &vao_);
    gl_.check("hush::glsl::npr_gabor: setting up");
  }
  npr_gabor_gpu(const npr_gabor_gpu&) = delete;
  npr_gabor_gpu& operator=(const npr_gabor_gpu&) = delete;
  ~npr_gabor_gpu() {
    gr_.DeleteVertexArrays(1, &vao_);
    gr_.DeleteFramebuffers(1, &fbo_);
    gl_.DeleteTextures(1, &texture_);
    gl_.DeleteBuffers(kStage1Buffers, stage1_buffers_);
    for (const std::vector<gl_uint>* v : {&level_nodes_, &level_flags_, &scan_sums_})
      if (!v->empty()) gl_.DeleteBuffers(static_cast<gl_sizei>(v->size()), v->data());
    gl_.DeleteBuffers(2, buffers_);
  }

  const npr_gabor_limits& limits() const { return limits_; }
  std::size_t draws() const { return draws_; }
  // Frames whose stage 1 ran on the GPU (render), and those it handed back to the CPU.
  std::size_t gpu_stage1_frames() const { return gpu_frames_; }
  std::size_t cpu_stage1_frames() const { return cpu_frames_; }
  // The last GPU stage 1's walk: nodes visited (every level's list) and levels.
  std::uint64_t stage1_nodes() const { return nodes_; }
  std::size_t stage1_levels() const { return levels_; }

  // Stage 2 of `j` into out (frame-sized, validated by npr_gabor::splat).
  void splat(const hush::detail::npr_gabor_splat_job& j, const image_view<float>& out) {
    draw(j, out, j.count, [&](std::size_t b0, std::size_t m) { pack(j.splats + b0, m); });
  }

  // Both stages of noise.render on the GPU (arguments validated by render); stage 1 on the
  // CPU where the GPU cannot run it (a per-pixel or per-vertex source, buffers beyond one
  // storage block: a level's nodes included; more than 2^32 - 1 records or nodes).
  void render(const npr_gabor& noise, const frame& f, const triangle_list& tris,
              const npr_gabor::sources& src, const image_view<float>& out) {
    std::size_t total = 0;
    if (!stage1(noise, f, tris, src, total)) {
      ++cpu_frames_;
      std::vector<npr_gabor_splat> splats;
      noise.make_splats(f, tris, splats, src);
      splat(noise.splat_job(f, splats.data(), splats.size()), out);
      return;
    }
    ++gpu_frames_;
    const state_guard guard(gl_, gr_);  // generate() switches programs between the draws
    draw(noise.splat_job(f, nullptr, 0), out, total,
         [&](std::size_t b0, std::size_t m) { generate(b0, m); });
  }

  // Stage 1 on the GPU alone, its records read back: for each record in order whose pixel
  // range is not empty, the 16 words of npr_gabor_gpu_record (box, kern, freq, plane) and 4
  // ids (object, triangle id, J low, J high); `empty` counts the others (a record whose box,
  // recomputed by the records pass, came out empty: none expected). Records come level by
  // level, each level in its list's order. False (nothing written) where render would run
  // stage 1 on the CPU. For tests and debugging.
  bool records(const npr_gabor& noise, const frame& f, const triangle_list& tris,
               const npr_gabor::sources& src, std::vector<std::uint32_t>& words,
               std::vector<std::uint32_t>& ids, std::size_t& empty) {
    std::size_t total = 0;
    if (!stage1(noise, f, tris, src, total)) return false;
    const state_guard guard(gl_, gr_);
    words.clear();
    ids.clear();
    empty = 0;
    const std::size_t batch = batch_records();
    std::vector<std::uint32_t> w, d;
    for (std::size_t b0 = 0; b0 < total; b0 += batch) {
      const std::size_t m = std::min(batch, total - b0);
      generate(b0, m);
      gl_.MemoryBarrier(kGlBufferUpdateBarrierBit);
      w.resize(m * 16);
      d.resize(m * 4);
      gl_.BindBuffer(kGlShaderStorageBuffer, buffers_[0]);
      gl_.GetBufferSubData(kGlShaderStorageBuffer, 0, static_cast<gl_sizeiptr>(m * 64), w.data());
      gl_.BindBuffer(kGlShaderStorageBuffer, buffers_[1]);
      gl_.GetBufferSubData(kGlShaderStorageBuffer, 0, static_cast<gl_sizeiptr>(m * 16), d.data());
      for (std::size_t k = 0; k < m; ++k) {
        npr_gabor_gpu_record r;
        std::memcpy(&r, &w[16 * k], sizeof r);
        if (r.box[0] > r.box[2] || r.box[1] > r.box[3]) {
          ++empty;
          continue;
        }
        words.insert(words.end(), w.begin() + static_cast<std::ptrdiff_t>(16 * k),
                     w.begin() + static_cast<std::ptrdiff_t>(16 * k + 16));
        ids.insert(ids.end(), d.begin() + static_cast<std::ptrdiff_t>(4 * k),
                   d.begin() + static_cast<std::ptrdiff_t>(4 * k + 4));
      }
    }
    gl_.check("hush::glsl::npr_gabor: reading stage 1's records");
    return true;
  }

 private:
  // Records per batch: one storage block.
  std::size_t batch_records() const {
    return std::max<std::size_t>(1, dev_.max_buffer_bytes() / kNprGaborRecordBytes);
  }

  // Stage 2: the records [0, total) of the frame in batches; fill(b0, m) puts records
  // b0 ... b0 + m - 1 into buffers_[0] (and their ids into buffers_[1]).
  template <class Fill>
  void draw(const hush::detail::npr_gabor_splat_job& j, const image_view<float>& out,
            std::size_t total, Fill fill) {
    namespace c = hush::detail::constants;
    const std::size_t w = out.width, h = out.height;
    if (w > static_cast<std::size_t>(limits_.max_frame_side) ||
        h > static_cast<std::size_t>(limits_.max_frame_side))
      hush::detail::throw_out_of_range(
          "hush::glsl::npr_gabor", "frame size", std::to_string(w) + "x" + std::to_string(h),
          ("sides up to " + std::to_string(limits_.max_frame_side) +
           " (GL_MAX_TEXTURE_SIZE, GL_MAX_VIEWPORT_DIMS, GL_MAX_RENDERBUFFER_SIZE)")
              .c_str());
    // The G-buffer views the tests read.
    frame f;
    f.depth = j.depth;
    f.object_id = j.object_id;
    f.triangle_id = j.triangle_id;
    frame_view which = frame_view::none;
    if (j.depth_test) which = which | frame_view::depth;
    if (j.object_test) which = which | frame_view::object_id;
    if (j.triangle_test) which = which | frame_view::triangle_id;
    if (which != frame_view::none) frame_.upload(f, which);
    const state_guard guard(gl_, gr_);
    target(w, h);
    gl_.UseProgram(program_.id());
    const gl_uint prog = program_.id();
    gl_.Uniform2ui(gl_.GetUniformLocation(prog, "hush_size"), static_cast<gl_uint>(w),
                   static_cast<gl_uint>(h));
    gl_.Uniform1ui(gl_.GetUniformLocation(prog, "hush_flags"),
                   (j.object_test ? 1u : 0u) | (j.triangle_test ? 2u : 0u) |
                       (j.depth_test ? 4u : 0u) | (j.soft_depth ? 8u : 0u));
    gl_.Uniform1f(gl_.GetUniformLocation(prog, "hush_tolerance"),
                  static_cast<float>(j.depth_tolerance));
    gl_.Uniform1f(gl_.GetUniformLocation(prog, "hush_neg_a"),
                  static_cast<float>(-j.envelope_exponent));
    gl_.Uniform1f(gl_.GetUniformLocation(prog, "hush_taper_k"),
                  static_cast<float>(1.0 / (1.0 - c::kGaborTaperStart)));
    // Unused views: any valid buffer (never read).
    const frame_view any = j.depth_test    ? frame_view::depth
                           : j.object_test ? frame_view::object_id
                                           : frame_view::triangle_id;
    // Records in batches of one storage block, drawn in order.
    const std::size_t batch = batch_records();
    for (std::size_t b0 = 0; b0 < total; b0 += batch) {
      const std::size_t m = std::min(batch, total - b0);
      fill(b0, m);
      gl_.UseProgram(program_.id());
      gl_.BindBufferBase(kGlShaderStorageBuffer, 0, buffers_[0]);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 4, buffers_[1]);
      if (which == frame_view::none) {  // no test: bind the records' buffer (never read)
        for (gl_uint b = 1; b <= 3; ++b) gl_.BindBufferBase(kGlShaderStorageBuffer, b, buffers_[0]);
      } else {
        frame_.bind(j.depth_test ? frame_view::depth : any, 1);
        frame_.bind(j.object_test ? frame_view::object_id : any, 2);
        frame_.bind(j.triangle_test ? frame_view::triangle_id : any, 3);
      }
      gr_.DrawArrays(kGlPoints, 0, static_cast<gl_sizei>(m));
      ++draws_;
    }
    // Read back (row y of the texture is image row y).
    pixels_.resize(w * h);
    gl_.PixelStorei(kGlPackAlignment, 4);
    gr_.ReadPixels(0, 0, static_cast<gl_sizei>(w), static_cast<gl_sizei>(h), kGlRed, kGlFloat,
                   pixels_.data());
    gl_.check("hush::glsl::npr_gabor: splatting");
    for (std::size_t y = 0; y < h; ++y)
      std::copy(pixels_.begin() + static_cast<std::ptrdiff_t>(y * w),
                pixels_.begin() + static_cast<std::ptrdiff_t>((y + 1) * w), out.row(y));
  }

 private:
  // Saves and restores the state the pass changes.
  class state_guard {
   public:
    state_guard(const gl_api& gl, const gl_raster_api& gr) : gl_(gl), gr_(gr) {
      gl.GetIntegerv(kGlCurrentProgram, &program_);
      gl.GetIntegerv(kGlVertexArrayBinding, &vao_);
      gl.GetIntegerv(kGlDrawFramebufferBinding, &draw_);
      gl.GetIntegerv(kGlReadFramebufferBinding, &read_);
      gl.GetIntegerv(kGlViewport, viewport_);
      gl.GetIntegerv(kGlShaderStorageBufferBinding, &buffer_);
      gl.GetIntegerv(kGlTextureBinding2d, &texture_);
      gl.GetIntegerv(kGlPackAlignment, &pack_);
      for (int i = 0; i < 4; ++i) gl.GetIntegerv(kBlendQueries[i], &blend_[i]);
      gl.GetIntegerv(kGlBlendEquationRgb, &equation_[0]);
      gl.GetIntegerv(kGlBlendEquationAlpha, &equation_[1]);
      for (int i = 0; i < 5; ++i) enabled_[i] = gr.IsEnabled(kCaps[i]) != 0;
    }
    state_guard(const state_guard&) = delete;
    state_guard& operator=(const state_guard&) = delete;
    ~state_guard() {
      gl_.UseProgram(static_cast<gl_uint>(program_));
      gr_.BindVertexArray(static_cast<gl_uint>(vao_));
      gr_.BindFramebuffer(kGlDrawFramebuffer, static_cast<gl_uint>(draw_));
      gr_.BindFramebuffer(kGlReadFramebuffer, static_cast<gl_uint>(read_));
      gr_.Viewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
      gl_.BindBuffer(kGlShaderStorageBuffer, static_cast<gl_uint>(buffer_));
      gl_.BindTexture(kGlTexture2d, static_cast<gl_uint>(texture_));
      gl_.PixelStorei(kGlPackAlignment, pack_);
      gr_.BlendFuncSeparate(static_cast<gl_enum>(blend_[0]), static_cast<gl_enum>(blend_[1]),
                            static_cast<gl_enum>(blend_[2]), static_cast<gl_enum>(blend_[3]));
      gr_.BlendEquationSeparate(static_cast<gl_enum>(equation_[0]),
                                static_cast<gl_enum>(equation_[1]));
      for (int i = 0; i < 5; ++i) (enabled_[i] ? gr_.Enable : gr_.Disable)(kCaps[i]);
    }

   private:
    static constexpr gl_enum kBlendQueries[4] = {kGlBlendSrcRgb, kGlBlendDstRgb, kGlBlendSrcAlpha,
                                                 kGlBlendDstAlpha};
    static constexpr gl_enum kCaps[5] = {kGlBlend, kGlDepthTest, kGlStencilTest, kGlScissorTest,
                                         kGlCullFace};
    const gl_api& gl_;
    const gl_raster_api& gr_;
    gl_int program_ = 0, vao_ = 0, draw_ = 0, read_ = 0, buffer_ = 0, texture_ = 0, pack_ = 4;
    gl_int viewport_[4] = {0, 0, 0, 0}, blend_[4] = {1, 0, 1, 0}, equation_[2] = {0, 0};
    bool enabled_[5] = {false, false, false, false, false};
  };

  // The R32F target, sized w x h and cleared to 0; blending set to a plain sum.
  void target(std::size_t w, std::size_t h) {
    gl_.BindTexture(kGlTexture2d, texture_);
    if (w != width_ || h != height_) {
      gl_.TexImage2D(kGlTexture2d, 0, static_cast<gl_int>(kGlR32f), static_cast<gl_sizei>(w),
                     static_cast<gl_sizei>(h), 0, kGlRed, kGlFloat, nullptr);
      for (const gl_enum p : {kGlTextureMinFilter, kGlTextureMagFilter})
        gl_.TexParameteri(kGlTexture2d, p, static_cast<gl_int>(kGlNearest));
      width_ = w;
      height_ = h;
    }
    gr_.BindFramebuffer(kGlFramebuffer, fbo_);
    gr_.FramebufferTexture2D(kGlFramebuffer, kGlColorAttachment0, kGlTexture2d, texture_, 0);
    if (gr_.CheckFramebufferStatus(kGlFramebuffer) != kGlFramebufferComplete)
      throw std::runtime_error(
          "hush::glsl::npr_gabor: the GL_R32F framebuffer is incomplete on this context");
    gr_.Viewport(0, 0, static_cast<gl_sizei>(w), static_cast<gl_sizei>(h));
    for (const gl_enum cap : {kGlDepthTest, kGlStencilTest, kGlScissorTest, kGlCullFace})
      gr_.Disable(cap);
    gr_.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    gr_.Clear(kGlColorBufferBit);
    gr_.Enable(kGlBlend);
    gr_.BlendFuncSeparate(kGlOne, kGlOne, kGlOne, kGlOne);
    gr_.BlendEquationSeparate(kGlFuncAdd, kGlFuncAdd);
    gr_.BindVertexArray(vao_);
  }

  // Records [0, m) of `s` into the two record buffers, bound at 0 and 4: offsets relative to
  // the first pixel, formed in double and rounded once.
  void pack(const npr_gabor_splat* s, std::size_t m) {
    words_.resize(m * 16);
    ids_.resize(m * 4);
    for (std::size_t i = 0; i < m; ++i) {
      const npr_gabor_gpu_record g = npr_gabor_gpu_record::of(s[i]);
      std::memcpy(words_.data() + 16 * i, &g, sizeof g);
      ids_[4 * i] = s[i].object;
      ids_[4 * i + 1] = s[i].triangle;
      ids_[4 * i + 2] = static_cast<std::uint32_t>(s[i].index);
      ids_[4 * i + 3] = static_cast<std::uint32_t>(s[i].index >> 32);
    }
    gl_.BindBuffer(kGlShaderStorageBuffer, buffers_[0]);
    gl_.BufferData(kGlShaderStorageBuffer, static_cast<gl_sizeiptr>(words_.size() * 4),
                   words_.data(), kGlStreamDraw);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 0, buffers_[0]);
    gl_.BindBuffer(kGlShaderStorageBuffer, buffers_[1]);
    gl_.BufferData(kGlShaderStorageBuffer, static_cast<gl_sizeiptr>(ids_.size() * 4), ids_.data(),
                   kGlStreamDraw);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 4, buffers_[1]);
  }

  void set(gl_uint prog, const char* name, gl_uint v) const {
    gl_.Uniform1ui(gl_.GetUniformLocation(prog, name), v);
  }
  // Runs `prog` over `items` invocations in groups of `group`, at most 65535 groups (GL 4.3's
  // minimum GL_MAX_COMPUTE_WORK_GROUP_COUNT) per dispatch; hush_group_base says where a
  // dispatch starts.
  void dispatch(gl_uint prog, std::size_t items, std::size_t group) const {
    constexpr std::size_t kMaxGroups = 65535;
    const std::size_t groups = (items + group - 1) / group;
    for (std::size_t g0 = 0; g0 < groups; g0 += kMaxGroups) {
      set(prog, "hush_group_base", static_cast<gl_uint>(g0));
      gl_.DispatchCompute(static_cast<gl_uint>(std::min(kMaxGroups, groups - g0)), 1, 1);
    }
  }
  void upload(int which, const void* data, std::size_t bytes, gl_uint binding) const {
    gl_.BindBuffer(kGlShaderStorageBuffer, stage1_buffers_[which]);
    gl_.BufferData(kGlShaderStorageBuffer,
                   static_cast<gl_sizeiptr>(std::max<std::size_t>(bytes, 4)), data, kGlStreamDraw);
    gl_.BindBufferBase(kGlShaderStorageBuffer, binding, stage1_buffers_[which]);
  }
  void bind_stage1() const {
    for (int b = 0; b < kStage1Buffers; ++b)
      gl_.BindBufferBase(kGlShaderStorageBuffer, static_cast<gl_uint>(b), stage1_buffers_[b]);
  }
  // Buffer i of `v`, made on first use.
  gl_uint buffer_at(std::vector<gl_uint>& v, std::size_t i) const {
    while (v.size() <= i) {
      gl_uint b = 0;
      gl_.GenBuffers(1, &b);
      v.push_back(b);
    }
    return v[i];
  }
  void allocate(gl_uint buffer, std::size_t bytes) const {
    gl_.BindBuffer(kGlShaderStorageBuffer, buffer);
    gl_.BufferData(kGlShaderStorageBuffer,
                   static_cast<gl_sizeiptr>(std::max<std::size_t>(bytes, 16)), nullptr,
                   kGlStreamDraw);
  }
  void run(int pass, std::size_t items, std::size_t group) const {
    dispatch(stage1_[pass].id(), items, group);
    gl_.MemoryBarrier(kGlShaderStorageBarrierBit | kGlBufferUpdateBarrierBit);
  }

  // The exclusive prefix sum of the n uvec2 items of `data`, in place; `total` gets their sum
  // (8 bytes read back). Blocks of kNprGaborScanBlock items per work group, then the blocks'
  // totals scanned the same way (recursively: depth d holds n / 1024^d totals) and added back.
  void scan(gl_uint data, std::size_t n, std::size_t depth, std::uint32_t total[2]) {
    total[0] = total[1] = 0;
    if (n == 0) return;
    const gl_uint prog = stage1_[kScanPass].id();
    const std::size_t groups = (n + kNprGaborScanBlock - 1) / kNprGaborScanBlock;
    const gl_uint sums = buffer_at(scan_sums_, depth);
    allocate(sums, groups * 8);
    const auto pass = [&](gl_uint add) {
      gl_.UseProgram(prog);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 0, data);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 1, sums);
      set(prog, "hush_items", static_cast<gl_uint>(n));
      set(prog, "hush_add", add);
      run(kScanPass, groups * kNprGaborScanSize, kNprGaborScanSize);
    };
    pass(0);
    if (groups > 1) {
      scan(sums, groups, depth + 1, total);
      pass(1);
    } else {
      gl_.BindBuffer(kGlShaderStorageBuffer, sums);
      gl_.GetBufferSubData(kGlShaderStorageBuffer, 0, 8, total);
    }
  }

  // Stage 1 up to the records: uploads the triangles and the per-object kernels, computes each
  // triangle's LOD, its root node, then walks the point sequence level by level (expand, scan,
  // children) keeping every level's nodes and scanned offsets for generate(); `total` the
  // number of records. False where the GPU cannot run stage 1 (see render).
  bool stage1(const npr_gabor& noise, const frame& f, const triangle_list& tris,
              const npr_gabor::sources& src, std::size_t& total) {
    // Per-pixel or per-vertex sources run on the CPU.
    if (!npr_gabor::per_object_at_most(src)) return false;
    const std::size_t nt = tris.triangles(), nv = tris.vertices();
    std::size_t objects = 0;  // table entries before the constants' one
    for (const param_source* p : {&src.frequency, &src.orientation, &src.bandwidth, &src.impulses})
      objects = std::max(objects, p->table_size());
    const std::size_t most = dev_.max_buffer_bytes();
    if (nt * kNprGaborLodBytes > most || nv * 16 > most || nt * 20 > most || (objects + 1) * 32 > most ||
        nt * kNprGaborNodeBytes > most || nt > 0xFFFFFFFFu)
      return false;
    const state_guard guard(gl_, gr_);
    // Vertices (x, y, depth, -), triangles (3 indices, id, object), the kernel table.
    floats_.assign(std::max<std::size_t>(nv, 1) * 4, 0.0f);
    for (std::size_t v = 0; v < nv; ++v) {
      floats_[4 * v] = tris.screen[v].x;
      floats_[4 * v + 1] = tris.screen[v].y;
      floats_[4 * v + 2] = tris.depth[v];
    }
    upload(0, floats_.data(), nv * 16, 0);
    words_.assign(std::max<std::size_t>(nt, 1) * 5, 0u);
    for (std::size_t t = 0; t < nt; ++t) {
      for (std::size_t i = 0; i < 3; ++i) words_[5 * t + i] = tris.indices[3 * t + i];
      words_[5 * t + 3] = tris.triangle_id[t];
      words_[5 * t + 4] = tris.object_of(t);
    }
    upload(1, words_.data(), nt * 20, 1);
    floats_.assign((objects + 1) * 8, 0.0f);
    for (std::size_t o = 0; o <= objects; ++o) {
      const npr_gabor::object_kernel k = noise.kernel_of_object(static_cast<std::uint32_t>(o), src);
      const double e[8] = {k.F.x * k.radius,
                           k.F.y * k.radius,
                           std::hypot(k.F.x, k.F.y) * k.radius,
                           1.0 / k.radius,
                           k.radius,
                           k.density,
                           k.scale,
                           0.0};
      for (int i = 0; i < 8; ++i)
        floats_[8 * o + static_cast<std::size_t>(i)] = static_cast<float>(e[i]);
    }
    upload(2, floats_.data(), floats_.size() * 4, 2);
    upload(3, nullptr, nt * kNprGaborLodBytes, 3);
    upload(4, nullptr, nt * 8, 4);
    const npr_gabor::params& p = noise.parameters();
    for (int pass = 0; pass < kNprGaborStage1Passes; ++pass) {
      const gl_uint prog = stage1_[pass].id();
      gl_.UseProgram(prog);
      set(prog, "hush_tris", static_cast<gl_uint>(nt));
      set(prog, "hush_table_last", static_cast<gl_uint>(objects));
      gl_.Uniform2ui(gl_.GetUniformLocation(prog, "hush_size"), static_cast<gl_uint>(f.width()),
                     static_cast<gl_uint>(f.height()));
      set(prog, "hush_key", seed_key(p.seed));
      set(prog, "hush_opts", (p.cull_back_faces ? 1u : 0u) | (p.thinning ? 2u : 0u));
      set(prog, "hush_isotropic", p.isotropic ? 1u : 0u);
      set(prog, "hush_local", p.local_density ? 1u : 0u);
    }
    level_nodes_count_.clear();
    level_first_.clear();
    level_records_.clear();
    nodes_ = 0;
    levels_ = 0;
    total = 0;
    if (nt == 0) return true;
    // Level 0: the LOD of every triangle, the roots at their scanned offsets.
    gl_.UseProgram(stage1_[kLodsPass].id());
    run(kLodsPass, nt, kNprGaborGroupSize);
    std::uint32_t sum[2];
    scan(stage1_buffers_[4], nt, 0, sum);
    std::size_t n = sum[1];
    gl_.UseProgram(stage1_[kRootsPass].id());
    bind_stage1();
    allocate(buffer_at(level_nodes_, 0), n * kNprGaborNodeBytes);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 6, level_nodes_[0]);
    run(kRootsPass, nt, kNprGaborGroupSize);
    // Level k -> k + 1: each node's record flag and kept children, scanned; the children at
    // their offsets. The count below 2^41 bounds the depth: (4^k - 1) / 3 <= J < 2^41, k <= 21
    // (local density: level 21, npr_gabor::max_depth(), keeps no children).
    std::size_t records = 0;
    for (std::size_t k = 0; n > 0; ++k) {
      if (k > kMaxLevels || n * 8 > most) return false;
      const gl_uint nodes = level_nodes_[k], flags = buffer_at(level_flags_, k);
      allocate(flags, n * 8);
      for (const int pass : {kExpandPass, kChildrenPass, kRecordsPass}) {
        gl_.UseProgram(stage1_[pass].id());
        set(stage1_[pass].id(), "hush_nodes", static_cast<gl_uint>(n));
        set(stage1_[pass].id(), "hush_level", static_cast<gl_uint>(k));
      }
      gl_.UseProgram(stage1_[kExpandPass].id());
      bind_stage1();
      gl_.BindBufferBase(kGlShaderStorageBuffer, 4, flags);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 5, nodes);
      run(kExpandPass, n, kNprGaborGroupSize);
      scan(flags, n, 0, sum);
      level_nodes_count_.push_back(n);
      level_first_.push_back(records);
      level_records_.push_back(sum[0]);
      records += sum[0];
      nodes_ += n;
      n = sum[1];
      if (n == 0) break;
      if (n * kNprGaborNodeBytes > most || n > 0xFFFFFFFFu) return false;
      allocate(buffer_at(level_nodes_, k + 1), n * kNprGaborNodeBytes);
      gl_.UseProgram(stage1_[kChildrenPass].id());
      gl_.BindBufferBase(kGlShaderStorageBuffer, 4, flags);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 5, nodes);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 6, level_nodes_[k + 1]);
      run(kChildrenPass, level_nodes_count_.back(), kNprGaborGroupSize);
    }
    gl_.check("hush::glsl::npr_gabor: stage 1 (the walk)");
    levels_ = level_nodes_count_.size();
    if (records > 0xFFFFFFFFu) return false;
    total = records;
    return true;
  }

  // Stage 1's last pass for records b0 ... b0 + m - 1 (the frame's records level by level):
  // into buffers_[0] and buffers_[1], from every level whose records meet the batch.
  void generate(std::size_t b0, std::size_t m) {
    gl_.MemoryBarrier(kGlShaderStorageBarrierBit);  // the last draw's reads come first
    const gl_uint prog = stage1_[kRecordsPass].id();
    gl_.UseProgram(prog);
    bind_stage1();
    gl_.BindBuffer(kGlShaderStorageBuffer, buffers_[0]);
    gl_.BufferData(kGlShaderStorageBuffer, static_cast<gl_sizeiptr>(m * 64), nullptr,
                   kGlStreamDraw);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 6, buffers_[0]);
    gl_.BindBuffer(kGlShaderStorageBuffer, buffers_[1]);
    gl_.BufferData(kGlShaderStorageBuffer, static_cast<gl_sizeiptr>(m * 16), nullptr,
                   kGlStreamDraw);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 7, buffers_[1]);
    set(prog, "hush_base", static_cast<gl_uint>(b0));
    set(prog, "hush_batch", static_cast<gl_uint>(m));
    for (std::size_t k = 0; k < level_nodes_count_.size(); ++k) {
      if (level_first_[k] + level_records_[k] <= b0 || level_first_[k] >= b0 + m) continue;
      set(prog, "hush_nodes", static_cast<gl_uint>(level_nodes_count_[k]));
      set(prog, "hush_first", static_cast<gl_uint>(level_first_[k]));
      gl_.BindBufferBase(kGlShaderStorageBuffer, 4, level_flags_[k]);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 5, level_nodes_[k]);
      dispatch(prog, level_nodes_count_[k], kNprGaborGroupSize);
    }
    gl_.MemoryBarrier(kGlShaderStorageBarrierBit);
    gl_.check("hush::glsl::npr_gabor: stage 1 (records)");
  }

  // Stage 1's buffers: vertices, triangles, kernel table, LOD per triangle, the triangles'
  // scan (roots).
  static constexpr int kStage1Buffers = 5;
  // The passes (npr_gabor_stage1_source).
  static constexpr int kLodsPass = 0, kScanPass = 1, kRootsPass = 2, kExpandPass = 3,
                       kChildrenPass = 4, kRecordsPass = 5;
  // Deeper than any J below 2^41 reaches (21): a guard, never taken.
  static constexpr std::size_t kMaxLevels = 24;

  glsl::device& dev_;
  const gl_api& gl_;
  gl_raster_api gr_;
  frame_upload frame_;
  npr_gabor_limits limits_;
  gl_program program_;
  gl_program stage1_[kNprGaborStage1Passes];
  gl_uint buffers_[2] = {0, 0};  // records, ids
  gl_uint stage1_buffers_[kStage1Buffers] = {0, 0, 0, 0, 0};
  // Per level of the walk: its nodes, its scanned (records, children) offsets; per depth of
  // the scan's recursion: the blocks' totals.
  std::vector<gl_uint> level_nodes_, level_flags_;
  mutable std::vector<gl_uint> scan_sums_;
  std::vector<std::size_t> level_nodes_count_, level_first_, level_records_;
  std::uint64_t nodes_ = 0;
  std::size_t levels_ = 0;
  std::size_t gpu_frames_ = 0, cpu_frames_ = 0;
  std::vector<float> floats_;
  gl_uint texture_ = 0, fbo_ = 0, vao_ = 0;
  std::size_t width_ = 0, height_ = 0, draws_ = 0;
  std::vector<std::uint32_t> words_, ids_;
  std::vector<float> pixels_;
};

}  // namespace detail

// The device's NPR Gabor splatting state (made on first use, kept with the device).
inline detail::npr_gabor_gpu& npr_gabor_state(device& dev) {
  return dev.extension<detail::npr_gabor_gpu>(
      "npr_gabor", [&] { return std::make_shared<detail::npr_gabor_gpu>(dev); });
}

// Stage 2 of NPR Gabor noise on `dev` (what hush::npr_gabor::splat and ::render call for
// exec::glsl, found by argument-dependent lookup): out (frame-sized, checked by the caller)
// receives the job's records' kernels, within the tolerance above of exec::scalar's.
inline void npr_gabor_glsl_splat(device& dev, const hush::detail::npr_gabor_splat_job& j,
                                 const image_view<float>& out) {
  npr_gabor_state(dev).splat(j, out);
}

// Both stages of NPR Gabor noise on `dev` (what hush::npr_gabor::render calls for exec::glsl;
// arguments validated by render): stage 1 by the compute passes above where every source is
// constant or per object, else on the CPU (make_splats), then stage 2.
inline void npr_gabor_glsl_render(device& dev, const npr_gabor& noise, const frame& f,
                                  const triangle_list& tris, const npr_gabor::sources& src,
                                  const image_view<float>& out) {
  npr_gabor_state(dev).render(noise, f, tris, src, out);
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_NPR_GABOR_HPP

// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// NPR Gabor noise (include/hush/npr_gabor.hpp) on the GPU, the paper's way (Benard et al.
// 2010, sec. 3.4 and 5): stage 2, the splatting, as point sprites. Include this header to use
// hush::exec::glsl{device} with hush::npr_gabor::render and ::splat:
//
//   hush::glsl::headless_device gpu;                // or a device on the application's context
//   noise.render(hush::exec::glsl{gpu.device}, frame, triangles, out);
//
// What runs where: stage 1 (make_splats: the points of every triangle, their LOD weights,
// parameters and planes) stays on the CPU, in double, exactly as for exec::scalar; the records
// go to shader storage buffers (64 + 8 bytes each) and are drawn as GL_POINTS, one vertex per
// record, in record order. A geometry shader turns each into one screen-aligned quad covering
// the record's pixel range x0 ... x1 + 1, y0 ... y1 + 1 (its kernel's disc, clamped to the
// image), a fragment shader runs the visibility tests against the G-buffer (object id,
// triangle id, depth with its tolerance, soft depth; SSBOs uploaded by frame_upload.hpp) and
// evaluates the tapered Gabor kernel with the library's float functions (the CPU's float
// operations, hush/glsl/gabor_glsl.hpp), and additive blending (GL_ONE, GL_ONE) sums the
// fragments into a GL_R32F framebuffer texture, read back into `out`. The normalisation is the
// CPU's: the weights in the records.
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
// 0 (fails) on GPUs that flush denormals, where the CPU passes it to the plane comparison.
//
// Throws std::runtime_error for GL errors (and when the context lacks storage blocks in the
// geometry or fragment stage: GL 4.3 requires them only in compute shaders; every desktop
// driver has them). Leaves the current program, vertex array, framebuffers, viewport, blend and
// the enables it touches (blend, depth, stencil, scissor, cull face) as it found them; rebinds
// the indexed storage-buffer bindings 0 to 4 (as hush::glsl::device does).
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
#include "hush/detail/npr_gabor_splat.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/device.hpp"
#include "hush/glsl/frame_upload.hpp"
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
constexpr const char* kNprGaborRecords = R"glsl(
struct hush_npr_splat {
  ivec4 box;
  vec4 kern;
  vec4 freq;
  vec4 plane;
};
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
layout(std430, binding = 4) readonly buffer hush_npr_ids_b { uvec2 hush_npr_ids[]; };
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
  uvec2 ids = hush_npr_ids[hush_g_splat];
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

}  // namespace detail

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
         std::to_string(kNprGaborSpriteVertices) + "\n" + detail::kNprGaborRecords +
         detail::kNprGaborGeometry;
}
inline std::string npr_gabor_fragment_source() {
  return std::string("#version 430 core\n// hush " HUSH_VERSION_STRING
                     " NPR Gabor splats: fragment stage, tests and kernel.\n") +
         library() + detail::kNprGaborRecords + detail::kNprGaborFragment;
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
    gl_.GenBuffers(2, buffers_);
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
    gl_.DeleteBuffers(2, buffers_);
  }

  const npr_gabor_limits& limits() const { return limits_; }
  std::size_t draws() const { return draws_; }

  // Stage 2 of `j` into out (frame-sized, validated by npr_gabor::splat).
  void splat(const hush::detail::npr_gabor_splat_job& j, const image_view<float>& out) {
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
    frame_.bind(j.depth_test ? frame_view::depth : any, 1);
    frame_.bind(j.object_test ? frame_view::object_id : any, 2);
    frame_.bind(j.triangle_test ? frame_view::triangle_id : any, 3);
    if (which == frame_view::none) {  // no test: bind the records' buffer (never read)
      for (gl_uint b = 1; b <= 3; ++b) gl_.BindBufferBase(kGlShaderStorageBuffer, b, buffers_[0]);
    }
    // Records in batches of one storage block, drawn in order.
    const std::size_t batch =
        std::max<std::size_t>(1, dev_.max_buffer_bytes() / kNprGaborRecordBytes);
    for (std::size_t b0 = 0; b0 < j.count; b0 += batch) {
      const std::size_t m = std::min(batch, j.count - b0);
      pack(j.splats + b0, m);
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
    ids_.resize(m * 2);
    for (std::size_t i = 0; i < m; ++i) {
      const npr_gabor_splat& r = s[i];
      std::uint32_t* o = words_.data() + 16 * i;
      const std::int32_t box[4] = {r.x0, r.y0, r.x1, r.y1};
      std::memcpy(o, box, sizeof box);
      const double fx0 = static_cast<double>(r.x0) + 0.5, fy0 = static_cast<double>(r.y0) + 0.5;
      const float f[12] = {static_cast<float>(fx0 - r.x),
                           static_cast<float>(fy0 - r.y),
                           static_cast<float>(1.0 / r.radius),
                           static_cast<float>(r.weight),
                           static_cast<float>(r.fx * r.radius),
                           static_cast<float>(r.fy * r.radius),
                           0.0f,
                           0.0f,
                           static_cast<float>(r.q0 + r.qx * fx0 + r.qy * fy0),
                           static_cast<float>(r.qx),
                           static_cast<float>(r.qy),
                           0.0f};
      std::memcpy(o + 4, f, sizeof f);
      ids_[2 * i] = r.object;
      ids_[2 * i + 1] = r.triangle;
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

  glsl::device& dev_;
  const gl_api& gl_;
  gl_raster_api gr_;
  frame_upload frame_;
  npr_gabor_limits limits_;
  gl_program program_;
  gl_uint buffers_[2] = {0, 0};  // records, ids
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

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_NPR_GABOR_HPP

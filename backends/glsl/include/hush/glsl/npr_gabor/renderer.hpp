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
// clipped part's projection, meeting the frame), a multi-level prefix sum gives every record and
// child its offset, a second pass writes the children as the next level's list. Here (exec::glsl)
// the host reads back each level's two totals (8 bytes) to size the next level; nothing is dropped
// (a level beyond one storage block runs stage 1 on the CPU instead). The resident path
// (npr_gabor_gl_render, frame.hpp) reads nothing back: after each prefix sum a one-invocation plan
// pass (kNprGaborPlan) writes the next level's count, its indirect dispatch commands and the draws'
// counts into a plan buffer, the passes read the counts from it (the level's slot as a uniform
// block) and run from glDispatchComputeIndirect / glDrawArraysIndirect, over buffers of capacities
// the renderer keeps (set by its first frame, which reads the totals back as here; a level beyond
// its capacity keeps the nodes that fit and is flagged in status words the host reads once the GPU
// has finished that frame, after which the next frame sets the capacities again). Then one pass per
// level writes the records at their scanned offsets, batch by batch: level by level, each in its
// list's order, the same order every run (no atomics), hence the same image. J (up to 2^41) is a
// uvec2; node corners are carried down as perspective-correct midpoints in float (homogeneous:
// plain midpoints). Per-pixel or per-vertex sources, buffers beyond one storage block, or more than
// 2^32 - 1 records: stage 1 on the CPU (make_splats), automatically. Float instead of double
// changes positions, weights and planes within the tolerance derived in
// tests/gabor/glsl_gabor_test.cpp (npr_tolerance_of); where float and double N straddle a power of
// two the second M points (weight <= sqrt(2 nu), nu N's relative float error) exist on one side
// only; with params::local_density, likewise a node whose float and double counts straddle a cut of
// the hat (1/4, 4): its record (weight <= sqrt((1 + 1/ln 4) nu_P n + n 2^-21), nu_P its count's
// relative error) exists on one side only; near the near plane also a node with a corner within its
// float depth error of w_near (crossing, weight 0, on one side). The homogeneous corners' float
// error: docs/npr-gabor.md "Triangles crossing the near plane", GPU.
//
// Stage 2: the records (made on the GPU or uploaded from the CPU's stage 1; shader storage
// buffers, 64 + 16 bytes each) are drawn as GL_POINTS, one vertex per record, in record order. A
// geometry shader turns each into one screen-aligned quad covering the record's pixel range x0 ...
// x1 + 1, y0 ... y1 + 1 (its kernel's disc, clamped to the image), a fragment shader runs the
// visibility tests against the G-buffer (object id, triangle id, depth with its tolerance, soft
// depth; R32F / R32UI textures read with texelFetch, uploaded from the frame's views) and
// evaluates the tapered Gabor kernel with the library's float functions (the CPU's float
// operations, hush/glsl/gabor/program.hpp), and additive blending (GL_ONE, GL_ONE) sums the
// fragments into a GL_R32F framebuffer texture, read back into `out`. The normalisation is the
// CPU's: the weights in the records. hush/glsl/npr_gabor/frame.hpp runs the same stages on the
// caller's own textures and buffers into the caller's texture (no image read-back).
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
// Agreement with the CPU (tests/gabor/glsl_gabor_test.cpp, "npr"): GL blends the fragments of
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
// the enables it touches (blend, depth, stencil, scissor, cull face), the active texture unit and
// the generic GL_SHADER_STORAGE_BUFFER, GL_DISPATCH_INDIRECT_BUFFER, GL_DRAW_INDIRECT_BUFFER,
// GL_UNIFORM_BUFFER, GL_COPY_READ_BUFFER and GL_COPY_WRITE_BUFFER bindings as it found them;
// rebinds the indexed storage-buffer bindings 0 to 7 (as hush::glsl::device does), the indexed
// uniform-buffer binding 0 (the plan's level slot) and the textures of units 0 - 2 (but the
// active unit's, restored; a sampler object of the renderer's is bound to units 0 - 2 during
// the draws only).
#ifndef HUSH_GLSL_NPR_GABOR_RENDERER_HPP
#define HUSH_GLSL_NPR_GABOR_RENDERER_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "hush/core/error.hpp"
#include "hush/detail/constants.hpp"
#include "hush/npr_gabor/splat.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/device.hpp"
#include "hush/glsl/detail/gl_resident.hpp"
#include "hush/glsl/npr_gabor/gl_frame.hpp"
#include "hush/glsl/npr_gabor/gl_raster.hpp"
#include "hush/glsl/npr_gabor/glsl.hpp"
#include "hush/npr_gabor.hpp"

namespace hush {
namespace glsl {

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
      : dev_(dev), gl_(dev.gl()), gr_(dev.gl().loader), rs_(dev.gl().loader) {
    limits_ = npr_gabor_gl_limits(gl_);
    if (!limits_.sprites_fit() || limits_.max_geometry_storage_blocks < 1 ||
        limits_.max_fragment_storage_blocks < 2)
      hush::detail::raise_error<std::runtime_error>(
          "hush::glsl::npr_gabor: the context lacks what the splatting needs (a quad of 4 "
          "vertices from the geometry stage, 1 storage block there and 2 in the fragment stage)");
    program_ = link_program(gl_, {{kGlVertexShader, npr_gabor_vertex_source()},
                                  {kGlGeometryShader, npr_gabor_geometry_source()},
                                  {kGlFragmentShader, npr_gabor_fragment_source()}});
    for (int i = 0; i < kNprGaborStage1Passes; ++i)
      stage1_[i] = link_program(gl_, {{kGlComputeShader, npr_gabor_stage1_source(i)}});
    plan_program_ =
        link_program(gl_, {{kGlComputeShader, npr_gabor_plan_source()}});
    // The plan: slot 0 (status), the levels' slots, the draws; zeroed once (the sync walk binds
    // a slot too, its uniform block unread there).
    gl_int align = 256;
    gl_.GetIntegerv(kGlUniformBufferOffsetAlignment, &align);
    const std::size_t a = static_cast<std::size_t>(std::max<gl_int>(align, 4));
    slot_words_ = ((256 + a - 1) / a) * a / 4;
    gl_.GenBuffers(1, &plan_);
    const std::vector<std::uint32_t> zeros((kDrawSlot + kDrawSlots) * slot_words_, 0u);
    gl_.BindBuffer(kGlShaderStorageBuffer, plan_);
    gl_.BufferData(kGlShaderStorageBuffer, static_cast<gl_sizeiptr>(zeros.size() * 4), zeros.data(),
                   kGlStreamDraw);
    gl_.GenBuffers(2, resident_records_);
    gl_.GenBuffers(2, buffers_);
    gl_.GenBuffers(kStage1Buffers, stage1_buffers_);
    gl_.GenTextures(1, &texture_);
    gl_.GenTextures(3, gbuffer_);
    sampler_ = rs_.nearest_sampler();
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
    gl_.DeleteTextures(3, gbuffer_);
    rs_.DeleteSamplers(1, &sampler_);
    gl_.DeleteBuffers(kStage1Buffers, stage1_buffers_);
    for (const std::vector<gl_uint>* v : {&level_nodes_, &level_flags_, &scan_sums_})
      if (!v->empty()) gl_.DeleteBuffers(static_cast<gl_sizei>(v->size()), v->data());
    gl_.DeleteBuffers(2, buffers_);
    gl_.DeleteBuffers(2, resident_records_);
    gl_.DeleteBuffers(1, &plan_);
    for (const std::vector<gl_uint>* v : {&res_nodes_, &res_flags_, &res_sums_})
      if (!v->empty()) gl_.DeleteBuffers(static_cast<gl_sizei>(v->size()), v->data());
    for (void*& f : status_fences_)
      if (f) gr_.DeleteSync(f);
    if (status_ != 0u) gl_.DeleteBuffers(1, &status_);
  }

  const npr_gabor_limits& limits() const { return limits_; }
  std::size_t draws() const { return draws_; }
  // Frames whose stage 1 ran on the GPU (render), and those it handed back to the CPU.
  std::size_t gpu_stage1_frames() const { return gpu_frames_; }
  std::size_t cpu_stage1_frames() const { return cpu_frames_; }
  // The last GPU stage 1's walk: nodes visited (every level's list) and levels (a resident
  // frame after the first: 0 nodes, not known to the host, and the levels issued).
  std::uint64_t stage1_nodes() const { return nodes_; }
  std::size_t stage1_levels() const { return levels_; }
  // The resident path (render_resident): whether its capacities are set (the first frame sets
  // them, reading each level's totals back); levels clamped to their capacity that the host
  // has seen so far (asynchronously, a frame or more later); the capacity of level k (nodes).
  bool resident_sized() const { return !caps_.empty(); }
  std::size_t resident_overflows() const { return overflows_seen_; }
  std::size_t resident_capacity(std::size_t k) const { return k < caps_.size() ? caps_[k] : 0; }
  // Reserves `nodes` nodes of capacity at every level (on top of the sizing frame's twice its
  // nodes): a walk none of whose levels needs more never overflows, so a scene that will grow
  // (the camera closing in, denser kernels: more nodes per level and deeper levels) renders
  // every frame exactly. Memory: kNprGaborNodeBytes + 8 bytes per node, at each of the
  // kNprGaborPlanLevels levels. Takes effect at the next resident frame (no read-back); never
  // shrinks a capacity. Throws hush::invalid_argument naming `nodes` beyond one storage block
  // (GL_MAX_SHADER_STORAGE_BLOCK_SIZE / kNprGaborNodeBytes) or one prefix sum's reach.
  void reserve_resident(std::size_t nodes) {
    const std::size_t most =
        std::min(dev_.max_buffer_bytes() / kNprGaborNodeBytes, kMaxGroups * kNprGaborScanBlock);
    if (nodes > most)
      hush::detail::throw_out_of_range(
          "hush::glsl::npr_gabor_state(dev).reserve_resident", "nodes", nodes,
          ("0 ... " + std::to_string(most) + " (one storage block per level)").c_str());
    reserved_ = std::max(reserved_, nodes);
    for (std::size_t& c : caps_) c = std::max(c, reserved_);
  }
  std::size_t resident_reserved() const { return reserved_; }

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

  // Both stages from the caller's GL objects into the caller's R32F texture (hush/glsl/
  // npr_gabor/frame.hpp states the contract; arguments checked there). False (nothing drawn)
  // where stage 1 cannot run on the GPU (stage1_fits, or a level beyond one storage block).
  bool render_resident(const npr_gabor& noise, const npr_gabor_gl_frame& g,
                       const npr_gabor::sources& src, gl_uint output) {
    const std::size_t w = g.width, h = g.height;
    check_frame(w, h);
    if (!stage1_fits(src, g.vertex_count, g.triangle_count)) return false;
    const state_guard guard(gl_, gr_);
    triangle_buffers_[0] = g.vertices;
    triangle_buffers_[1] = g.triangles;
    // The job's tests and kernel constants (its views are not read: the textures are).
    frame f;
    f.depth = image_view<const float>(nullptr, w, h);
    const gl_uint gbuffer[3] = {g.depth, g.object_id, g.triangle_id};
    bool ok = true;
    if (!caps_.empty()) poll_status();
    if (caps_.empty() || resize_) {
      // The first frame, and the first after a frame beyond the capacities was seen: the walk
      // with each level's totals read back, which sets the capacities (twice each level's
      // nodes, at least kMinCapacity and the reserve; never less than before).
      std::size_t total = 0;
      ok = walk(noise, w, h, g.triangle_count, src, total);
      if (ok) {
        caps_.resize(kPlanLevels, std::max(kMinCapacity, reserved_));
        for (std::size_t k = 0; k < level_nodes_count_.size() && k < kPlanLevels; ++k)
          caps_[k] = std::max(caps_[k], 2 * level_nodes_count_[k]);
        resize_ = false;
        make_status();
        draw_into(noise.splat_job(f, nullptr, 0), w, h, gbuffer, output, total,
                  [&](std::size_t b0, std::size_t m) { generate(b0, m); });
      }
    } else {
      ok = walk_resident(noise, w, h, g.triangle_count, src);
      if (ok) {
        draw_into(
            noise.splat_job(f, nullptr, 0), w, h, gbuffer, output,
            g.triangle_count > 0 ? record_capacity() : 0,
            [&](std::size_t b0, std::size_t m) { generate_resident(b0, m); }, true);
        push_status();
      }
    }
    if (ok) ++gpu_frames_;
    triangle_buffers_[0] = stage1_buffers_[0];  // the records pass read the caller's until here
    triangle_buffers_[1] = stage1_buffers_[1];
    if (!ok) return false;
    gr_.FramebufferTexture2D(kGlFramebuffer, kGlColorAttachment0, kGlTexture2d, 0, 0);
    gl_.check("hush::glsl::npr_gabor: splatting");
    return true;
  }

 private:
  // Records per batch: one storage block.
  std::size_t batch_records() const {
    return std::max<std::size_t>(1, dev_.max_buffer_bytes() / kNprGaborRecordBytes);
  }

  // Stage 2: the records [0, total) of the frame in batches; fill(b0, m) puts records
  // b0 ... b0 + m - 1 into buffers_[0] (and their ids into buffers_[1]). The job's G-buffer
  // views go into textures, the frame into the device's R32F target, read back into out.
  template <class Fill>
  void draw(const hush::detail::npr_gabor_splat_job& j, const image_view<float>& out,
            std::size_t total, Fill fill) {
    const std::size_t w = out.width, h = out.height;
    check_frame(w, h);
    // The G-buffer views the tests read (0: not read).
    if (w != gbuffer_width_ || h != gbuffer_height_) {
      allocate_texture(gl_, gbuffer_[0], w, h, kGlR32fFormat, kGlRedChannel, kGlFloat);
      for (int k = 1; k < 3; ++k)
        allocate_texture(gl_, gbuffer_[k], w, h, kGlR32uiFormat, kGlRedInteger, kGlUnsignedInt);
      gbuffer_width_ = w;
      gbuffer_height_ = h;
    }
    if (j.depth_test) upload_view(gl_, rs_, gbuffer_[0], j.depth, kGlRedChannel, kGlFloat);
    if (j.object_test)
      upload_view(gl_, rs_, gbuffer_[1], j.object_id, kGlRedInteger, kGlUnsignedInt);
    if (j.triangle_test)
      upload_view(gl_, rs_, gbuffer_[2], j.triangle_id, kGlRedInteger, kGlUnsignedInt);
    gl_.check("hush::glsl::npr_gabor: uploading the G-buffer");
    const gl_uint g[3] = {gbuffer_[0], gbuffer_[1], gbuffer_[2]};
    const state_guard guard(gl_, gr_);
    gl_.BindTexture(kGlTexture2d, texture_);
    if (w != width_ || h != height_) {
      gl_.TexImage2D(kGlTexture2d, 0, static_cast<gl_int>(kGlR32fFormat), static_cast<gl_sizei>(w),
                     static_cast<gl_sizei>(h), 0, kGlRedChannel, kGlFloat, nullptr);
      for (const gl_enum p : {kGlTextureMinFilter, kGlTextureMagFilter})
        gl_.TexParameteri(kGlTexture2d, p, static_cast<gl_int>(kGlNearestFilter));
      width_ = w;
      height_ = h;
    }
    draw_into(j, w, h, g, texture_, total, fill);
    // Read back (row y of the texture is image row y).
    pixels_.resize(w * h);
    gl_.PixelStorei(kGlPackAlignment, 4);
    gr_.ReadPixels(0, 0, static_cast<gl_sizei>(w), static_cast<gl_sizei>(h), kGlRedChannel, kGlFloat,
                   pixels_.data());
    gl_.check("hush::glsl::npr_gabor: splatting");
    for (std::size_t y = 0; y < h; ++y)
      std::copy(pixels_.begin() + static_cast<std::ptrdiff_t>(y * w),
                pixels_.begin() + static_cast<std::ptrdiff_t>((y + 1) * w), out.row(y));
  }

  // Throws hush::invalid_argument for a frame beyond the GL limits.
  void check_frame(std::size_t w, std::size_t h) const {
    if (w > static_cast<std::size_t>(limits_.max_frame_side) ||
        h > static_cast<std::size_t>(limits_.max_frame_side))
      hush::detail::throw_out_of_range(
          "hush::glsl::npr_gabor", "frame size", std::to_string(w) + "x" + std::to_string(h),
          ("sides up to " + std::to_string(limits_.max_frame_side) +
           " (GL_MAX_TEXTURE_SIZE, GL_MAX_VIEWPORT_DIMS, GL_MAX_RENDERBUFFER_SIZE)")
              .c_str());
  }

  // The splatting proper (the state guarded by the caller): the records in batches into
  // `target` (R32F, w x h, cleared first), the G-buffer read from the textures g (depth, object
  // ids, triangle ids; those of tests the job does not run are not read). Both the CPU-image
  // path (draw) and the resident one (render_resident) splat here.
  // indirect: `total` is the records' capacity, each batch drawn with the plan's count
  // (glDrawArraysIndirect) from resident_records_.
  template <class Fill>
  void draw_into(const hush::detail::npr_gabor_splat_job& j, std::size_t w, std::size_t h,
                 const gl_uint g[3], gl_uint target_texture, std::size_t total, Fill fill,
                 bool indirect = false) {
    namespace c = hush::detail::constants;
    target(target_texture, w, h);
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
    const bool read[3] = {j.depth_test, j.object_test, j.triangle_test};
    gl_int active = 0;
    gl_.GetIntegerv(kGlActiveTexture, &active);
    for (gl_uint u = 0; u < 3; ++u) {
      gl_.ActiveTexture(kGlTexture0 + u);
      gl_.BindTexture(kGlTexture2d, read[u] ? g[u] : 0u);
      rs_.BindSampler(u, sampler_);
    }
    gl_.ActiveTexture(static_cast<gl_enum>(active));
    // Records in batches of one storage block, drawn in order.
    const std::size_t batch = batch_records();
    const gl_uint* records = indirect ? resident_records_ : buffers_;
    for (std::size_t b0 = 0; b0 < total; b0 += batch) {
      const std::size_t m = std::min(batch, total - b0);
      fill(b0, m);
      gl_.UseProgram(program_.id());
      gl_.BindBufferBase(kGlShaderStorageBuffer, 0, records[0]);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 4, records[1]);
      if (indirect) {
        gl_.BindBuffer(kGlDrawIndirectBuffer, plan_);
        const std::size_t at = (kDrawSlot * slot_words_ + 4 * (b0 / batch)) * 4;
        // GL takes the offset into the bound indirect buffer as a pointer.
        // NOLINTNEXTLINE(performance-no-int-to-ptr)
        gr_.DrawArraysIndirect(kGlPoints, reinterpret_cast<const void*>(at));
      } else {
        gr_.DrawArrays(kGlPoints, 0, static_cast<gl_sizei>(m));
      }
      ++draws_;
    }
    for (gl_uint u = 0; u < 3; ++u) rs_.BindSampler(u, 0);
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
      for (int i = 0; i < 5; ++i) gl.GetIntegerv(kBufferQueries[i], &buffers_[i]);
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
      for (int i = 0; i < 5; ++i)
        gl_.BindBuffer(kBufferTargets[i], static_cast<gl_uint>(buffers_[i]));
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
    // The generic buffer bindings the resident walk uses (indirect commands, uniform block,
    // copies), and their queries (GL_COPY_READ_BUFFER_BINDING is GL_COPY_READ_BUFFER's value).
    static constexpr gl_enum kBufferTargets[5] = {kGlDispatchIndirectBuffer, kGlDrawIndirectBuffer,
                                                  kGlUniformBuffer, kGlCopyReadBuffer,
                                                  kGlCopyWriteBuffer};
    static constexpr gl_enum kBufferQueries[5] = {
        kGlDispatchIndirectBufferBinding, kGlDrawIndirectBufferBinding, kGlUniformBufferBinding,
        kGlCopyReadBuffer, kGlCopyWriteBuffer};
    gl_int buffers_[5] = {0, 0, 0, 0, 0};
    const gl_api& gl_;
    const gl_raster_api& gr_;
    gl_int program_ = 0, vao_ = 0, draw_ = 0, read_ = 0, buffer_ = 0, texture_ = 0, pack_ = 4;
    gl_int viewport_[4] = {0, 0, 0, 0}, blend_[4] = {1, 0, 1, 0}, equation_[2] = {0, 0};
    bool enabled_[5] = {false, false, false, false, false};
  };

  // The R32F texture t (w x h) as the target, cleared to 0; blending set to a plain sum.
  void target(gl_uint t, std::size_t w, std::size_t h) {
    gr_.BindFramebuffer(kGlFramebuffer, fbo_);
    gr_.FramebufferTexture2D(kGlFramebuffer, kGlColorAttachment0, kGlTexture2d, t, 0);
    if (gr_.CheckFramebufferStatus(kGlFramebuffer) != kGlFramebufferComplete)
      hush::detail::raise_error<std::runtime_error>(
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
      gl_.BindBufferBase(kGlShaderStorageBuffer, static_cast<gl_uint>(b),
                         b < 2 ? triangle_buffers_[b] : stage1_buffers_[b]);
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
      set(prog, "hush_items_host", static_cast<gl_uint>(n));
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
    const std::size_t nt = tris.triangles(), nv = tris.vertices();
    if (!stage1_fits(src, nv, nt)) return false;
    const state_guard guard(gl_, gr_);
    // Vertices and triangles in the layouts of npr_gabor_gl_frame (gl_frame.hpp).
    npr_gabor_gl_pack(tris, floats_, words_);
    upload(0, floats_.data(), nv * kNprGaborVertexBytes, 0);
    triangle_buffers_[0] = stage1_buffers_[0];
    upload(1, words_.data(), nt * kNprGaborTriangleBytes, 1);
    triangle_buffers_[1] = stage1_buffers_[1];
    return walk(noise, f.width(), f.height(), nt, src, total);
  }

  // Whether stage 1 can run on the GPU: sources constant or per object, every buffer within
  // one storage block.
  bool stage1_fits(const npr_gabor::sources& src, std::size_t nv, std::size_t nt) const {
    if (!npr_gabor::per_object_at_most(src)) return false;  // per pixel or vertex: the CPU
    const std::size_t most = dev_.max_buffer_bytes();
    return !(nt * kNprGaborLodBytes > most || nv * kNprGaborVertexBytes > most ||
             nt * kNprGaborTriangleBytes > most ||
             (table_entries(src) + 1) * 32 > most || nt * kNprGaborNodeBytes > most ||
             nt > 0xFFFFFFFFu);
  }
  // Kernel table entries before the constants' one.
  static std::size_t table_entries(const npr_gabor::sources& src) {
    std::size_t objects = 0;
    for (const param_source* p : {&src.frequency, &src.orientation, &src.bandwidth, &src.impulses})
      objects = std::max(objects, p->table_size());
    return objects;
  }

  // The kernel table, the per-triangle buffers and every pass's frame uniforms (both walks).
  void prepare(const npr_gabor& noise, std::size_t width, std::size_t height, std::size_t nt,
               const npr_gabor::sources& src) {
    const std::size_t objects = table_entries(src);
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
    bind_slot(1);  // the plan's block is declared, not read (the host's counts)
    const npr_gabor::params& p = noise.parameters();
    for (int pass = 0; pass < kNprGaborStage1Passes; ++pass) {
      const gl_uint prog = stage1_[pass].id();
      gl_.UseProgram(prog);
      set(prog, "hush_tris", static_cast<gl_uint>(nt));
      set(prog, "hush_table_last", static_cast<gl_uint>(objects));
      gl_.Uniform2ui(gl_.GetUniformLocation(prog, "hush_size"), static_cast<gl_uint>(width),
                     static_cast<gl_uint>(height));
      set(prog, "hush_key", seed_key(p.seed));
      set(prog, "hush_opts", (p.cull_back_faces ? 1u : 0u) | (p.thinning ? 2u : 0u) |
                                 (p.front_face == npr_gabor_front_face::clockwise ? 4u : 0u));
      set(prog, "hush_isotropic", p.isotropic ? 1u : 0u);
      set(prog, "hush_local", p.local_density ? 1u : 0u);
    }
  }

  // Stage 1 from the triangles in triangle_buffers_ (vertices, triangles; the layouts of
  // npr_gabor_gl_frame): the kernel table, the LODs, the walk (state guarded by the caller),
  // each level's totals read back (8 bytes per scan) to size the next level exactly.
  bool walk(const npr_gabor& noise, std::size_t width, std::size_t height, std::size_t nt,
            const npr_gabor::sources& src, std::size_t& total) {
    const std::size_t most = dev_.max_buffer_bytes();
    prepare(noise, width, height, nt, src);
    level_nodes_count_.clear();
    level_first_.clear();
    level_records_.clear();
    nodes_ = 0;
    levels_ = 0;
    total = 0;
    if (nt == 0) return true;
    // Level 0: the LOD of every triangle, the roots at their scanned offsets.
    gl_.UseProgram(stage1_[kLodsPass].id());
    bind_stage1();
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
        set(stage1_[pass].id(), "hush_nodes_host", static_cast<gl_uint>(n));
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

  // ---- The resident walk (render_resident after its first frame): no read-back. The host
  // issues every level's passes (kPlanLevels, the deepest any walk reaches) over buffers of
  // the capacities caps_; after each scan the plan pass (kNprGaborPlan) writes the next
  // level's count, its dispatch commands and the draws' counts into plan_, and the passes run
  // with glDispatchComputeIndirect / glDrawArraysIndirect (an empty level: zero work groups).

  // Slices of kMaxGroups work groups that cover `nodes` nodes (GL 4.3's minimum count per
  // dispatch dimension).
  static std::size_t slices(std::size_t nodes) {
    const std::size_t groups = (nodes + kNprGaborGroupSize - 1) / kNprGaborGroupSize;
    return std::max<std::size_t>(1, (groups + kMaxGroups - 1) / kMaxGroups);
  }
  std::size_t slot_bytes(std::size_t slot) const { return slot * slot_words_ * 4; }
  // Plan slot `slot` as the passes' uniform block (binding 0).
  void bind_slot(std::size_t slot) const {
    gr_.BindBufferRange(kGlUniformBuffer, 0, plan_, static_cast<gl_intptr>(slot_bytes(slot)), 32);
  }
  void barrier() const {
    gl_.MemoryBarrier(kGlShaderStorageBarrierBit | kGlUniformBarrierBit | kGlCommandBarrierBit |
                      kGlBufferUpdateBarrierBit);
  }
  // Records the capacities hold: every level's nodes (a node has at most one record).
  std::size_t record_capacity() const {
    std::size_t n = 0;
    for (const std::size_t c : caps_) n += c;
    return n;
  }
  std::size_t batches() const {
    const std::size_t batch = batch_records();
    return (record_capacity() + batch - 1) / batch;
  }
  // Whether the capacities fit: each level's buffers in one storage block, its node passes
  // within kMaxSlices dispatches and its scans within one per depth, at most
  // kDrawSlots * slot_words_ / 4 draws, records below 2^32.
  bool capacities_fit() const {
    const std::size_t most = dev_.max_buffer_bytes();
    for (const std::size_t c : caps_)
      if (c * kNprGaborNodeBytes > most || c > kMaxGroups * kNprGaborScanBlock ||
          slices(c) > kMaxSlices)
        return false;
    return record_capacity() <= 0xFFFFFFFFu && batches() <= kDrawSlots * slot_words_ / 4;
  }
  // Buffers for the capacities (made or grown when they change, not per frame).
  void allocate_resident(std::size_t nt) {
    bool changed = res_caps_ != caps_ || res_triangles_ < nt;
    if (!changed) return;
    for (std::size_t k = 0; k < kPlanLevels; ++k) {
      allocate(buffer_at(res_nodes_, k), caps_[k] * kNprGaborNodeBytes);
      allocate(buffer_at(res_flags_, k), caps_[k] * 8);
    }
    // The scans' block totals per depth: the largest list (a level's or the triangles').
    std::size_t items = std::max(nt, *std::max_element(caps_.begin(), caps_.end()));
    std::size_t d = 0;
    do {
      items = (items + kNprGaborScanBlock - 1) / kNprGaborScanBlock;
      allocate(buffer_at(res_sums_, d++), items * 8);
    } while (items > 1);
    const std::size_t m = std::min(batch_records(), record_capacity());
    allocate(resident_records_[0], m * kNprGaborRecordBytes);
    allocate(resident_records_[1], m * 16);
    res_caps_ = caps_;
    res_triangles_ = nt;
  }
  // The exclusive prefix sum of `data` in place, as scan() but without read-back: `items`
  // counted by the host, or (gpu) at most `items`, the plan's count of the bound slot `slot`,
  // dispatched from its commands. Returns the buffer whose first uvec2 is the total.
  gl_uint scan_resident(gl_uint data, std::size_t items, std::size_t depth, bool gpu,
                        std::size_t slot) {
    const gl_uint prog = stage1_[kScanPass].id();
    const std::size_t groups = (items + kNprGaborScanBlock - 1) / kNprGaborScanBlock;
    const gl_uint sums = res_sums_[depth];
    const auto pass = [&](gl_uint add) {
      gl_.UseProgram(prog);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 0, data);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 1, sums);
      set(prog, "hush_items_host", gpu ? kGpuCount : static_cast<gl_uint>(items));
      set(prog, "hush_depth", static_cast<gl_uint>(depth));
      set(prog, "hush_add", add);
      set(prog, "hush_group_base", 0u);
      if (gpu) {
        gl_.BindBuffer(kGlDispatchIndirectBuffer, plan_);
        gr_.DispatchComputeIndirect(
            static_cast<gl_intptr>(slot_bytes(slot) + (kScanArgsWord + 3 * depth) * 4));
      } else {
        gl_.DispatchCompute(static_cast<gl_uint>(groups), 1, 1);
      }
      barrier();
    };
    pass(0);
    if (groups <= 1) return sums;
    const gl_uint total = scan_resident(sums, groups, depth + 1, gpu, slot);
    pass(1);
    return total;
  }
  // The plan pass after the scan of `level` (kGpuCount: the triangles'), whose total is the
  // first uvec2 of `total`; the next level holds `cap` nodes.
  void plan(gl_uint level, gl_uint total, std::size_t cap) {
    const gl_uint prog = plan_program_.id();
    gl_.UseProgram(prog);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 0, total);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 1, plan_);
    set(prog, "hush_plan_level", level);
    set(prog, "hush_plan_cap", static_cast<gl_uint>(cap));
    set(prog, "hush_plan_stride", static_cast<gl_uint>(slot_words_));
    set(prog, "hush_plan_slices", static_cast<gl_uint>(slices(cap)));
    set(prog, "hush_plan_batch", static_cast<gl_uint>(batch_records()));
    set(prog, "hush_plan_batches", static_cast<gl_uint>(batches()));
    set(prog, "hush_plan_draws", static_cast<gl_uint>(kDrawSlot * slot_words_));
    gl_.DispatchCompute(1, 1, 1);
    barrier();
  }
  // Runs a node pass of level k (its slot bound) from the plan's commands.
  void dispatch_level(gl_uint prog, std::size_t k) const {
    gl_.BindBuffer(kGlDispatchIndirectBuffer, plan_);
    for (std::size_t i = 0; i < slices(caps_[k]); ++i) {
      set(prog, "hush_group_base", static_cast<gl_uint>(i * kMaxGroups));
      gr_.DispatchComputeIndirect(
          static_cast<gl_intptr>(slot_bytes(1 + k) + (kNodeArgsWord + 3 * i) * 4));
    }
    barrier();
  }
  // Stage 1 up to the records without read-back (the state guarded by the caller). False
  // where the capacities exceed what one storage block or dispatch holds.
  bool walk_resident(const npr_gabor& noise, std::size_t width, std::size_t height, std::size_t nt,
                     const npr_gabor::sources& src) {
    caps_[0] = std::max(caps_[0], nt);  // one root per triangle at most: known here
    if (!capacities_fit()) return false;
    allocate_resident(nt);
    prepare(noise, width, height, nt, src);
    levels_ = kPlanLevels;
    nodes_ = 0;
    if (nt == 0) return true;
    // Level 0: the LOD of every triangle, the roots at their scanned offsets.
    gl_.UseProgram(stage1_[kLodsPass].id());
    bind_stage1();
    run(kLodsPass, nt, kNprGaborGroupSize);
    plan(kGpuCount, scan_resident(stage1_buffers_[4], nt, 0, false, 0), caps_[0]);
    gl_.UseProgram(stage1_[kRootsPass].id());
    bind_stage1();
    gl_.BindBufferBase(kGlShaderStorageBuffer, 6, res_nodes_[0]);
    run(kRootsPass, nt, kNprGaborGroupSize);
    for (std::size_t k = 0; k < kPlanLevels; ++k) {
      bind_slot(1 + k);
      for (const int pass : {kExpandPass, kChildrenPass}) {
        gl_.UseProgram(stage1_[pass].id());
        set(stage1_[pass].id(), "hush_nodes_host", kGpuCount);
        set(stage1_[pass].id(), "hush_level", static_cast<gl_uint>(k));
      }
      gl_.UseProgram(stage1_[kExpandPass].id());
      bind_stage1();
      gl_.BindBufferBase(kGlShaderStorageBuffer, 4, res_flags_[k]);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 5, res_nodes_[k]);
      dispatch_level(stage1_[kExpandPass].id(), k);
      const gl_uint total = scan_resident(res_flags_[k], caps_[k], 0, true, 1 + k);
      const bool last = k + 1 == kPlanLevels;
      plan(static_cast<gl_uint>(k), total, last ? 0 : caps_[k + 1]);
      if (last) break;
      bind_slot(1 + k);
      gl_.UseProgram(stage1_[kChildrenPass].id());
      bind_stage1();
      gl_.BindBufferBase(kGlShaderStorageBuffer, 4, res_flags_[k]);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 5, res_nodes_[k]);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 6, res_nodes_[k + 1]);
      dispatch_level(stage1_[kChildrenPass].id(), k);
    }
    gl_.check("hush::glsl::npr_gabor: stage 1 (the resident walk)");
    return true;
  }
  // The records pass of the resident walk for records b0 ... b0 + m - 1 into
  // resident_records_: every level, from the plan's commands (the shader skips records
  // outside the batch).
  void generate_resident(std::size_t b0, std::size_t m) {
    barrier();  // the last draw's reads come first
    const gl_uint prog = stage1_[kRecordsPass].id();
    gl_.UseProgram(prog);
    bind_stage1();
    gl_.BindBufferBase(kGlShaderStorageBuffer, 6, resident_records_[0]);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 7, resident_records_[1]);
    set(prog, "hush_base", static_cast<gl_uint>(b0));
    set(prog, "hush_batch", static_cast<gl_uint>(m));
    set(prog, "hush_nodes_host", kGpuCount);
    set(prog, "hush_first_host", kGpuCount);
    for (std::size_t k = 0; k < kPlanLevels; ++k) {
      bind_slot(1 + k);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 4, res_flags_[k]);
      gl_.BindBufferBase(kGlShaderStorageBuffer, 5, res_nodes_[k]);
      set(prog, "hush_level", static_cast<gl_uint>(k));
      dispatch_level(prog, k);
    }
    gl_.check("hush::glsl::npr_gabor: stage 1 (resident records)");
  }

  // ---- The status: slot 0's first kStatusWords words (levels clamped, records, the most
  // nodes each level needed), copied on the GPU after each resident frame into a ring of
  // kStatusRing entries, each with a fence; the host reads an entry only once its fence has
  // signalled (glClientWaitSync with timeout 0: never waits), from a persistently mapped
  // buffer where the context has glBufferStorage (GL 4.4, ARB_buffer_storage), else with
  // glGetBufferSubData (a read of 128 bytes the GPU has already written).
  void make_status() {
    if (status_ != 0u) return;
    gl_.GenBuffers(1, &status_);
    gl_.BindBuffer(kGlCopyWriteBuffer, status_);
    const std::size_t bytes = kStatusRing * kStatusWords * 4;
    using storage_fn = void(HUSH_GLAPI*)(gl_enum, gl_sizeiptr, const void*, gl_bitfield);
    using map_fn = void*(HUSH_GLAPI*)(gl_enum, gl_intptr, gl_sizeiptr, gl_bitfield);
    const auto storage = reinterpret_cast<storage_fn>(gl_.loader("glBufferStorage"));
    const auto map = reinterpret_cast<map_fn>(gl_.loader("glMapBufferRange"));
    gl_int major = 0, minor = 0;
    gl_.GetIntegerv(kGlMajorVersion, &major);
    gl_.GetIntegerv(kGlMinorVersion, &minor);
    if (storage && map && (major > 4 || (major == 4 && minor >= 4))) {
      const gl_bitfield flags = kGlMapReadBit | kGlMapPersistentBit | kGlMapCoherentBit;
      storage(kGlCopyWriteBuffer, static_cast<gl_sizeiptr>(bytes), nullptr, flags);
      status_map_ = static_cast<const std::uint32_t*>(
          map(kGlCopyWriteBuffer, 0, static_cast<gl_sizeiptr>(bytes), flags));
    }
    if (!status_map_)
      gl_.BufferData(kGlCopyWriteBuffer, static_cast<gl_sizeiptr>(bytes), nullptr, kGlDynamicRead);
    gl_.check("hush::glsl::npr_gabor: the status buffer");
  }
  // After a resident frame: its status into the next ring entry, fenced (skipped while every
  // entry waits for the GPU: the needed counts are maxima, a later copy carries them).
  void push_status() {
    void*& fence = status_fences_[status_next_];
    if (fence) return;
    gl_.BindBuffer(kGlCopyReadBuffer, plan_);
    gl_.BindBuffer(kGlCopyWriteBuffer, status_);
    rs_.CopyBufferSubData(kGlCopyReadBuffer, kGlCopyWriteBuffer, 0,
                          static_cast<gl_intptr>(status_next_ * kStatusWords * 4),
                          static_cast<gl_sizeiptr>(kStatusWords * 4));
    fence = gr_.FenceSync(kGlSyncGpuCommandsComplete, 0);
    status_next_ = (status_next_ + 1) % kStatusRing;
  }
  // Before a resident frame: every entry whose fence has signalled, oldest first; where a
  // level needed more nodes than its capacity (its own count is exact, the deeper levels'
  // only count the children of the nodes kept), the frame is walked with read-backs again.
  void poll_status() {
    for (std::size_t i = 0; i < kStatusRing; ++i) {
      const std::size_t e = (status_next_ + i) % kStatusRing;
      void*& fence = status_fences_[e];
      if (!fence) continue;
      const gl_enum r = gr_.ClientWaitSync(fence, 0, 0);
      if (r != kGlAlreadySignaled && r != kGlConditionSatisfied) break;
      gr_.DeleteSync(fence);
      fence = nullptr;
      std::uint32_t w[kStatusWords];
      if (status_map_) {
        std::memcpy(w, status_map_ + e * kStatusWords, sizeof w);
      } else {
        gl_.BindBuffer(kGlCopyReadBuffer, status_);
        gl_.GetBufferSubData(kGlCopyReadBuffer, static_cast<gl_intptr>(e * kStatusWords * 4),
                             sizeof w, w);
      }
      if (w[0] > overflows_seen_) {
        overflows_seen_ = w[0];
        resize_ = true;
      }
    }
  }

  // Stage 1's last pass for records b0 ... b0 + m - 1 (the frame's records level by level):
  // into buffers_[0] and buffers_[1], from every level whose records meet the batch.
  void generate(std::size_t b0, std::size_t m) {
    gl_.MemoryBarrier(kGlShaderStorageBarrierBit);  // the last draw's reads come first
    const gl_uint prog = stage1_[kRecordsPass].id();
    gl_.UseProgram(prog);
    bind_stage1();
    bind_slot(1);  // the plan's block is declared, not read (the host's counts)
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
      set(prog, "hush_nodes_host", static_cast<gl_uint>(level_nodes_count_[k]));
      set(prog, "hush_first_host", static_cast<gl_uint>(level_first_[k]));
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
  // The resident walk's levels and work groups per dispatch (glsl.hpp); a level's least
  // capacity (nodes); "the plan's count" for the count uniforms.
  static constexpr std::size_t kPlanLevels = kNprGaborPlanLevels;
  static constexpr std::size_t kMaxGroups = kNprGaborMaxGroups;
  static constexpr std::size_t kMinCapacity = 4096;
  static constexpr gl_uint kGpuCount = 0xFFFFFFFFu;
  // Plan layout (words within a slot, kNprGaborPlan): node-pass commands, scan commands;
  // slot 0's needed counts; the draws' slots after the levels' (0, 1 ... kPlanLevels + 1).
  static constexpr std::size_t kNodeArgsWord = 8, kScanArgsWord = 32, kNeededWord = 8;
  static constexpr std::size_t kMaxSlices = (kScanArgsWord - kNodeArgsWord) / 3;
  static constexpr std::size_t kDrawSlot = kPlanLevels + 2, kDrawSlots = 2;
  static constexpr std::size_t kStatusWords = 32, kStatusRing = 4;
  static_assert(kNeededWord + kPlanLevels + 1 <= kStatusWords, "status layout");

  glsl::device& dev_;
  const gl_api& gl_;
  gl_raster_api gr_;
  gl_resident_api rs_;
  npr_gabor_limits limits_;
  gl_program program_;
  gl_program stage1_[kNprGaborStage1Passes];
  gl_program plan_program_;
  // The resident walk: the plan, capacities per level (empty: not sized yet) and the ones the
  // buffers were made for, its buffers, the status ring.
  gl_uint plan_ = 0;
  std::size_t slot_words_ = 64;
  std::vector<std::size_t> caps_, res_caps_;
  std::size_t res_triangles_ = 0;
  std::vector<gl_uint> res_nodes_, res_flags_, res_sums_;
  gl_uint resident_records_[2] = {0, 0};
  gl_uint status_ = 0;
  const std::uint32_t* status_map_ = nullptr;
  void* status_fences_[kStatusRing] = {nullptr, nullptr, nullptr, nullptr};
  std::size_t status_next_ = 0, overflows_seen_ = 0;
  bool resize_ = false;
  std::size_t reserved_ = 0;  // reserve_resident's nodes per level
  gl_uint buffers_[2] = {0, 0};  // records, ids
  gl_uint stage1_buffers_[kStage1Buffers] = {0, 0, 0, 0, 0};
  // The vertices and triangles stage 1 reads: stage1_buffers_[0, 1] or the caller's.
  gl_uint triangle_buffers_[2] = {0, 0};
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
  gl_uint gbuffer_[3] = {0, 0, 0};  // the CPU-image path's G-buffer: depth, object, triangle ids
  gl_uint sampler_ = 0;
  std::size_t gbuffer_width_ = 0, gbuffer_height_ = 0;
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

#endif  // HUSH_GLSL_NPR_GABOR_RENDERER_HPP

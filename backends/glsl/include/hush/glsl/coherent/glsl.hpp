// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GLSL source of coherent noise (include/hush/coherent.hpp) on the GPU: the compute pass
// that runs one frame's step (hush/coherent/kernel.hpp, statement by statement) and its
// generated constants. hush/glsl/coherent/renderer.hpp runs it and states its contract;
// `hush glsl-export` writes it (hush/glsl/export.hpp).
#ifndef HUSH_GLSL_COHERENT_GLSL_HPP
#define HUSH_GLSL_COHERENT_GLSL_HPP

#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "hush/detail/constants.hpp"
#include "hush/glsl/compute_source.hpp"
#include "hush/glsl/generator.hpp"
#include "hush/glsl/library.hpp"

namespace hush {
namespace glsl {

// Where a field's values come from (the program's HUSH_COHERENT_INPUT / _REFILL).
enum class coherent_field_mode : std::uint32_t { white = 0, bandpass = 1, plane = 2 };

// The uniform arrays of the pass hold kCoherentFieldUniforms fields per channel (input,
// refill x, refill y), for every channel a stream may have.
constexpr unsigned kCoherentFieldUniforms = 3;
constexpr unsigned kCoherentFieldSlots =
    kCoherentFieldUniforms * static_cast<unsigned>(hush::detail::constants::kCoherentMaxChannels);

// The GLSL constants of the coherent pass, generated from hush/detail/constants.hpp and
// std::numeric_limits<float> (the same machinery as generator.hpp's constant_table()).
inline std::vector<glsl_constant> coherent_constant_table() {
  namespace c = hush::detail::constants;
  using detail::float_bits;
  using detail::float_constant;
  using detail::uint_constant;
  using flt = std::numeric_limits<float>;
  return {
      uint_constant("HUSH_COHERENT_WHITE_SHIFT", c::kCoherentWhiteShift,
                    "white noise: hash >> shift (24 bits)"),
      float_constant("HUSH_COHERENT_WHITE_CENTRE", c::kCoherentWhiteCentre, "2^24 - 1"),
      float_constant("HUSH_COHERENT_WHITE_SCALE", c::kCoherentWhiteScale, "sqrt(3) 2^-24"),
      uint_constant("HUSH_COHERENT_PIXEL_PRIME", c::kCoherentPixelPrime, "pixel hash multiplier"),
      {"HUSH_COHERENT_FLT_MIN",
       glsl_constant::type::f32,
       false,
       {float_bits(flt::min())},
       "smallest normal float: smaller magnitudes are not surfaces / read as 0"},
      {"HUSH_COHERENT_FLT_MAX",
       glsl_constant::type::f32,
       false,
       {float_bits(flt::max())},
       "largest finite float"},
      uint_constant("HUSH_COHERENT_FIELDS", kCoherentFieldUniforms,
                    "fields per channel in the uniforms: input, refill x, refill y"),
      uint_constant("HUSH_COHERENT_FIELD_SLOTS", kCoherentFieldSlots,
                    "field uniforms: fields per channel times the most channels"),
      uint_constant("HUSH_COHERENT_WHITE", static_cast<std::uint32_t>(coherent_field_mode::white),
                    "field source: hashed white noise"),
      uint_constant("HUSH_COHERENT_BANDPASS",
                    static_cast<std::uint32_t>(coherent_field_mode::bandpass),
                    "field source: Perlin of CPU-split lattice triples"),
      uint_constant("HUSH_COHERENT_PLANE", static_cast<std::uint32_t>(coherent_field_mode::plane),
                    "field source: the caller's image"),
  };
}

namespace detail {

// The pass body: coherent_kernel.hpp's coherent_reproject and coherent_pixel, statement by
// statement. Reads only generated names and the uniforms below.
constexpr const char* kCoherentBody = R"glsl(
// ---- Coherent noise pass (hush/glsl/coherent/glsl.hpp; hush/coherent/kernel.hpp).
// HUSH_COHERENT_INPUT and HUSH_COHERENT_REFILL (defined before this text) say where the input
// and the refill fields come from: HUSH_COHERENT_WHITE (hashed), HUSH_COHERENT_BANDPASS (Perlin
// of CPU-split lattice triples in hush_planes) or, for the input, HUSH_COHERENT_PLANE (the
// caller's images in hush_planes); one program per combination, so no lane runs a path it
// does not need.
uniform uint hush_first;       // first pixel of this dispatch
uniform uint hush_count;       // pixels of the frame
uniform uvec2 hush_size;       // width, height
uniform uint hush_flags;       // 1: reference frame, 2: ids in both frames, 4: stationary
uniform uint hush_channels;
uniform uint hush_frame_ids;   // 1: this frame has object ids (hush_ids_tex), 0: none
uniform uint hush_sign;        // floatBitsToUint(motion sign): +1 velocity, -1 forward velocity
uniform uint hush_eps_rel;     // float bits
uniform uint hush_eps_abs;
uniform uint hush_alpha;
uniform uint hush_beta;
uniform uint hush_k;
uniform uint hush_scale;       // band-pass scale 1 / sqrt(Perlin variance), float bits
// Per channel c and field f (0 input, 1 refill x, 2 refill y), index HUSH_COHERENT_FIELDS c + f:
// the frame key (white), the Perlin key (band-pass), and the field's offset in hush_planes
// (band-pass: (width + 1) column triples, then (height + 1) row triples; plane: width x height).
uniform uint hush_field_key[HUSH_COHERENT_FIELD_SLOTS];
uniform uint hush_field_offset[HUSH_COHERENT_FIELD_SLOTS];
// The frame: textures read with texelFetch, texel (x, y) = pixel (x, y) (hush/glsl/coherent/
// frame.hpp: depth R32F, object ids R32UI, motion (dx, dy, dz) in .xyz of an RGB(A)32F).
layout(binding = 0) uniform sampler2D hush_depth_tex;
layout(binding = 1) uniform usampler2D hush_ids_tex;
layout(binding = 2) uniform sampler2D hush_motion_tex;
// The reference frame (the previous one): depth bits, then ids; and this frame's, written for
// the next.
layout(std430, binding = 2) readonly buffer hush_ref_in_b { uint hush_ref_in[]; };
layout(std430, binding = 3) writeonly buffer hush_ref_out_b { uint hush_ref_out[]; };
layout(std430, binding = 5) readonly buffer hush_history_in_b { float hush_history_in[]; };
// The new history: channels planes, then the fresh flags (0.0 or 1.0).
layout(std430, binding = 6) writeonly buffer hush_history_out_b { float hush_history_out[]; };
layout(std430, binding = 7) readonly buffer hush_planes_b { uint hush_planes[]; };
// The output: gain times the new history of channel c into image c, for c < hush_outputs.
uniform uint hush_outputs;
uniform uint hush_gain;        // float bits
layout(r32f, binding = 0) writeonly uniform image2D hush_out0;
layout(r32f, binding = 1) writeonly uniform image2D hush_out1;
layout(r32f, binding = 2) writeonly uniform image2D hush_out2;
layout(r32f, binding = 3) writeonly uniform image2D hush_out3;

void hush_coherent_store(uint c, ivec2 p, float v) {
  vec4 t = vec4(v * uintBitsToFloat(hush_gain));
  if (c == 0u) imageStore(hush_out0, p, t);
  else if (c == 1u) imageStore(hush_out1, p, t);
  else if (c == 2u) imageStore(hush_out2, p, t);
  else imageStore(hush_out3, p, t);
}
bool hush_coherent_surface(float d) { return d >= HUSH_COHERENT_FLT_MIN && d <= HUSH_COHERENT_FLT_MAX; }
bool hush_coherent_finite(float v) { return v >= -HUSH_COHERENT_FLT_MAX && v <= HUSH_COHERENT_FLT_MAX; }
float hush_coherent_flush(float v) { return abs(v) < HUSH_COHERENT_FLT_MIN ? 0.0 : v; }
float hush_coherent_white(uint row_key, uint x) {
  uint h = hush_hash32(row_key ^ (x * HUSH_COHERENT_PIXEL_PRIME));
  float centred = float(2u * (h >> HUSH_COHERENT_WHITE_SHIFT)) - HUSH_COHERENT_WHITE_CENTRE;
  return centred * HUSH_COHERENT_WHITE_SCALE;
}
float hush_coherent_bandpass(uint index, uint x, uint y) {
  uint base = hush_field_offset[index];
  uint tx = base + 3u * x, ty = base + 3u * (hush_size.x + 1u + y);
  float v = hush_perlin2_cells(uvec2(hush_planes[tx], hush_planes[ty]),
                               uvec2(hush_planes[tx + 1u], hush_planes[ty + 1u]),
                               vec2(uintBitsToFloat(hush_planes[tx + 2u]),
                                    uintBitsToFloat(hush_planes[ty + 2u])), hush_field_key[index]);
  return v * uintBitsToFloat(hush_scale);
}
// Field `index` (input or refill, see HUSH_COHERENT_INPUT / _REFILL) at (x, y), as `mode` says.
float hush_coherent_field(uint mode, uint index, uint x, uint y) {
  if (mode == HUSH_COHERENT_WHITE) return hush_coherent_white(hush_hash32(hush_field_key[index], y), x);
  if (mode == HUSH_COHERENT_BANDPASS) return hush_coherent_bandpass(index, x, y);
  float v = uintBitsToFloat(hush_planes[hush_field_offset[index] + y * hush_size.x + x]);
  return hush_coherent_finite(v) ? v : 0.0;
}

void main() {
  uint n = hush_first + gl_GlobalInvocationID.x;
  if (n >= hush_count) return;
  uint width = hush_size.x, height = hush_size.y;
  uint x = n % width, y = n / width;
  // ---- Reprojection: never fused (precise), so the decisions are the CPU's.
  precise float sgn = uintBitsToFloat(hush_sign);
  ivec2 pixel = ivec2(int(x), int(y));
  precise float depth = texelFetch(hush_depth_tex, pixel, 0).x;
  vec3 motion = texelFetch(hush_motion_tex, pixel, 0).xyz;
  precise float mx = hush_coherent_flush(sgn * motion.x);
  precise float my = hush_coherent_flush(sgn * motion.y);
  precise float mz = hush_coherent_flush(sgn * motion.z);
  bool use_ids = (hush_flags & 2u) != 0u;
  uint id = hush_frame_ids != 0u ? texelFetch(hush_ids_tex, pixel, 0).x : 0u;
  uint plane = width * height;
  hush_ref_out[n] = floatBitsToUint(depth);
  hush_ref_out[plane + n] = id;
  bool visible = false;
  uint t00 = 0u, t10 = 0u, t01 = 0u, t11 = 0u;
  precise float w00 = 0.0, w10 = 0.0, w01 = 0.0, w11 = 0.0;
  precise float tx = 0.0, ty = 0.0, a = 1.0, b = 1.0;
  if ((hush_flags & 1u) != 0u && hush_coherent_surface(depth) && hush_coherent_finite(mx) &&
      hush_coherent_finite(my) && hush_coherent_finite(mz)) {
    precise float u = float(x) - mx;
    precise float v = float(y) - my;
    if (u >= 0.0 && u <= float(width - 1u) && v >= 0.0 && v <= float(height - 1u)) {
      precise float i0 = min(floor(u), float(width > 1u ? width - 2u : 0u));
      precise float j0 = min(floor(v), float(height > 1u ? height - 2u : 0u));
      tx = u - i0;
      ty = v - j0;
      a = 1.0 - tx;
      b = 1.0 - ty;
      w00 = a * b;
      w10 = tx * b;
      w01 = a * ty;
      w11 = tx * ty;
      t00 = uint(j0) * width + uint(i0);
      t10 = t00 + (width > 1u ? 1u : 0u);
      t01 = t00 + (height > 1u ? width : 0u);
      t11 = t01 + (t10 - t00);
      bool ok = true;
      // Taps with weight 0 are never read (a background tap must not matter).
      precise float interpolated = 0.0;
      float d;
      if (w00 != 0.0) {
        d = uintBitsToFloat(hush_ref_in[t00]);
        ok = ok && hush_coherent_surface(d) && (!use_ids || hush_ref_in[plane + t00] == id);
        interpolated = interpolated + w00 * d;
      }
      if (w10 != 0.0) {
        d = uintBitsToFloat(hush_ref_in[t10]);
        ok = ok && hush_coherent_surface(d) && (!use_ids || hush_ref_in[plane + t10] == id);
        interpolated = interpolated + w10 * d;
      }
      if (w01 != 0.0) {
        d = uintBitsToFloat(hush_ref_in[t01]);
        ok = ok && hush_coherent_surface(d) && (!use_ids || hush_ref_in[plane + t01] == id);
        interpolated = interpolated + w01 * d;
      }
      if (w11 != 0.0) {
        d = uintBitsToFloat(hush_ref_in[t11]);
        ok = ok && hush_coherent_surface(d) && (!use_ids || hush_ref_in[plane + t11] == id);
        interpolated = interpolated + w11 * d;
      }
      precise float expected = depth - mz;
      precise float tolerance = uintBitsToFloat(hush_eps_rel) * expected + uintBitsToFloat(hush_eps_abs);
      visible = ok && hush_coherent_surface(expected) && abs(interpolated - expected) <= tolerance;
    }
  }
  hush_history_out[hush_channels * plane + n] = visible ? 0.0 : 1.0;
  // ---- Values, per channel (the blends may fuse: the tolerance's part).
  float alpha = uintBitsToFloat(hush_alpha), beta = uintBitsToFloat(hush_beta);
  float kk = uintBitsToFloat(hush_k);
  float sx = sqrt(tx * a), sy = sqrt(ty * b);
  bool stationary = (hush_flags & 4u) != 0u;
  for (uint c = 0u; c < hush_channels; ++c) {
    uint f = HUSH_COHERENT_FIELDS * c;
    float wv = hush_coherent_field(HUSH_COHERENT_INPUT, f, x, y);
    float value = kk * wv;
    if (visible) {
      uint o = c * plane;
      float h = w00 * hush_history_in[o + t00] + w10 * hush_history_in[o + t10] +
                w01 * hush_history_in[o + t01] + w11 * hush_history_in[o + t11];
      if (!stationary) {
        value = alpha * h + beta * wv;
      } else {
        float x00 = hush_coherent_field(HUSH_COHERENT_REFILL, f + 1u, x, y);
        float x10 = hush_coherent_field(HUSH_COHERENT_REFILL, f + 1u, x + 1u, y);
        float x01 = hush_coherent_field(HUSH_COHERENT_REFILL, f + 1u, x, y + 1u);
        float x11 = hush_coherent_field(HUSH_COHERENT_REFILL, f + 1u, x + 1u, y + 1u);
        float y00 = hush_coherent_field(HUSH_COHERENT_REFILL, f + 2u, x, y);
        float y01 = hush_coherent_field(HUSH_COHERENT_REFILL, f + 2u, x, y + 1u);
        float dx = b * (x00 - x10) + ty * (x01 - x11);
        float dd = kk * (sx * dx + sy * (y00 - y01));
        value = alpha * (h + dd) + beta * wv;
      }
    }
    value = hush_coherent_flush(value);
    hush_history_out[c * plane + n] = value;
    if (c < hush_outputs) hush_coherent_store(c, pixel, value);
  }
}
)glsl";

}  // namespace detail

// The compute shader of the pass (#version 430 core; Vulkan too, hush/glsl/dialect.hpp) for input
// and refill fields taken from `input` and `refill` (white or band-pass; the input also from the
// caller's plane): the library, the coherent constants, the two field sources, the body. `hush
// glsl-export` writes the white / white one as hush_coherent_pass.comp.
inline std::string coherent_source(coherent_field_mode input = coherent_field_mode::white,
                                   coherent_field_mode refill = coherent_field_mode::white) {
  std::string constants =
      "// ---- Coherent-noise constants (hush::glsl::coherent_constant_table()).\n";
  for (const glsl_constant& k : coherent_constant_table())
    constants += std::string("const ") + (k.kind == glsl_constant::type::u32 ? "uint " : "float ") +
                 k.name + " = " + glsl_literal(k.kind, k.bits[0]) + ";  // " + k.what + "\n";
  auto source = [](coherent_field_mode m) {
    return m == coherent_field_mode::white      ? "HUSH_COHERENT_WHITE"
           : m == coherent_field_mode::bandpass ? "HUSH_COHERENT_BANDPASS"
                                                : "HUSH_COHERENT_PLANE";
  };
  return dual_dialect(
      "#version 430 core\n// hush " HUSH_VERSION_STRING
      " coherent-noise pass (hush/glsl/coherent/glsl.hpp).\nlayout(local_size_x = " +
          std::to_string(kLocalSize) + ") in;\n" + library() + constants +
          "#define HUSH_COHERENT_INPUT " + source(input) + "\n#define HUSH_COHERENT_REFILL " +
          source(refill) + "\n" + detail::kCoherentBody,
      "hush_coherent_params");
}

namespace detail {

// The files `hush glsl-export` writes for coherent noise (hush/glsl/export.hpp), as
// (file name, text): the pass with white input and refill.
inline std::vector<std::pair<std::string, std::string>> coherent_exports() {
  return {{"hush_coherent_pass.comp", coherent_source()}};
}

}  // namespace detail

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_COHERENT_GLSL_HPP

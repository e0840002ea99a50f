// The resident-path suites' GL loader (tests/coherent/glsl_coherent_frame_test.cpp,
// tests/npr_gabor/glsl_npr_gabor_frame_test.cpp,
// tests/anisotropic/glsl_anisotropic_frame_test.cpp): the wrapped loader of wrapped_loader.hpp
// (every GL call counted, GPU work skippable) with replacements that count every entry point
// reading GL data back to the host, and every one that uploads host data (buffers, 2D textures),
// with the amount uploaded. counted_device() is a hush::glsl::device whose GL calls all go through
// it. test_gl: the test's own GL calls (textures, their contents and read-back), through the plain
// loader.
#ifndef HUSH_TESTS_GLSL_READBACK_COUNTER_HPP
#define HUSH_TESTS_GLSL_READBACK_COUNTER_HPP

#include <string>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "glsl/wrapped_loader.hpp"
#include "hush/glsl/detail/gl_raster.hpp"
#include "hush/glsl/detail/gl_resident.hpp"
#include "hush/glsl/device.hpp"

namespace hush_glsl_test {

namespace hgl = hush::glsl::detail;

// The read-backs and uploads made through the wrapped loader.
struct readback_counter {
  // Calls of glGetBufferSubData, glReadPixels, glGetTexImage, glMapBufferRange.
  enum which { get_buffer_calls, read_pixels_calls, get_tex_calls, map_calls };
  static int& count(which w) {
    static int n[4] = {0, 0, 0, 0};
    return n[w];
  }
  static int count() {
    return count(get_buffer_calls) + count(read_pixels_calls) + count(get_tex_calls) +
           count(map_calls);
  }
  // Host data sent to GL: calls of glBufferData / glBufferSubData / glTexImage2D /
  // glTexSubImage2D with data, and their sizes (bytes for buffers, texels for textures).
  struct uploads {
    int calls = 0;
    long long buffer_bytes = 0, texels = 0;
    bool operator==(const uploads& o) const {
      return calls == o.calls && buffer_bytes == o.buffer_bytes && texels == o.texels;
    }
  };
  static uploads& uploaded() {
    static uploads u;
    return u;
  }
  // The wrapped loader, with the counting replacements set on first use; the real loader is
  // the headless context's.
  static void* loader(const char* name) {
    static const bool ready = install();
    (void)ready;
    return wrapped_gl::loader(name);
  }

 private:
  template <gl_entry_id Id>
  using entry = gl_entry<Id>;
  using id = gl_entry_id;
  static void upload(long long bytes, long long texels) {
    ++uploaded().calls;
    uploaded().buffer_bytes += bytes;
    uploaded().texels += texels;
  }
  static void HUSH_GLAPI buffer_data(hgl::gl_enum t, hgl::gl_sizeiptr s, const void* d,
                                     hgl::gl_enum u) {
    if (d) upload(static_cast<long long>(s), 0);
    entry<id::BufferData>::real(t, s, d, u);
  }
  static void HUSH_GLAPI buffer_sub(hgl::gl_enum t, hgl::gl_intptr o, hgl::gl_sizeiptr s,
                                    const void* d) {
    upload(static_cast<long long>(s), 0);
    entry<id::BufferSubData>::real(t, o, s, d);
  }
  static void HUSH_GLAPI tex_image(hgl::gl_enum t, hgl::gl_int l, hgl::gl_int i, hgl::gl_sizei w,
                                   hgl::gl_sizei h, hgl::gl_int b, hgl::gl_enum f, hgl::gl_enum ty,
                                   const void* d) {
    if (d) upload(0, static_cast<long long>(w) * h);
    entry<id::TexImage2D>::real(t, l, i, w, h, b, f, ty, d);
  }
  static void HUSH_GLAPI tex_sub(hgl::gl_enum t, hgl::gl_int l, hgl::gl_int x, hgl::gl_int y,
                                 hgl::gl_sizei w, hgl::gl_sizei h, hgl::gl_enum f, hgl::gl_enum ty,
                                 const void* d) {
    upload(0, static_cast<long long>(w) * h);
    entry<id::TexSubImage2D>::real(t, l, x, y, w, h, f, ty, d);
  }
  static void HUSH_GLAPI get_buffer(hgl::gl_enum t, hgl::gl_intptr o, hgl::gl_sizeiptr s, void* d) {
    ++count(get_buffer_calls);
    entry<id::GetBufferSubData>::real(t, o, s, d);
  }
  static void HUSH_GLAPI read_pixels(hgl::gl_int x, hgl::gl_int y, hgl::gl_sizei w, hgl::gl_sizei h,
                                     hgl::gl_enum f, hgl::gl_enum t, void* d) {
    ++count(read_pixels_calls);
    entry<id::ReadPixels>::real(x, y, w, h, f, t, d);
  }
  static void HUSH_GLAPI get_tex(hgl::gl_enum t, hgl::gl_int l, hgl::gl_enum f, hgl::gl_enum ty,
                                 void* d) {
    ++count(get_tex_calls);
    entry<id::GetTexImage>::real(t, l, f, ty, d);
  }
  static void* HUSH_GLAPI map(hgl::gl_enum t, hgl::gl_intptr o, hgl::gl_sizeiptr s,
                              hgl::gl_bitfield a) {
    ++count(map_calls);
    return entry<id::MapBufferRange>::real(t, o, s, a);
  }
  static bool install() {
    wrapped_gl::install(headless().context.loader());
    entry<id::BufferData>::replacement = &buffer_data;
    entry<id::BufferSubData>::replacement = &buffer_sub;
    entry<id::TexImage2D>::replacement = &tex_image;
    entry<id::TexSubImage2D>::replacement = &tex_sub;
    entry<id::GetBufferSubData>::replacement = &get_buffer;
    entry<id::ReadPixels>::replacement = &read_pixels;
    entry<id::GetTexImage>::replacement = &get_tex;
    entry<id::MapBufferRange>::replacement = &map;
    return true;
  }
};

// A device whose GL calls go through the counting loader.
inline hush::glsl::device& counted_device() {
  headless();
  static hush::glsl::device d(&readback_counter::loader);
  return d;
}

// The GL calls of one frame `frame()` through the wrapped loader: run for real, and run with
// the GPU's work skipped (which must change no call). Every entry point hush loaded must be
// wrapped (wrapped_gl::unwrapped() empty), so these are all its GL calls.
struct frame_calls {
  long long real = 0, skipped = 0;
};
template <class F>
frame_calls calls_per_frame(F&& frame) {
  frame_calls c;
  c.real = gl_calls_of(frame);
  const skipping_gpu_work skip;
  c.skipped = gl_calls_of(frame);
  return c;
}

// The names hush loaded that the wrapped loader lacks, comma-separated ("" when every call is
// counted), so that a failing check names them.
inline std::string unwrapped_names() {
  std::string names;
  for (const std::string& n : wrapped_gl::unwrapped()) names += (names.empty() ? "" : ", ") + n;
  return names;
}

// The test's own GL: textures for the G-buffer and the outputs, and their read-back.
struct test_gl {
  const hgl::gl_api& api = headless().device.gl();
  hgl::gl_resident_api rs{api.loader};
  hgl::gl_raster_api gr{api.loader};
  // A w x h texture of `internal` format; contents from `data` (layout, type) or none.
  hgl::gl_uint texture(hgl::gl_enum internal, int w, int h, hgl::gl_enum layout, hgl::gl_enum type,
                       const void* data = nullptr) const {
    hgl::gl_uint t = 0;
    api.GenTextures(1, &t);
    api.BindTexture(hgl::kGlTexture2d, t);
    api.TexImage2D(hgl::kGlTexture2d, 0, static_cast<hgl::gl_int>(internal), w, h, 0, layout, type,
                   data);
    api.BindTexture(hgl::kGlTexture2d, 0);
    api.check("test: a texture");
    return t;
  }
  void update(hgl::gl_uint t, int w, int h, hgl::gl_enum layout, hgl::gl_enum type,
              const void* data) const {
    api.BindTexture(hgl::kGlTexture2d, t);
    rs.TexSubImage2D(hgl::kGlTexture2d, 0, 0, 0, w, h, layout, type, data);
    api.BindTexture(hgl::kGlTexture2d, 0);
  }
  std::vector<float> read(hgl::gl_uint t, int w, int h) const {
    std::vector<float> v(static_cast<std::size_t>(w) * h);
    api.BindTexture(hgl::kGlTexture2d, t);
    api.PixelStorei(hgl::kGlPackAlignment, 4);
    gr.GetTexImage(hgl::kGlTexture2d, 0, hgl::kGlRedChannel, hgl::kGlFloat, v.data());
    api.BindTexture(hgl::kGlTexture2d, 0);
    api.check("test: reading a texture");
    return v;
  }
};

}  // namespace hush_glsl_test

#endif  // HUSH_TESTS_GLSL_READBACK_COUNTER_HPP

// A GL loader for the resident-path suites (tests/coherent/glsl_coherent_frame_test.cpp,
// tests/npr_gabor/glsl_npr_gabor_frame_test.cpp, tests/anisotropic/glsl_anisotropic_frame_test.cpp):
// every entry point that reads GL data back to the host, and every one that uploads host data
// (buffers, 2D textures), is handed out as a wrapper that counts its calls and, for uploads,
// the amount; the others resolve as the headless context's loader resolves them.
// counted_device() is a hush::glsl::device whose GL calls all go through it. test_gl: the
// test's own GL calls (textures, their contents and read-back), through the plain loader.
#ifndef HUSH_TESTS_GLSL_READBACK_COUNTER_HPP
#define HUSH_TESTS_GLSL_READBACK_COUNTER_HPP

#include <string>
#include <type_traits>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "hush/glsl/detail/gl_resident.hpp"
#include "hush/glsl/device.hpp"

namespace hush_glsl_test {

namespace hgl = hush::glsl::detail;

// A loader that hands out counting wrappers for every entry point that reads GL data back to
// the host; the other names resolve as the real loader resolves them.
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
  using buffer_data_fn = void(HUSH_GLAPI*)(hgl::gl_enum, hgl::gl_sizeiptr, const void*,
                                           hgl::gl_enum);
  using buffer_sub_fn = void(HUSH_GLAPI*)(hgl::gl_enum, hgl::gl_intptr, hgl::gl_sizeiptr,
                                          const void*);
  using tex_image_fn = void(HUSH_GLAPI*)(hgl::gl_enum, hgl::gl_int, hgl::gl_int, hgl::gl_sizei,
                                         hgl::gl_sizei, hgl::gl_int, hgl::gl_enum, hgl::gl_enum,
                                         const void*);
  using tex_sub_fn = void(HUSH_GLAPI*)(hgl::gl_enum, hgl::gl_int, hgl::gl_int, hgl::gl_int,
                                       hgl::gl_sizei, hgl::gl_sizei, hgl::gl_enum, hgl::gl_enum,
                                       const void*);
  template <class Fn>
  static Fn& slot() {
    static Fn f = nullptr;
    return f;
  }
  static void HUSH_GLAPI counted_buffer_data(hgl::gl_enum t, hgl::gl_sizeiptr s, const void* d,
                                             hgl::gl_enum u) {
    if (d) {
      ++uploaded().calls;
      uploaded().buffer_bytes += static_cast<long long>(s);
    }
    slot<buffer_data_fn>()(t, s, d, u);
  }
  static void HUSH_GLAPI counted_buffer_sub(hgl::gl_enum t, hgl::gl_intptr o, hgl::gl_sizeiptr s,
                                            const void* d) {
    ++uploaded().calls;
    uploaded().buffer_bytes += static_cast<long long>(s);
    slot<buffer_sub_fn>()(t, o, s, d);
  }
  static void HUSH_GLAPI counted_tex_image(hgl::gl_enum t, hgl::gl_int l, hgl::gl_int i,
                                           hgl::gl_sizei w, hgl::gl_sizei h, hgl::gl_int b,
                                           hgl::gl_enum f, hgl::gl_enum ty, const void* d) {
    if (d) {
      ++uploaded().calls;
      uploaded().texels += static_cast<long long>(w) * h;
    }
    slot<tex_image_fn>()(t, l, i, w, h, b, f, ty, d);
  }
  static void HUSH_GLAPI counted_tex_sub(hgl::gl_enum t, hgl::gl_int l, hgl::gl_int x,
                                         hgl::gl_int y, hgl::gl_sizei w, hgl::gl_sizei h,
                                         hgl::gl_enum f, hgl::gl_enum ty, const void* d) {
    ++uploaded().calls;
    uploaded().texels += static_cast<long long>(w) * h;
    slot<tex_sub_fn>()(t, l, x, y, w, h, f, ty, d);
  }
  using get_buffer_fn = void(HUSH_GLAPI*)(hgl::gl_enum, hgl::gl_intptr, hgl::gl_sizeiptr, void*);
  using read_pixels_fn = void(HUSH_GLAPI*)(hgl::gl_int, hgl::gl_int, hgl::gl_sizei, hgl::gl_sizei,
                                           hgl::gl_enum, hgl::gl_enum, void*);
  using get_tex_fn = void(HUSH_GLAPI*)(hgl::gl_enum, hgl::gl_int, hgl::gl_enum, hgl::gl_enum,
                                       void*);
  using map_fn = void*(HUSH_GLAPI*)(hgl::gl_enum, hgl::gl_intptr, hgl::gl_sizeiptr,
                                    hgl::gl_bitfield);
  static get_buffer_fn& get_buffer() {
    static get_buffer_fn f = nullptr;
    return f;
  }
  static read_pixels_fn& read_pixels() {
    static read_pixels_fn f = nullptr;
    return f;
  }
  static get_tex_fn& get_tex() {
    static get_tex_fn f = nullptr;
    return f;
  }
  static map_fn& map() {
    static map_fn f = nullptr;
    return f;
  }
  static void HUSH_GLAPI counted_get_buffer(hgl::gl_enum t, hgl::gl_intptr o, hgl::gl_sizeiptr s,
                                            void* d) {
    ++count(get_buffer_calls);
    get_buffer()(t, o, s, d);
  }
  static void HUSH_GLAPI counted_read_pixels(hgl::gl_int x, hgl::gl_int y, hgl::gl_sizei w,
                                             hgl::gl_sizei h, hgl::gl_enum f, hgl::gl_enum t,
                                             void* d) {
    ++count(read_pixels_calls);
    read_pixels()(x, y, w, h, f, t, d);
  }
  static void HUSH_GLAPI counted_get_tex(hgl::gl_enum t, hgl::gl_int l, hgl::gl_enum f,
                                         hgl::gl_enum ty, void* d) {
    ++count(get_tex_calls);
    get_tex()(t, l, f, ty, d);
  }
  static void* HUSH_GLAPI counted_map(hgl::gl_enum t, hgl::gl_intptr o, hgl::gl_sizeiptr s,
                                      hgl::gl_bitfield a) {
    ++count(map_calls);
    return map()(t, o, s, a);
  }
  static void* loader(const char* name) {
    const hgl::loader_fn real = headless().context.loader();
    void* p = real(name);
    const std::string n = name;
    auto swap = [&](auto& slot, auto counted) {
      slot = reinterpret_cast<std::remove_reference_t<decltype(slot)>>(p);
      return reinterpret_cast<void*>(counted);
    };
    if (!p) return p;
    if (n == "glGetBufferSubData") return swap(get_buffer(), &counted_get_buffer);
    if (n == "glReadPixels") return swap(read_pixels(), &counted_read_pixels);
    if (n == "glGetTexImage") return swap(get_tex(), &counted_get_tex);
    if (n == "glMapBufferRange") return swap(map(), &counted_map);
    if (n == "glBufferData") return swap(slot<buffer_data_fn>(), &counted_buffer_data);
    if (n == "glBufferSubData") return swap(slot<buffer_sub_fn>(), &counted_buffer_sub);
    if (n == "glTexImage2D") return swap(slot<tex_image_fn>(), &counted_tex_image);
    if (n == "glTexSubImage2D") return swap(slot<tex_sub_fn>(), &counted_tex_sub);
    return p;
  }
};

// A device whose GL calls go through the counting loader.
inline hush::glsl::device& counted_device() {
  headless();
  static hush::glsl::device d(&readback_counter::loader);
  return d;
}

// The test's own GL: textures for the G-buffer and the outputs, and their read-back.
struct test_gl {
  const hgl::gl_api& api = headless().device.gl();
  void(HUSH_GLAPI* TexSubImage2D)(hgl::gl_enum, hgl::gl_int, hgl::gl_int, hgl::gl_int,
                                  hgl::gl_sizei, hgl::gl_sizei, hgl::gl_enum, hgl::gl_enum,
                                  const void*) = nullptr;
  void(HUSH_GLAPI* GetTexImage)(hgl::gl_enum, hgl::gl_int, hgl::gl_enum, hgl::gl_enum,
                                void*) = nullptr;
  test_gl() {
    hgl::gl_api::load(api.loader, TexSubImage2D, "glTexSubImage2D");
    hgl::gl_api::load(api.loader, GetTexImage, "glGetTexImage");
  }
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
    TexSubImage2D(hgl::kGlTexture2d, 0, 0, 0, w, h, layout, type, data);
    api.BindTexture(hgl::kGlTexture2d, 0);
  }
  std::vector<float> read(hgl::gl_uint t, int w, int h) const {
    std::vector<float> v(static_cast<std::size_t>(w) * h);
    api.BindTexture(hgl::kGlTexture2d, t);
    api.PixelStorei(0x0D05, 4);  // GL_PACK_ALIGNMENT
    GetTexImage(hgl::kGlTexture2d, 0, hgl::kGlRedChannel, hgl::kGlFloat, v.data());
    api.BindTexture(hgl::kGlTexture2d, 0);
    api.check("test: reading a texture");
    return v;
  }
};

}  // namespace hush_glsl_test

#endif  // HUSH_TESTS_GLSL_READBACK_COUNTER_HPP

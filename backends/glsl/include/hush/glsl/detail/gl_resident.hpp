// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// What the resident scene-driven paths share (hush/glsl/coherent/frame.hpp,
// hush/glsl/npr_gabor/frame.hpp): the GL entry points and enums beyond gl_api for reading a
// G-buffer from textures (through a GL_NEAREST sampler object, so a texture's own filters and
// mipmaps do not matter) and writing R32F outputs, and the upload of a CPU image view into such
// a texture (the CPU-image paths run the resident pass on uploaded textures).
#ifndef HUSH_GLSL_DETAIL_GL_RESIDENT_HPP
#define HUSH_GLSL_DETAIL_GL_RESIDENT_HPP

#include <cstddef>

#include "hush/core/views.hpp"
#include "hush/glsl/detail/gl.hpp"

namespace hush {
namespace glsl {
namespace detail {

// Khronos gl.xml.
constexpr gl_enum kGlNearestFilter = 0x2600;  // GL_NEAREST
constexpr gl_enum kGlClampToEdge = 0x812F;
constexpr gl_enum kGlWriteOnly = 0x88B9;
constexpr gl_enum kGlR32fFormat = 0x822E;       // GL_R32F
constexpr gl_enum kGlR32uiFormat = 0x8236;      // GL_R32UI
constexpr gl_enum kGlRgb32fFormat = 0x8815;     // GL_RGB32F
constexpr gl_enum kGlRedChannel = 0x1903;       // GL_RED
constexpr gl_enum kGlRedInteger = 0x8D94;       // GL_RED_INTEGER
constexpr gl_enum kGlRgbChannels = 0x1907;      // GL_RGB
constexpr gl_enum kGlUnsignedInt = 0x1405;      // GL_UNSIGNED_INT
constexpr gl_enum kGlUnpackRowLength = 0x0CF2;  // GL_UNPACK_ROW_LENGTH
constexpr gl_enum kGlCopyReadBuffer = 0x8F36;   // GL_COPY_READ_BUFFER
constexpr gl_enum kGlCopyWriteBuffer = 0x8F37;  // GL_COPY_WRITE_BUFFER
constexpr gl_bitfield kGlAllBarrierBits = 0xFFFFFFFFu;

// The entry points of the resident paths beyond gl_api (GL 3.3 - 4.3 core).
struct gl_resident_api {
  void(HUSH_GLAPI* GenSamplers)(gl_sizei, gl_uint*) = nullptr;
  void(HUSH_GLAPI* DeleteSamplers)(gl_sizei, const gl_uint*) = nullptr;
  void(HUSH_GLAPI* BindSampler)(gl_uint, gl_uint) = nullptr;
  void(HUSH_GLAPI* SamplerParameteri)(gl_uint, gl_enum, gl_int) = nullptr;
  void(HUSH_GLAPI* BindImageTexture)(gl_uint, gl_uint, gl_int, unsigned char, gl_int, gl_enum,
                                     gl_enum) = nullptr;
  void(HUSH_GLAPI* TexSubImage2D)(gl_enum, gl_int, gl_int, gl_int, gl_sizei, gl_sizei, gl_enum,
                                  gl_enum, const void*) = nullptr;
  void(HUSH_GLAPI* CopyBufferSubData)(gl_enum, gl_enum, gl_intptr, gl_intptr,
                                      gl_sizeiptr) = nullptr;

  explicit gl_resident_api(loader_fn loader) {
    gl_api::load(loader, GenSamplers, "glGenSamplers");
    gl_api::load(loader, DeleteSamplers, "glDeleteSamplers");
    gl_api::load(loader, BindSampler, "glBindSampler");
    gl_api::load(loader, SamplerParameteri, "glSamplerParameteri");
    gl_api::load(loader, BindImageTexture, "glBindImageTexture");
    gl_api::load(loader, TexSubImage2D, "glTexSubImage2D");
    gl_api::load(loader, CopyBufferSubData, "glCopyBufferSubData");
  }

  // A sampler object reading texel for texel (GL_NEAREST, clamped).
  gl_uint nearest_sampler() const {
    gl_uint s = 0;
    GenSamplers(1, &s);
    for (gl_enum p : {kGlTextureMinFilter, kGlTextureMagFilter})
      SamplerParameteri(s, p, static_cast<gl_int>(kGlNearestFilter));
    for (gl_enum p : {kGlTextureWrapS, kGlTextureWrapT})
      SamplerParameteri(s, p, static_cast<gl_int>(kGlClampToEdge));
    return s;
  }
};

// Allocates texture t as w x h of `internal` format (level 0 only).
inline void allocate_texture(const gl_api& gl, gl_uint t, std::size_t w, std::size_t h,
                             gl_enum internal, gl_enum layout, gl_enum type) {
  gl_int previous = 0;
  gl.GetIntegerv(kGlTextureBinding2d, &previous);
  gl.BindTexture(kGlTexture2d, t);
  gl.TexImage2D(kGlTexture2d, 0, static_cast<gl_int>(internal), static_cast<gl_sizei>(w),
                static_cast<gl_sizei>(h), 0, layout, type, nullptr);
  gl.BindTexture(kGlTexture2d, static_cast<gl_uint>(previous));
}

// View v into texture t (allocated at v's size; rows of v.stride elements, one element one
// texel); the texture binding and unpack state are restored.
template <class T>
void upload_view(const gl_api& gl, const gl_resident_api& gr, gl_uint t,
                 const image_view<const T>& v, gl_enum layout, gl_enum type) {
  gl_int previous = 0, row = 0, align = 0;
  gl.GetIntegerv(kGlTextureBinding2d, &previous);
  gl.GetIntegerv(kGlUnpackRowLength, &row);
  gl.GetIntegerv(kGlUnpackAlignment, &align);
  gl.BindTexture(kGlTexture2d, t);
  gl.PixelStorei(kGlUnpackRowLength, static_cast<gl_int>(v.stride));
  gl.PixelStorei(kGlUnpackAlignment, 4);
  gr.TexSubImage2D(kGlTexture2d, 0, 0, 0, static_cast<gl_sizei>(v.width),
                   static_cast<gl_sizei>(v.height), layout, type, v.data);
  gl.PixelStorei(kGlUnpackRowLength, row);
  gl.PixelStorei(kGlUnpackAlignment, align);
  gl.BindTexture(kGlTexture2d, static_cast<gl_uint>(previous));
}

}  // namespace detail
}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_DETAIL_GL_RESIDENT_HPP

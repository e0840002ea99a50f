// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// A noise inside the user's own shader. hush::glsl::shader_for(noise) (declared by each
// noise in hush/glsl/<noise>/shader.hpp) returns a shader_kit: the GLSL functions a
// fragment, vertex or compute shader calls per invocation, and every resource they read
// (the noise's parameters as a std140 uniform block, its tiles and tables as textures),
// each with its GLSL name, binding and layout, so an engine uploads and binds them itself:
//
//   hush::wavelet<3> noise{prm};
//   const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);
//   std::string fs = "#version 430 core\n" + kit.source + my_fragment_shader;
//   // my_fragment_shader calls e.g. hush_wavelet3(p) and hush_wavelet3_filtered(p, dFdx(p), dFdy(p))
//   for (const auto& r : kit.resources) { /* upload r.words at r.binding, see shader_resource */ }
//   // or let hush create and bind the GL objects (a GL 4.3 context current on this thread):
//   hush::glsl::bound_kit bound{loader, kit};   bound.bind();
//
// kit.source has no #version line. Each resource is declared in it with
// `layout(binding = <binding_macro>)`; the macro defaults to shader_resource::binding and the
// engine may #define it before the source to move the resource. Under Vulkan (glslang defines
// VULKAN) the declarations take `set = HUSH_DESCRIPTOR_SET` (default 0); under GLSL ES 3.00,
// which has no binding qualifier, the engine binds them by name. Which GLSL versions
// a kit compiles under is in kit.versions; tests compile every kit with glslangValidator for
// each version named there (tests/glsl/ and each noise's tests).
#ifndef HUSH_GLSL_SHADER_HPP
#define HUSH_GLSL_SHADER_HPP

#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/detail/gl_resident.hpp"  // the texture enums it shares

namespace hush {
namespace glsl {

// What a resource of a kit is in GLSL.
enum class resource_kind {
  uniform_block,   // `layout(std140, binding = B) uniform NAME { ... };`, words = the block's bytes
  storage_buffer,  // `layout(std430, binding = B) readonly buffer NAME { ... };` (GL 4.3, not ES 3.00)
  texture_2d,      // `layout(binding = B) uniform sampler2D NAME;` (or usampler2D), words = texels
  texture_3d,      // `layout(binding = B) uniform sampler3D NAME;`, words = texels
};

// The texel format of a texture resource: GL internal format, and the component count and type
// of its words.
enum class texel_format {
  r32f,     // GL_R32F: one float per texel
  rg32f,    // GL_RG32F
  rgba32f,  // GL_RGBA32F
  r32ui,    // GL_R32UI: one uint per texel (read with texelFetch on a usampler)
};

inline int texel_components(texel_format f) {
  return f == texel_format::rg32f ? 2 : f == texel_format::rgba32f ? 4 : 1;
}

// One resource a kit's functions read.
struct shader_resource {
  std::string name;           // its GLSL name: the block's name or the sampler's
  resource_kind kind = resource_kind::uniform_block;
  unsigned binding = 0;       // the binding (texture unit for samplers) the source uses by default
  std::string binding_macro;  // #define this before kit.source to use another binding
  std::string layout;         // its layout in words: the block's members and offsets, or the
                              // texel format, size, filtering and wrap, and what a texel holds
  // The contents as 32-bit words: floats by their bits, uints as they are. Blocks and buffers:
  // the std140 / std430 bytes. Textures: texels with x fastest, then y, then z, each texel
  // texel_components(format) words.
  std::vector<std::uint32_t> words;
  // Textures only.
  texel_format format = texel_format::r32f;
  unsigned width = 0, height = 0, depth = 0;  // depth 0 for 2D textures
  bool linear = false;                        // GL_LINEAR filtering, else GL_NEAREST
  bool repeat = true;                         // GL_REPEAT wrapping, else GL_CLAMP_TO_EDGE
};

// A noise's functions for the user's shader and the resources they read.
struct shader_kit {
  std::string source;                       // GLSL declarations and functions, no #version line
  std::vector<shader_resource> resources;   // in binding order
  std::string versions;  // the GLSL versions it compiles under, e.g. "430 core, Vulkan 450, 300 es"
  std::string usage;     // the functions' signatures and contracts, as a GLSL comment block
  // The resource named `name`, or nullptr.
  const shader_resource* find(const std::string& name) const {
    for (const auto& r : resources)
      if (r.name == name) return &r;
    return nullptr;
  }
};

// Writes a std140 uniform block member by member (GL 4.6 sec. 7.6.2.2): scalars align to 4
// bytes, vec2 to 8, vec3 and vec4 to 16; arrays of scalars or vectors have a 16-byte stride.
// Used by every noise's shader_for, so the block and the GLSL declaration it describes are
// written side by side.
class std140_writer {
 public:
  std140_writer& f(float v) { return put(&v, 1, 1); }
  std140_writer& u(std::uint32_t v) { return put(&v, 1, 1); }
  std140_writer& i(std::int32_t v) { return put(&v, 1, 1); }
  std140_writer& vec2(float x, float y) { const float v[2] = {x, y}; return put(v, 2, 2); }
  std140_writer& vec3(float x, float y, float z) {
    const float v[3] = {x, y, z};
    return put(v, 3, 4);
  }
  std140_writer& vec4(float x, float y, float z, float w) {
    const float v[4] = {x, y, z, w};
    return put(v, 4, 4);
  }
  std140_writer& uvec2(std::uint32_t x, std::uint32_t y) {
    const std::uint32_t v[2] = {x, y};
    return put(v, 2, 2);
  }
  std140_writer& uvec3(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    const std::uint32_t v[3] = {x, y, z};
    return put(v, 3, 4);
  }
  std140_writer& uvec4(std::uint32_t x, std::uint32_t y, std::uint32_t z, std::uint32_t w) {
    const std::uint32_t v[4] = {x, y, z, w};
    return put(v, 4, 4);
  }
  // An array element of a float array: each element takes a 16-byte slot.
  std140_writer& f_array(const float* v, std::size_t n) {
    for (std::size_t k = 0; k < n; ++k) vec4(v[k], 0.0f, 0.0f, 0.0f);
    return *this;
  }
  // The block's words, padded to 16 bytes (a block's size is a multiple of its alignment).
  std::vector<std::uint32_t> words() const {
    std::vector<std::uint32_t> w = words_;
    while (w.size() % 4u != 0u) w.push_back(0u);
    return w;
  }
  std::size_t offset_bytes() const { return words_.size() * 4u; }

 private:
  template <class T>
  std140_writer& put(const T* v, std::size_t n, std::size_t align_words) {
    while (words_.size() % align_words != 0u) words_.push_back(0u);
    for (std::size_t k = 0; k < n; ++k) {
      std::uint32_t w;
      std::memcpy(&w, &v[k], sizeof w);
      words_.push_back(w);
    }
    return *this;
  }
  std::vector<std::uint32_t> words_;
};

// The bits of a float, for texture words.
inline std::uint32_t float_word(float v) {
  std::uint32_t w;
  std::memcpy(&w, &v, sizeof w);
  return w;
}

// The declaration prefix every kit resource uses: `layout(<packing>binding = MACRO)` in GL,
// with `set = HUSH_DESCRIPTOR_SET` under Vulkan, and the #ifndef that gives MACRO its default.
// GLSL ES 3.00 has no binding qualifier: there the block keeps only its packing and the engine
// binds by name (glUniformBlockBinding, glUniform1i for samplers). packing: "std140" for
// blocks, "" for samplers.
inline std::string resource_layout(const std::string& macro, unsigned binding,
                                   const std::string& packing) {
  const std::string sep = packing.empty() ? "" : packing + ", ";
  return "#ifndef " + macro + "\n#define " + macro + " " + std::to_string(binding) +
         "\n#endif\n#if defined(VULKAN)\nlayout(" + sep + "set = HUSH_DESCRIPTOR_SET, binding = " +
         macro + ")\n#elif defined(GL_ES) && __VERSION__ < 310\n" +
         (packing.empty() ? std::string() : "layout(" + packing + ")\n") + "#else\nlayout(" +
         sep + "binding = " + macro + ")\n#endif\n";
}

// Once per shader: the descriptor set under Vulkan and ES's default precisions.
constexpr const char* kShaderPrelude = R"glsl(
#ifndef HUSH_SHADER_PRELUDE
#define HUSH_SHADER_PRELUDE
#ifndef HUSH_DESCRIPTOR_SET
#define HUSH_DESCRIPTOR_SET 0
#endif
#ifdef GL_ES
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler3D;
precision highp usampler2D;
#endif
#endif
)glsl";

namespace detail {
constexpr gl_enum kGlTexture3d = 0x806F;
constexpr gl_enum kGlTextureWrapR = 0x8072;
constexpr gl_enum kGlRg32fFormat = 0x8230;
constexpr gl_enum kGlRedFormat = 0x1903;
constexpr gl_enum kGlRgFormat = 0x8227;
}  // namespace detail

// GL objects holding a kit's resources, created from the kit's words on construction (a GL
// 4.3 context current on this thread; loader as hush::glsl::device takes it) and deleted on
// destruction. bind() binds each at its default binding: blocks to GL_UNIFORM_BUFFER,
// buffers to GL_SHADER_STORAGE_BUFFER, textures to texture unit `binding`. hush's own device
// binds kits through this class. Throws std::runtime_error on a GL error.
class bound_kit {
 public:
  bound_kit(detail::loader_fn loader, const shader_kit& kit) : gl_(loader) {
    detail::gl_api::load(loader, TexImage3D_, "glTexImage3D");
    for (const auto& r : kit.resources) add(r);
    gl_.check("hush::glsl::bound_kit: uploading a kit");
  }
  bound_kit(const bound_kit&) = delete;
  bound_kit& operator=(const bound_kit&) = delete;
  ~bound_kit() {
    for (const auto& o : objects_) {
      if (o.texture)
        gl_.DeleteTextures(1, &o.id);
      else
        gl_.DeleteBuffers(1, &o.id);
    }
  }

  // Binds every resource at its binding (see the class comment).
  void bind() const {
    for (const auto& o : objects_) {
      if (o.texture) {
        gl_.ActiveTexture(detail::kGlTexture0 + o.binding);
        gl_.BindTexture(o.target, o.id);
      } else {
        gl_.BindBufferBase(o.target, o.binding, o.id);
      }
    }
    gl_.ActiveTexture(detail::kGlTexture0);
    gl_.check("hush::glsl::bound_kit::bind");
  }

  // The GL name of the resource at index i of the kit's resources (a buffer or a texture).
  detail::gl_uint object(std::size_t i) const { return objects_.at(i).id; }

 private:
  struct object_t {
    detail::gl_uint id = 0;
    detail::gl_enum target = 0;
    unsigned binding = 0;
    bool texture = false;
  };

  void add(const shader_resource& r) {
    object_t o;
    o.binding = r.binding;
    if (r.kind == resource_kind::uniform_block || r.kind == resource_kind::storage_buffer) {
      o.target = r.kind == resource_kind::uniform_block ? detail::kGlUniformBuffer
                                                        : detail::kGlShaderStorageBuffer;
      gl_.GenBuffers(1, &o.id);
      objects_.push_back(o);
      gl_.BindBuffer(o.target, o.id);
      gl_.BufferData(o.target, static_cast<detail::gl_sizeiptr>(r.words.size() * 4u),
                     r.words.data(), detail::kGlStaticDraw);
      gl_.BindBuffer(o.target, 0u);
      return;
    }
    o.texture = true;
    o.target = r.kind == resource_kind::texture_3d ? detail::kGlTexture3d : detail::kGlTexture2d;
    gl_.GenTextures(1, &o.id);
    objects_.push_back(o);
    gl_.BindTexture(o.target, o.id);
    detail::gl_enum internal = detail::kGlR32fFormat, format = detail::kGlRedFormat,
                    type = detail::kGlFloat;
    switch (r.format) {
      case texel_format::r32f:
        break;
      case texel_format::rg32f:
        internal = detail::kGlRg32fFormat;
        format = detail::kGlRgFormat;
        break;
      case texel_format::rgba32f:
        internal = detail::kGlRgba32f;
        format = detail::kGlRgba;
        break;
      case texel_format::r32ui:
        internal = detail::kGlR32uiFormat;
        format = detail::kGlRedInteger;
        type = detail::kGlUnsignedInt;
        break;
    }
    gl_.PixelStorei(detail::kGlUnpackAlignment, 4);
    const auto w = static_cast<detail::gl_sizei>(r.width);
    const auto h = static_cast<detail::gl_sizei>(r.height);
    if (r.kind == resource_kind::texture_3d)
      TexImage3D_(o.target, 0, static_cast<detail::gl_int>(internal), w, h,
                  static_cast<detail::gl_sizei>(r.depth), 0, format, type, r.words.data());
    else
      gl_.TexImage2D(o.target, 0, static_cast<detail::gl_int>(internal), w, h, 0, format, type,
                     r.words.data());
    // Integer textures take nearest filtering only.
    const auto filter = static_cast<detail::gl_int>(
        r.linear && r.format != texel_format::r32ui ? detail::kGlLinear
                                                    : detail::kGlNearestFilter);
    const auto wrap =
        static_cast<detail::gl_int>(r.repeat ? detail::kGlRepeat : detail::kGlClampToEdge);
    gl_.TexParameteri(o.target, detail::kGlTextureMinFilter, filter);
    gl_.TexParameteri(o.target, detail::kGlTextureMagFilter, filter);
    gl_.TexParameteri(o.target, detail::kGlTextureWrapS, wrap);
    gl_.TexParameteri(o.target, detail::kGlTextureWrapT, wrap);
    if (r.kind == resource_kind::texture_3d)
      gl_.TexParameteri(o.target, detail::kGlTextureWrapR, wrap);
    gl_.BindTexture(o.target, 0u);
  }

  detail::gl_api gl_;
  void(HUSH_GLAPI* TexImage3D_)(detail::gl_enum, detail::gl_int, detail::gl_int, detail::gl_sizei,
                                detail::gl_sizei, detail::gl_sizei, detail::gl_int,
                                detail::gl_enum, detail::gl_enum, const void*) = nullptr;
  std::vector<object_t> objects_;
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_SHADER_HPP

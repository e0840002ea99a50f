// hush — test scenes: the OpenGL G-buffer rasterizer (see raster_gl.hpp).
#define GL_GLEXT_PROTOTYPES 1  // libOSMesa exports the GL 4.5 entry points
#include "raster_gl.hpp"

#include <GL/gl.h>
#include <GL/glext.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "hush/core/error.hpp"
#include "hush/glsl/osmesa_context.hpp"
#include "raster_cpu.hpp"

namespace hush_tools {
namespace scene {
namespace {

// The render targets, in draw-buffer order; the shaders' `location`s are these.
enum target : int {
  kPositionDepth,    // xyz object-space position, w linear depth
  kNormal,           // xyz
  kBarycentric,      // xyz
  kVelocity,         // xyz
  kForwardVelocity,  // xyz: to frame i + 1
  kUv,               // xy
  kJacobian,         // du/dx, du/dy, dv/dx, dv/dy
  kIds,              // RG32UI: object id, triangle id
  kTargets
};

const char* const kVertexShader = R"(#version 450 core
in vec3 a_position;  // locations: queried by name (upload)
in vec3 a_normal;
in vec2 a_uv;
in vec3 a_corner;  // the vertex's barycentric corner
uniform mat4 u_clip_from_object;
uniform mat4 u_prev_clip_from_object;
uniform mat4 u_next_clip_from_object;
uniform mat3 u_normal_to_world;
out vec3 v_position;
out vec3 v_normal;
out vec2 v_uv;
out vec3 v_barycentric;
out vec4 v_prev_clip;
out vec4 v_next_clip;
out float v_depth;
void main() {
  vec4 clip = u_clip_from_object * vec4(a_position, 1.0);
  gl_Position = clip;
  v_position = a_position;
  v_normal = u_normal_to_world * a_normal;
  v_uv = a_uv;
  v_barycentric = a_corner;
  v_prev_clip = u_prev_clip_from_object * vec4(a_position, 1.0);
  v_next_clip = u_next_clip_from_object * vec4(a_position, 1.0);
  v_depth = clip.w;
}
)";

const char* const kFragmentShader = R"(
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
in vec3 v_barycentric;
in vec4 v_prev_clip;
in vec4 v_next_clip;
in float v_depth;
uniform uint u_object_id;
uniform vec2 u_size;
uniform bool u_first_frame;
layout(location = TARGET_POSITION_DEPTH) out vec4 o_position_depth;
layout(location = TARGET_NORMAL) out vec4 o_normal;
layout(location = TARGET_BARYCENTRIC) out vec4 o_barycentric;
layout(location = TARGET_VELOCITY) out vec4 o_velocity;
layout(location = TARGET_FORWARD_VELOCITY) out vec4 o_forward_velocity;
layout(location = TARGET_UV) out vec4 o_uv;
layout(location = TARGET_JACOBIAN) out vec4 o_jacobian;
layout(location = TARGET_IDS) out uvec2 o_ids;
void main() {
  o_position_depth = vec4(v_position, v_depth);
  o_normal = vec4(normalize(v_normal), 0.0);
  o_barycentric = vec4(v_barycentric, 0.0);
  // Screen position with y down (G-buffer row 0 at the top; GL's row 0 is the bottom).
  vec2 p = vec2(gl_FragCoord.x, u_size.y - gl_FragCoord.y);
  vec3 velocity = vec3(0.0);
  if (!u_first_frame) {
    if (v_prev_clip.w > 0.0) {
      vec2 ndc = v_prev_clip.xy / v_prev_clip.w;
      vec2 prev = vec2((ndc.x + 1.0) * 0.5 * u_size.x, (1.0 - ndc.y) * 0.5 * u_size.y);
      velocity = vec3(p - prev, v_depth - v_prev_clip.w);
    } else {
      velocity = vec3(uintBitsToFloat(0x7fc00000u));  // no previous position: NaN
    }
  }
  o_velocity = vec4(velocity, 0.0);
  // Forward: where the point is in frame i + 1; NaN when not in front of that camera.
  vec3 forward = vec3(uintBitsToFloat(0x7fc00000u));
  if (v_next_clip.w > 0.0) {
    vec2 ndc = v_next_clip.xy / v_next_clip.w;
    vec2 next = vec2((ndc.x + 1.0) * 0.5 * u_size.x, (1.0 - ndc.y) * 0.5 * u_size.y);
    forward = vec3(next - p, v_next_clip.w - v_depth);
  }
  o_forward_velocity = vec4(forward, 0.0);
  o_uv = vec4(v_uv, 0.0, 0.0);
  // (u, v, 1) / w is affine in screen space, so its fine derivatives (differences
  // within the 2x2 quad) are exact. Built from the perspective-correct uv and depth:
  // noperspective varyings come out NaN on triangles llvmpipe clips at the guard band.
  // Screen y is down, GL's y is up.
  vec3 q = vec3(v_uv, 1.0) / v_depth, qx = dFdxFine(q), qy = -dFdyFine(q);
  vec2 du_dxy = (vec2(qx.x, qy.x) * q.z - q.x * vec2(qx.z, qy.z)) / (q.z * q.z);
  vec2 dv_dxy = (vec2(qx.y, qy.y) * q.z - q.y * vec2(qx.z, qy.z)) / (q.z * q.z);
  o_jacobian = vec4(du_dxy, dv_dxy);
  o_ids = uvec2(u_object_id, uint(gl_PrimitiveID));
}
)";

// The fragment shader's preamble: the render-target locations, written from the enum
// (one source of truth, as DESIGN.md asks).
std::string fragment_source() {
  const char* const names[kTargets] = {
      "TARGET_POSITION_DEPTH",   "TARGET_NORMAL", "TARGET_BARYCENTRIC", "TARGET_VELOCITY",
      "TARGET_FORWARD_VELOCITY", "TARGET_UV",     "TARGET_JACOBIAN",    "TARGET_IDS"};
  std::string text = "#version 450 core\n";
  for (int t = 0; t < kTargets; ++t)
    text += std::string("#define ") + names[t] + " " + std::to_string(t) + "\n";
  return text + kFragmentShader;
}

GLuint compile(GLenum type, const char* source) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[4096] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error(std::string("raster_gl: shader compilation failed: ") + log);
  }
  return shader;
}

void check_gl(const char* where) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR)
    throw std::runtime_error(std::string("raster_gl: GL error 0x") + std::to_string(e) + " in " +
                             where);
}

struct gpu_mesh {
  std::shared_ptr<const mesh> shape;  // kept alive: the cache key is its address
  GLuint vao = 0, vbo = 0;
  GLsizei vertices = 0;
};

// Unindexed vertex layout: position, normal, uv, barycentric corner.
constexpr int kFloatsPerVertex = 3 + 3 + 2 + 3;

}  // namespace

struct gl_rasterizer::impl {
  hush::glsl::osmesa_context context;
  GLuint program = 0, fbo = 0, depth_buffer = 0;
  GLuint targets[kTargets] = {};
  int width = 0, height = 0;
  std::map<const mesh*, gpu_mesh> meshes;
  GLint u_clip = -1, u_prev_clip = -1, u_next_clip = -1, u_normal = -1, u_object = -1, u_size = -1,
        u_first = -1;

  impl() {
    const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader);
    const std::string fragment = fragment_source();
    const GLuint fs = compile(GL_FRAGMENT_SHADER, fragment.c_str());
    program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
      char log[4096] = {};
      glGetProgramInfoLog(program, sizeof log, nullptr, log);
      throw std::runtime_error(std::string("raster_gl: program link failed: ") + log);
    }
    u_clip = glGetUniformLocation(program, "u_clip_from_object");
    u_prev_clip = glGetUniformLocation(program, "u_prev_clip_from_object");
    u_next_clip = glGetUniformLocation(program, "u_next_clip_from_object");
    u_normal = glGetUniformLocation(program, "u_normal_to_world");
    u_object = glGetUniformLocation(program, "u_object_id");
    u_size = glGetUniformLocation(program, "u_size");
    u_first = glGetUniformLocation(program, "u_first_frame");
    check_gl("setup");
  }

  ~impl() {
    for (auto& m : meshes) {
      glDeleteBuffers(1, &m.second.vbo);
      glDeleteVertexArrays(1, &m.second.vao);
    }
    release_targets();
    if (program) glDeleteProgram(program);
  }
  impl(const impl&) = delete;
  impl& operator=(const impl&) = delete;

  void release_targets() {
    if (fbo) glDeleteFramebuffers(1, &fbo);
    if (depth_buffer) glDeleteRenderbuffers(1, &depth_buffer);
    glDeleteTextures(kTargets, targets);
    fbo = depth_buffer = 0;
    for (GLuint& t : targets) t = 0;
  }

  void resize(int w, int h) {
    if (w == width && h == height && fbo) return;
    release_targets();
    width = w;
    height = h;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenTextures(kTargets, targets);
    GLenum buffers[kTargets];
    for (int t = 0; t < kTargets; ++t) {
      glBindTexture(GL_TEXTURE_2D, targets[t]);
      glTexStorage2D(GL_TEXTURE_2D, 1, t == kIds ? GL_RG32UI : GL_RGBA32F, w, h);
      glFramebufferTexture2D(GL_FRAMEBUFFER, static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + t),
                             GL_TEXTURE_2D, targets[t], 0);
      buffers[t] = static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + t);
    }
    glGenRenderbuffers(1, &depth_buffer);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_buffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer);
    glDrawBuffers(kTargets, buffers);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("raster_gl: the G-buffer framebuffer is incomplete");
    check_gl("resize");
  }

  const gpu_mesh& upload(const std::shared_ptr<const mesh>& shape) {
    auto it = meshes.find(shape.get());
    if (it != meshes.end()) return it->second;
    const mesh& m = *shape;
    std::vector<float> data;
    data.reserve(m.indices.size() * kFloatsPerVertex);
    for (std::size_t i = 0; i < m.indices.size(); ++i) {
      const std::uint32_t v = m.indices[i];
      const float corner[3] = {i % 3 == 0 ? 1.0f : 0.0f, i % 3 == 1 ? 1.0f : 0.0f,
                               i % 3 == 2 ? 1.0f : 0.0f};
      data.insert(data.end(), {m.positions[v].x, m.positions[v].y, m.positions[v].z, m.normals[v].x,
                               m.normals[v].y, m.normals[v].z, m.uvs[v].x, m.uvs[v].y, corner[0],
                               corner[1], corner[2]});
    }
    gpu_mesh g;
    g.shape = shape;
    g.vertices = static_cast<GLsizei>(m.indices.size());
    // Separate attribute formats (GL 4.3): one buffer binding, attributes at relative
    // offsets. (libOSMesa does not export the 4.5 direct-state-access entry points.)
    glGenVertexArrays(1, &g.vao);
    glBindVertexArray(g.vao);
    glGenBuffers(1, &g.vbo);
    glBindBuffer(GL_ARRAY_BUFFER, g.vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data(),
                 GL_STATIC_DRAW);
    glBindVertexBuffer(0, g.vbo, 0, kFloatsPerVertex * sizeof(float));
    const char* const names[4] = {"a_position", "a_normal", "a_uv", "a_corner"};
    const int sizes[4] = {3, 3, 2, 3};
    GLuint offset = 0;
    for (int a = 0; a < 4; ++a) {
      const GLint location = glGetAttribLocation(program, names[a]);
      if (location < 0)
        throw std::runtime_error(std::string("raster_gl: no attribute ") + names[a]);
      const GLuint l = static_cast<GLuint>(location);
      glEnableVertexAttribArray(l);
      glVertexAttribFormat(l, sizes[a], GL_FLOAT, GL_FALSE,
                           offset * static_cast<GLuint>(sizeof(float)));
      glVertexAttribBinding(l, 0);
      offset += static_cast<GLuint>(sizes[a]);
    }
    check_gl("upload");
    return meshes.emplace(shape.get(), g).first->second;
  }
};

gl_rasterizer::gl_rasterizer() : impl_(new impl) {}
gl_rasterizer::~gl_rasterizer() = default;

std::string gl_rasterizer::renderer() const {
  impl_->context.make_current();
  const auto text = [](GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return text(GL_RENDERER) + "; " + text(GL_VERSION);
}

gbuffer gl_rasterizer::render(const scene& s, int frame, int width, int height) {
  check_render_arguments(frame, width, height);
  impl& d = *impl_;
  d.context.make_current();
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width > max_size || height > max_size)
    throw hush::invalid_argument("render_gl: size exceeds GL_MAX_RENDERBUFFER_SIZE = " +
                                 std::to_string(max_size));
  d.resize(width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, d.fbo);
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  for (int t = 0; t < kTargets; ++t) {
    if (t == kIds) {
      const GLuint none[4] = {0u, 0u, 0u, 0u};
      glClearBufferuiv(GL_COLOR, t, none);
    } else {
      glClearBufferfv(GL_COLOR, t, zero);
    }
  }
  const float far_depth = 1.0f;
  glClearBufferfv(GL_DEPTH, 0, &far_depth);

  const int prev_frame = frame > 0 ? frame - 1 : frame;
  if (!s.camera) throw hush::invalid_argument("render: the scene has no camera");
  const camera_pose pose = s.camera(frame), prev_pose = s.camera(prev_frame),
                    next_pose = s.camera(frame + 1);
  check_scene(s, pose);
  check_scene(s, prev_pose);
  check_scene(s, next_pose);
  const glm::dmat4 clip_from_world = projection_matrix(pose, width, height) * view_matrix(pose);
  const glm::dmat4 prev_clip_from_world =
      projection_matrix(prev_pose, width, height) * view_matrix(prev_pose);
  const glm::dmat4 next_clip_from_world =
      projection_matrix(next_pose, width, height) * view_matrix(next_pose);
  glUseProgram(d.program);
  glUniform2f(d.u_size, static_cast<float>(width), static_cast<float>(height));
  glUniform1i(d.u_first, frame == 0 ? 1 : 0);
  for (std::size_t o = 0; o < s.objects.size(); ++o) {
    const object& obj = s.objects[o];
    const gpu_mesh& g = d.upload(obj.shape);
    const glm::dmat4 model = obj.model(frame), prev_model = obj.model(prev_frame),
                     next_model = obj.model(frame + 1);
    const glm::mat4 clip(clip_from_world * model), prev_clip(prev_clip_from_world * prev_model),
        next_clip(next_clip_from_world * next_model);
    const glm::mat3 normal(glm::transpose(glm::inverse(glm::dmat3(model))));
    glUniformMatrix4fv(d.u_clip, 1, GL_FALSE, glm::value_ptr(clip));
    glUniformMatrix4fv(d.u_prev_clip, 1, GL_FALSE, glm::value_ptr(prev_clip));
    glUniformMatrix4fv(d.u_next_clip, 1, GL_FALSE, glm::value_ptr(next_clip));
    glUniformMatrix3fv(d.u_normal, 1, GL_FALSE, glm::value_ptr(normal));
    glUniform1ui(d.u_object, static_cast<GLuint>(o + 1));
    if (obj.shape->closed)
      glEnable(GL_CULL_FACE);
    else
      glDisable(GL_CULL_FACE);
    glBindVertexArray(g.vao);
    glDrawArrays(GL_TRIANGLES, 0, g.vertices);
  }
  check_gl("draw");

  // Read back (GL rows bottom-up; the G-buffer's row 0 is the top).
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<float> rgba[kTargets - 1];
  std::vector<GLuint> ids(2 * n);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  for (int t = 0; t < kTargets; ++t) {
    glReadBuffer(static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + t));
    if (t == kIds) {
      glReadPixels(0, 0, width, height, GL_RG_INTEGER, GL_UNSIGNED_INT, ids.data());
    } else {
      rgba[t].resize(4 * n);
      glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rgba[t].data());
    }
  }
  check_gl("read back");
  gbuffer g = make_background(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t dst = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                              static_cast<std::size_t>(x);
      const std::size_t src =
          static_cast<std::size_t>(height - 1 - y) * static_cast<std::size_t>(width) +
          static_cast<std::size_t>(x);
      if (ids[2 * src] == 0u) continue;
      g.object_id[dst] = ids[2 * src];
      g.triangle_id[dst] = ids[2 * src + 1];
      g.depth[dst] = rgba[kPositionDepth][4 * src + 3];
      for (std::size_t c = 0; c < 3; ++c) {
        g.position[3 * dst + c] = rgba[kPositionDepth][4 * src + c];
        g.normal[3 * dst + c] = rgba[kNormal][4 * src + c];
        g.barycentric[3 * dst + c] = rgba[kBarycentric][4 * src + c];
        g.velocity[3 * dst + c] = rgba[kVelocity][4 * src + c];
        g.forward_velocity[3 * dst + c] = rgba[kForwardVelocity][4 * src + c];
      }
      for (std::size_t c = 0; c < 2; ++c) g.uv[2 * dst + c] = rgba[kUv][4 * src + c];
      for (std::size_t c = 0; c < 4; ++c) g.uv_jacobian[4 * dst + c] = rgba[kJacobian][4 * src + c];
    }
  return g;
}

gbuffer render_gl(const scene& s, int frame, int width, int height) {
  gl_rasterizer r;
  return r.render(s, frame, width, height);
}

}  // namespace scene
}  // namespace hush_tools

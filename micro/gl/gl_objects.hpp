#pragma once
// RAII owners for GL objects: every buffer, texture, framebuffer, program and query
// the suite creates is released when its owner goes out of scope.
#include <utility>

#include "gl/gl.hpp"

namespace oitbench::gl {

template <void (*Delete)(GLuint)>
class Handle {
 public:
  Handle() = default;
  explicit Handle(GLuint id) : id_(id) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  ~Handle() { reset(); }
  void reset() {
    if (id_) Delete(id_);
    id_ = 0;
  }
  GLuint get() const { return id_; }
  explicit operator bool() const { return id_ != 0; }

 private:
  GLuint id_ = 0;
};

inline void delete_buffer(GLuint id) { glDeleteBuffers(1, &id); }
inline void delete_texture(GLuint id) { glDeleteTextures(1, &id); }
inline void delete_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
inline void delete_renderbuffer(GLuint id) { glDeleteRenderbuffers(1, &id); }
inline void delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
inline void delete_query(GLuint id) { glDeleteQueries(1, &id); }
inline void delete_program(GLuint id) { glDeleteProgram(id); }
inline void delete_shader(GLuint id) { glDeleteShader(id); }

using Buffer = Handle<delete_buffer>;
using Texture = Handle<delete_texture>;
using Framebuffer = Handle<delete_framebuffer>;
using Renderbuffer = Handle<delete_renderbuffer>;
using VertexArray = Handle<delete_vertex_array>;
using Query = Handle<delete_query>;
using Program = Handle<delete_program>;
using Shader = Handle<delete_shader>;

// One object from a glCreate* entry point, which takes its leading arguments (a texture's or a
// query's target), a count and where to write the names.
template <class Object, class Create, class... Leading>
Object create_one(Create create, Leading... leading) {
  GLuint id = 0;
  create(leading..., 1, &id);
  return Object(id);
}

inline Buffer make_buffer() { return create_one<Buffer>(glCreateBuffers); }
inline Texture make_texture(GLenum target) { return create_one<Texture>(glCreateTextures, target); }
inline Framebuffer make_framebuffer() { return create_one<Framebuffer>(glCreateFramebuffers); }
inline Renderbuffer make_renderbuffer() { return create_one<Renderbuffer>(glCreateRenderbuffers); }
inline VertexArray make_vertex_array() { return create_one<VertexArray>(glCreateVertexArrays); }
inline Query make_query(GLenum target) { return create_one<Query>(glCreateQueries, target); }

}  // namespace oitbench::gl

#include "gl/shader.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "gl/embedded_shaders.h"
#include "gl/gl_error.h"

namespace tspgl {

namespace {

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw tsp::IoError(path.string() + ": cannot read shader file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw tsp::IoError(path.string() + ": cannot read shader file");
  return text.str();
}

template <typename GetLength, typename GetLog>
std::string info_log(GLuint id, GetLength get_length, GetLog get_log) {
  GLint length = 0;
  get_length(id, GL_INFO_LOG_LENGTH, &length);
  if (length <= 1) return "(no info log)";
  std::vector<char> log(std::size_t(length), '\0');
  get_log(id, length, nullptr, log.data());
  return std::string(log.data());
}

GLuint compile(const GlApi& gl, GLenum stage, const std::string& label, std::string_view source) {
  const GLuint shader = gl.CreateShader(stage);
  if (shader == 0) throw tsp::GlError(label + ": glCreateShader failed");
  const char* text = source.data();
  const auto length = GLint(source.size());
  gl.ShaderSource(shader, 1, &text, &length);
  gl.CompileShader(shader);
  GLint ok = GL_FALSE;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(shader, gl.GetShaderiv, gl.GetShaderInfoLog);
    gl.DeleteShader(shader);
    const char* kind = stage == GL_VERTEX_SHADER ? "vertex" : "fragment";
    throw tsp::GlError(label + ": " + kind + " shader does not compile:\n" + log);
  }
  return shader;
}

}  // namespace

std::string shader_source(const std::string& name) {
  const char* dir = std::getenv(kShaderDirEnv);
  if (dir && *dir) return read_file(std::filesystem::path(dir) / name);
  for (const EmbeddedShader& s : embedded_shaders())
    if (name == s.name) return s.source;
  std::string known;
  for (const EmbeddedShader& s : embedded_shaders()) known += std::string(" ") + s.name;
  throw tsp::UsageError("no shader named '" + name + "' in shaders/; embedded:" + known);
}

Program::~Program() {
  if (id_) gl_->DeleteProgram(id_);
}

Program& Program::operator=(Program&& o) noexcept {
  if (this != &o) {
    if (id_) gl_->DeleteProgram(id_);
    gl_ = o.gl_;
    id_ = o.id_;
    o.id_ = 0;
  }
  return *this;
}

Program build_program(const GlApi& gl, const std::string& label, std::string_view vertex_source,
                      std::string_view fragment_source) {
  const GLuint vs = compile(gl, GL_VERTEX_SHADER, label, vertex_source);
  GLuint fs = 0;
  try {
    fs = compile(gl, GL_FRAGMENT_SHADER, label, fragment_source);
  } catch (...) {
    gl.DeleteShader(vs);
    throw;
  }
  Program program(gl, gl.CreateProgram());
  gl.AttachShader(program.id(), vs);
  gl.AttachShader(program.id(), fs);
  gl.LinkProgram(program.id());
  // The program keeps the compiled code; the shader objects are no longer needed.
  gl.DetachShader(program.id(), vs);
  gl.DetachShader(program.id(), fs);
  gl.DeleteShader(vs);
  gl.DeleteShader(fs);
  GLint ok = GL_FALSE;
  gl.GetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok)
    throw tsp::GlError(label + ": program does not link:\n" +
                       info_log(program.id(), gl.GetProgramiv, gl.GetProgramInfoLog));
  check_gl(gl, label + " program build");
  return program;
}

Program load_program(const GlApi& gl, const std::string& vertex_name,
                     const std::string& fragment_name) {
  return build_program(gl, vertex_name + " + " + fragment_name, shader_source(vertex_name),
                       shader_source(fragment_name));
}

Program load_program_with(const GlApi& gl, const std::string& vertex_name,
                          const std::string& fragment_name,
                          const std::vector<std::string>& includes, const std::string& prelude) {
  std::string frag = shader_source(fragment_name), inserted = prelude;
  for (const std::string& name : includes) inserted += shader_source(name);
  const std::size_t eol = frag.find('\n');
  frag.insert(eol == std::string::npos ? frag.size() : eol + 1, inserted);
  return build_program(gl, vertex_name + " + " + fragment_name, shader_source(vertex_name), frag);
}

}  // namespace tspgl

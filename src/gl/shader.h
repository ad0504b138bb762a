// GLSL programs: sources embedded at build time from shaders/ (or read from $TSPPLAY_SHADER_DIR
// while developing), compiled and linked with the info log in every error.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "gl/gl_api.h"

namespace tspgl {

/// Environment variable naming a directory whose shader files replace the embedded ones.
inline constexpr const char* kShaderDirEnv = "TSPPLAY_SHADER_DIR";

/// Text of shader file `name` (e.g. "solid.frag"): from $TSPPLAY_SHADER_DIR/name when that
/// variable is set and non-empty, else the copy embedded from shaders/. Throws tsp::IoError when
/// the override file cannot be read, tsp::UsageError for an unknown name.
std::string shader_source(const std::string& name);

/// A linked GL program; deletes it on destruction (with its context current). Move-only.
class Program {
 public:
  /// An empty program (id 0).
  Program() = default;
  /// Takes ownership of program id of the context whose functions are gl.
  Program(const GlApi& gl, GLuint id) : gl_(&gl), id_(id) {}
  /// Deletes the program (its context must be current).
  ~Program();
  /// Takes o's program, leaving o empty.
  Program(Program&& o) noexcept : gl_(o.gl_), id_(o.id_) { o.id_ = 0; }
  /// Deletes this program and takes o's.
  Program& operator=(Program&& o) noexcept;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  /// The GL program name (0 when empty).
  GLuint id() const { return id_; }
  /// glUseProgram on this program.
  void use() const { gl_->UseProgram(id_); }
  /// Location of a uniform; −1 when the program has no active uniform of that name.
  GLint uniform(const char* name) const { return gl_->GetUniformLocation(id_, name); }

 private:
  const GlApi* gl_ = nullptr;
  GLuint id_ = 0;
};

/// Compiles and links a vertex and a fragment shader. `label` names the program in errors.
/// Throws tsp::GlError carrying the compiler's or linker's info log.
Program build_program(const GlApi& gl, const std::string& label, std::string_view vertex_source,
                      std::string_view fragment_source);

/// build_program on the shader files vertex_name and fragment_name (see shader_source).
/// Throws tsp::GlError, tsp::IoError, tsp::UsageError.
Program load_program(const GlApi& gl, const std::string& vertex_name,
                     const std::string& fragment_name);

/// build_program on vertex_name and fragment_name with `prelude` (e.g. #define lines) and then
/// the GLSL files `includes`, in order, inserted after the fragment shader's #version line.
/// Throws tsp::GlError, tsp::IoError, tsp::UsageError.
Program load_program_with(const GlApi& gl, const std::string& vertex_name,
                          const std::string& fragment_name,
                          const std::vector<std::string>& includes, const std::string& prelude = "");

}  // namespace tspgl

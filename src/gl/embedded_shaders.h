// The GLSL files of shaders/, compiled into the library by cmake/embed_shaders.cmake.
#pragma once
#include <span>

namespace tspgl {

/// One shader file: its name in shaders/ ("solid.frag") and its text.
struct EmbeddedShader {
  const char* name;
  const char* source;
};

/// Every embedded shader, sorted by name.
std::span<const EmbeddedShader> embedded_shaders();

}  // namespace tspgl

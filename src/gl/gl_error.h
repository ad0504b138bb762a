// The error thrown when OpenGL or a context fails.
#pragma once
#include "tsp/core/error.h"

namespace tsp {

/// An OpenGL context could not be created or made current, a GL entry point is missing, a shader
/// failed to compile or link, or GL reported an error.
class GlError : public Error {
 public:
  using Error::Error;
};

}  // namespace tsp

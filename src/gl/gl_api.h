// Our own OpenGL 3.3 core loader: a table of the GL functions tspplay uses, filled through the
// current context's get-proc-address. Nothing links libGL, so the OSMesa/libGL link-order
// problem cannot arise (docs/rendering.md). To add a function: add one X(...) line below.
#pragma once
#include <GL/glcorearb.h>

#include <string>

namespace tspgl {

// X(PFN type from <GL/glcorearb.h>, name without the "gl" prefix).
#define TSPGL_FUNCTIONS(X)                                       \
  /* state, clearing, read-back */                               \
  X(PFNGLGETERRORPROC, GetError)                                 \
  X(PFNGLGETSTRINGPROC, GetString)                               \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                           \
  X(PFNGLENABLEPROC, Enable)                                     \
  X(PFNGLDISABLEPROC, Disable)                                   \
  X(PFNGLVIEWPORTPROC, Viewport)                                 \
  X(PFNGLCLEARCOLORPROC, ClearColor)                             \
  X(PFNGLCLEARPROC, Clear)                                       \
  X(PFNGLFINISHPROC, Finish)                                     \
  X(PFNGLFLUSHPROC, Flush)                                       \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                           \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                             \
  X(PFNGLREADPIXELSPROC, ReadPixels)                             \
  X(PFNGLDEPTHMASKPROC, DepthMask)                               \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                               \
  X(PFNGLCULLFACEPROC, CullFace)                                 \
  X(PFNGLSCISSORPROC, Scissor)                                   \
  X(PFNGLCOLORMASKPROC, ColorMask)                               \
  /* blending */                                                 \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                               \
  X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)               \
  X(PFNGLBLENDEQUATIONPROC, BlendEquation)                       \
  /* buffers and vertex arrays */                                \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                             \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                       \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                             \
  X(PFNGLBUFFERDATAPROC, BufferData)                             \
  X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                       \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                   \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)             \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                   \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)   \
  X(PFNGLDISABLEVERTEXATTRIBARRAYPROC, DisableVertexAttribArray) \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)           \
  X(PFNGLVERTEXATTRIB4FPROC, VertexAttrib4f)                     \
  /* drawing */                                                  \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                             \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)           \
  X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)           \
  X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                           \
  X(PFNGLMULTIDRAWARRAYSPROC, MultiDrawArrays)                   \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                         \
  /* shaders, programs, uniforms */                              \
  X(PFNGLCREATESHADERPROC, CreateShader)                         \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                         \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                       \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                           \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                 \
  X(PFNGLDELETESHADERPROC, DeleteShader)                         \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                       \
  X(PFNGLATTACHSHADERPROC, AttachShader)                         \
  X(PFNGLDETACHSHADERPROC, DetachShader)                         \
  X(PFNGLBINDATTRIBLOCATIONPROC, BindAttribLocation)             \
  X(PFNGLBINDFRAGDATALOCATIONPROC, BindFragDataLocation)         \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                           \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                         \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)               \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                       \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                             \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)             \
  X(PFNGLGETATTRIBLOCATIONPROC, GetAttribLocation)               \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                               \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                               \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                               \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                               \
  X(PFNGLUNIFORM3IPROC, Uniform3i)                               \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                               \
  X(PFNGLUNIFORM3FVPROC, Uniform3fv)                             \
  X(PFNGLUNIFORM4FVPROC, Uniform4fv)                             \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                 \
  X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv)                 \
  X(PFNGLUNIFORM1IVPROC, Uniform1iv)                             \
  /* textures (1D transfer-function lookup, 3D bricks) */        \
  X(PFNGLGENTEXTURESPROC, GenTextures)                           \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                     \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                           \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                       \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                       \
  X(PFNGLTEXPARAMETERFVPROC, TexParameterfv)                     \
  X(PFNGLTEXIMAGE1DPROC, TexImage1D)                             \
  X(PFNGLTEXSUBIMAGE1DPROC, TexSubImage1D)                       \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                             \
  X(PFNGLTEXIMAGE3DPROC, TexImage3D)                             \
  X(PFNGLTEXSUBIMAGE3DPROC, TexSubImage3D)                       \
  X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D)                       \
  /* framebuffer objects */                                      \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                   \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)             \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                   \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)         \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)   \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)     \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                 \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)           \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                 \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)           \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                   \
  /* timer queries (GPU time per frame) */                       \
  X(PFNGLGENQUERIESPROC, GenQueries)                             \
  X(PFNGLDELETEQUERIESPROC, DeleteQueries)                       \
  X(PFNGLBEGINQUERYPROC, BeginQuery)                             \
  X(PFNGLENDQUERYPROC, EndQuery)                                 \
  X(PFNGLQUERYCOUNTERPROC, QueryCounter)                         \
  X(PFNGLGETQUERYOBJECTIVPROC, GetQueryObjectiv)                 \
  X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)

/// A generic function pointer, as get-proc-address functions return it.
using ProcAddress = void (*)();
/// Looks up a GL entry point by its full name ("glClear"); null when unknown.
using GetProcAddress = ProcAddress (*)(const char* name);

/// The GL 3.3 core functions tspplay calls, named without the "gl" prefix: gl.Clear(...).
struct GlApi {
#define TSPGL_DECLARE(type, name) type name = nullptr;
  TSPGL_FUNCTIONS(TSPGL_DECLARE)
#undef TSPGL_DECLARE
};

/// Fills the table through get_proc (with the context current). Throws tsp::GlError naming every
/// function it could not find.
GlApi load_gl_api(GetProcAddress get_proc);

/// The GL error enum's name ("GL_INVALID_ENUM"), or its hex value when unknown.
std::string gl_error_name(GLenum error);

/// Throws tsp::GlError naming `what` and every pending GL error; does nothing when there is none.
void check_gl(const GlApi& gl, const std::string& what);

}  // namespace tspgl

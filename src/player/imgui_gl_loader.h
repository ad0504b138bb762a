// Our GL loader for Dear ImGui's OpenGL 3 back end, which is compiled with
// IMGUI_IMPL_OPENGL_LOADER_CUSTOM and this header force-included (CMakeLists.txt): Debian's
// ImGui 1.86 ships a loader that stores 54 entry points into a 53-entry table (upstream issue
// 4830), which UBSan reports on every start of the player. Here every entry point the back end
// calls is one named member, loaded by name through the context's get-proc-address; the table
// that loads them is built from the members themselves, so it cannot overrun.
#pragma once
#include <GL/glcorearb.h>

/// The GL entry points the ImGui OpenGL 3 back end calls.
struct TspImGuiGl {
  PFNGLACTIVETEXTUREPROC           ActiveTexture;
  PFNGLATTACHSHADERPROC            AttachShader;
  PFNGLBINDBUFFERPROC              BindBuffer;
  PFNGLBINDSAMPLERPROC             BindSampler;
  PFNGLBINDTEXTUREPROC             BindTexture;
  PFNGLBINDVERTEXARRAYPROC         BindVertexArray;
  PFNGLBLENDEQUATIONPROC           BlendEquation;
  PFNGLBLENDEQUATIONSEPARATEPROC   BlendEquationSeparate;
  PFNGLBLENDFUNCSEPARATEPROC       BlendFuncSeparate;
  PFNGLBUFFERDATAPROC              BufferData;
  PFNGLBUFFERSUBDATAPROC           BufferSubData;
  PFNGLCLEARPROC                   Clear;
  PFNGLCLEARCOLORPROC              ClearColor;
  PFNGLCOMPILESHADERPROC           CompileShader;
  PFNGLCREATEPROGRAMPROC           CreateProgram;
  PFNGLCREATESHADERPROC            CreateShader;
  PFNGLDELETEBUFFERSPROC           DeleteBuffers;
  PFNGLDELETEPROGRAMPROC           DeleteProgram;
  PFNGLDELETESHADERPROC            DeleteShader;
  PFNGLDELETETEXTURESPROC          DeleteTextures;
  PFNGLDELETEVERTEXARRAYSPROC      DeleteVertexArrays;
  PFNGLDETACHSHADERPROC            DetachShader;
  PFNGLDISABLEPROC                 Disable;
  PFNGLDRAWELEMENTSPROC            DrawElements;
  PFNGLDRAWELEMENTSBASEVERTEXPROC  DrawElementsBaseVertex;
  PFNGLENABLEPROC                  Enable;
  PFNGLENABLEVERTEXATTRIBARRAYPROC EnableVertexAttribArray;
  PFNGLGENBUFFERSPROC              GenBuffers;
  PFNGLGENTEXTURESPROC             GenTextures;
  PFNGLGENVERTEXARRAYSPROC         GenVertexArrays;
  PFNGLGETATTRIBLOCATIONPROC       GetAttribLocation;
  PFNGLGETERRORPROC                GetError;
  PFNGLGETINTEGERVPROC             GetIntegerv;
  PFNGLGETPROGRAMINFOLOGPROC       GetProgramInfoLog;
  PFNGLGETPROGRAMIVPROC            GetProgramiv;
  PFNGLGETSHADERINFOLOGPROC        GetShaderInfoLog;
  PFNGLGETSHADERIVPROC             GetShaderiv;
  PFNGLGETSTRINGPROC               GetString;
  PFNGLGETSTRINGIPROC              GetStringi;
  PFNGLGETUNIFORMLOCATIONPROC      GetUniformLocation;
  PFNGLISENABLEDPROC               IsEnabled;
  PFNGLLINKPROGRAMPROC             LinkProgram;
  PFNGLPIXELSTOREIPROC             PixelStorei;
  PFNGLPOLYGONMODEPROC             PolygonMode;
  PFNGLREADPIXELSPROC              ReadPixels;
  PFNGLSCISSORPROC                 Scissor;
  PFNGLSHADERSOURCEPROC            ShaderSource;
  PFNGLTEXIMAGE2DPROC              TexImage2D;
  PFNGLTEXPARAMETERIPROC           TexParameteri;
  PFNGLUNIFORM1IPROC               Uniform1i;
  PFNGLUNIFORMMATRIX4FVPROC        UniformMatrix4fv;
  PFNGLUSEPROGRAMPROC              UseProgram;
  PFNGLVERTEXATTRIBPOINTERPROC     VertexAttribPointer;
  PFNGLVIEWPORTPROC                Viewport;
};

/// The back end's entry points (filled by tsp_imgui_gl_load). Use from the GL thread only.
extern TspImGuiGl tsp_imgui_gl;

#include "player/imgui_gl_load.h"

#define glActiveTexture tsp_imgui_gl.ActiveTexture
#define glAttachShader tsp_imgui_gl.AttachShader
#define glBindBuffer tsp_imgui_gl.BindBuffer
#define glBindSampler tsp_imgui_gl.BindSampler
#define glBindTexture tsp_imgui_gl.BindTexture
#define glBindVertexArray tsp_imgui_gl.BindVertexArray
#define glBlendEquation tsp_imgui_gl.BlendEquation
#define glBlendEquationSeparate tsp_imgui_gl.BlendEquationSeparate
#define glBlendFuncSeparate tsp_imgui_gl.BlendFuncSeparate
#define glBufferData tsp_imgui_gl.BufferData
#define glBufferSubData tsp_imgui_gl.BufferSubData
#define glClear tsp_imgui_gl.Clear
#define glClearColor tsp_imgui_gl.ClearColor
#define glCompileShader tsp_imgui_gl.CompileShader
#define glCreateProgram tsp_imgui_gl.CreateProgram
#define glCreateShader tsp_imgui_gl.CreateShader
#define glDeleteBuffers tsp_imgui_gl.DeleteBuffers
#define glDeleteProgram tsp_imgui_gl.DeleteProgram
#define glDeleteShader tsp_imgui_gl.DeleteShader
#define glDeleteTextures tsp_imgui_gl.DeleteTextures
#define glDeleteVertexArrays tsp_imgui_gl.DeleteVertexArrays
#define glDetachShader tsp_imgui_gl.DetachShader
#define glDisable tsp_imgui_gl.Disable
#define glDrawElements tsp_imgui_gl.DrawElements
#define glDrawElementsBaseVertex tsp_imgui_gl.DrawElementsBaseVertex
#define glEnable tsp_imgui_gl.Enable
#define glEnableVertexAttribArray tsp_imgui_gl.EnableVertexAttribArray
#define glGenBuffers tsp_imgui_gl.GenBuffers
#define glGenTextures tsp_imgui_gl.GenTextures
#define glGenVertexArrays tsp_imgui_gl.GenVertexArrays
#define glGetAttribLocation tsp_imgui_gl.GetAttribLocation
#define glGetError tsp_imgui_gl.GetError
#define glGetIntegerv tsp_imgui_gl.GetIntegerv
#define glGetProgramInfoLog tsp_imgui_gl.GetProgramInfoLog
#define glGetProgramiv tsp_imgui_gl.GetProgramiv
#define glGetShaderInfoLog tsp_imgui_gl.GetShaderInfoLog
#define glGetShaderiv tsp_imgui_gl.GetShaderiv
#define glGetString tsp_imgui_gl.GetString
#define glGetStringi tsp_imgui_gl.GetStringi
#define glGetUniformLocation tsp_imgui_gl.GetUniformLocation
#define glIsEnabled tsp_imgui_gl.IsEnabled
#define glLinkProgram tsp_imgui_gl.LinkProgram
#define glPixelStorei tsp_imgui_gl.PixelStorei
#define glPolygonMode tsp_imgui_gl.PolygonMode
#define glReadPixels tsp_imgui_gl.ReadPixels
#define glScissor tsp_imgui_gl.Scissor
#define glShaderSource tsp_imgui_gl.ShaderSource
#define glTexImage2D tsp_imgui_gl.TexImage2D
#define glTexParameteri tsp_imgui_gl.TexParameteri
#define glUniform1i tsp_imgui_gl.Uniform1i
#define glUniformMatrix4fv tsp_imgui_gl.UniformMatrix4fv
#define glUseProgram tsp_imgui_gl.UseProgram
#define glVertexAttribPointer tsp_imgui_gl.VertexAttribPointer
#define glViewport tsp_imgui_gl.Viewport

#include "player/imgui_gl_loader.h"

#include <utility>

TspImGuiGl tsp_imgui_gl{};

const char* tsp_imgui_gl_load(TspImGuiGetProc get_proc) {
  const std::pair<const char*, void**> entries[] = {
    {"glActiveTexture", reinterpret_cast<void**>(&tsp_imgui_gl.ActiveTexture)},
    {"glAttachShader", reinterpret_cast<void**>(&tsp_imgui_gl.AttachShader)},
    {"glBindBuffer", reinterpret_cast<void**>(&tsp_imgui_gl.BindBuffer)},
    {"glBindSampler", reinterpret_cast<void**>(&tsp_imgui_gl.BindSampler)},
    {"glBindTexture", reinterpret_cast<void**>(&tsp_imgui_gl.BindTexture)},
    {"glBindVertexArray", reinterpret_cast<void**>(&tsp_imgui_gl.BindVertexArray)},
    {"glBlendEquation", reinterpret_cast<void**>(&tsp_imgui_gl.BlendEquation)},
    {"glBlendEquationSeparate", reinterpret_cast<void**>(&tsp_imgui_gl.BlendEquationSeparate)},
    {"glBlendFuncSeparate", reinterpret_cast<void**>(&tsp_imgui_gl.BlendFuncSeparate)},
    {"glBufferData", reinterpret_cast<void**>(&tsp_imgui_gl.BufferData)},
    {"glBufferSubData", reinterpret_cast<void**>(&tsp_imgui_gl.BufferSubData)},
    {"glClear", reinterpret_cast<void**>(&tsp_imgui_gl.Clear)},
    {"glClearColor", reinterpret_cast<void**>(&tsp_imgui_gl.ClearColor)},
    {"glCompileShader", reinterpret_cast<void**>(&tsp_imgui_gl.CompileShader)},
    {"glCreateProgram", reinterpret_cast<void**>(&tsp_imgui_gl.CreateProgram)},
    {"glCreateShader", reinterpret_cast<void**>(&tsp_imgui_gl.CreateShader)},
    {"glDeleteBuffers", reinterpret_cast<void**>(&tsp_imgui_gl.DeleteBuffers)},
    {"glDeleteProgram", reinterpret_cast<void**>(&tsp_imgui_gl.DeleteProgram)},
    {"glDeleteShader", reinterpret_cast<void**>(&tsp_imgui_gl.DeleteShader)},
    {"glDeleteTextures", reinterpret_cast<void**>(&tsp_imgui_gl.DeleteTextures)},
    {"glDeleteVertexArrays", reinterpret_cast<void**>(&tsp_imgui_gl.DeleteVertexArrays)},
    {"glDetachShader", reinterpret_cast<void**>(&tsp_imgui_gl.DetachShader)},
    {"glDisable", reinterpret_cast<void**>(&tsp_imgui_gl.Disable)},
    {"glDrawElements", reinterpret_cast<void**>(&tsp_imgui_gl.DrawElements)},
    {"glDrawElementsBaseVertex", reinterpret_cast<void**>(&tsp_imgui_gl.DrawElementsBaseVertex)},
    {"glEnable", reinterpret_cast<void**>(&tsp_imgui_gl.Enable)},
    {"glEnableVertexAttribArray", reinterpret_cast<void**>(&tsp_imgui_gl.EnableVertexAttribArray)},
    {"glGenBuffers", reinterpret_cast<void**>(&tsp_imgui_gl.GenBuffers)},
    {"glGenTextures", reinterpret_cast<void**>(&tsp_imgui_gl.GenTextures)},
    {"glGenVertexArrays", reinterpret_cast<void**>(&tsp_imgui_gl.GenVertexArrays)},
    {"glGetAttribLocation", reinterpret_cast<void**>(&tsp_imgui_gl.GetAttribLocation)},
    {"glGetError", reinterpret_cast<void**>(&tsp_imgui_gl.GetError)},
    {"glGetIntegerv", reinterpret_cast<void**>(&tsp_imgui_gl.GetIntegerv)},
    {"glGetProgramInfoLog", reinterpret_cast<void**>(&tsp_imgui_gl.GetProgramInfoLog)},
    {"glGetProgramiv", reinterpret_cast<void**>(&tsp_imgui_gl.GetProgramiv)},
    {"glGetShaderInfoLog", reinterpret_cast<void**>(&tsp_imgui_gl.GetShaderInfoLog)},
    {"glGetShaderiv", reinterpret_cast<void**>(&tsp_imgui_gl.GetShaderiv)},
    {"glGetString", reinterpret_cast<void**>(&tsp_imgui_gl.GetString)},
    {"glGetStringi", reinterpret_cast<void**>(&tsp_imgui_gl.GetStringi)},
    {"glGetUniformLocation", reinterpret_cast<void**>(&tsp_imgui_gl.GetUniformLocation)},
    {"glIsEnabled", reinterpret_cast<void**>(&tsp_imgui_gl.IsEnabled)},
    {"glLinkProgram", reinterpret_cast<void**>(&tsp_imgui_gl.LinkProgram)},
    {"glPixelStorei", reinterpret_cast<void**>(&tsp_imgui_gl.PixelStorei)},
    {"glPolygonMode", reinterpret_cast<void**>(&tsp_imgui_gl.PolygonMode)},
    {"glReadPixels", reinterpret_cast<void**>(&tsp_imgui_gl.ReadPixels)},
    {"glScissor", reinterpret_cast<void**>(&tsp_imgui_gl.Scissor)},
    {"glShaderSource", reinterpret_cast<void**>(&tsp_imgui_gl.ShaderSource)},
    {"glTexImage2D", reinterpret_cast<void**>(&tsp_imgui_gl.TexImage2D)},
    {"glTexParameteri", reinterpret_cast<void**>(&tsp_imgui_gl.TexParameteri)},
    {"glUniform1i", reinterpret_cast<void**>(&tsp_imgui_gl.Uniform1i)},
    {"glUniformMatrix4fv", reinterpret_cast<void**>(&tsp_imgui_gl.UniformMatrix4fv)},
    {"glUseProgram", reinterpret_cast<void**>(&tsp_imgui_gl.UseProgram)},
    {"glVertexAttribPointer", reinterpret_cast<void**>(&tsp_imgui_gl.VertexAttribPointer)},
    {"glViewport", reinterpret_cast<void**>(&tsp_imgui_gl.Viewport)},
  };
  for (const auto& [name, slot] : entries) {
    *slot = reinterpret_cast<void*>(get_proc(name));
    if (!*slot) return name;
  }
  return nullptr;
}

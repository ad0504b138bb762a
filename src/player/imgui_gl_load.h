// Loading the GL entry points of Dear ImGui's OpenGL 3 back end through our context's
// get-proc-address (imgui_gl_loader.h, which only the back end includes, names them).
#pragma once

/// A get-proc-address function (OSMesaGetProcAddress, glfwGetProcAddress).
using TspImGuiGetProc = void (*(*)(const char* name))();

/// Loads every entry point the back end calls through get_proc (the context must be current);
/// returns the name of the first one it could not find, or nullptr when all were found. Call
/// before ImGui_ImplOpenGL3_Init. Never throws; not thread-safe.
const char* tsp_imgui_gl_load(TspImGuiGetProc get_proc);

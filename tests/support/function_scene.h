// A rendering scene built from a formula, shared by the render tests that compare pictures of
// one step: a 65³ (or any) .tsp of f in a RenderScene (an offscreen context, the TSP renderer
// over the reference metric — zero tolerance draws every brick — and the non-TSP baseline), and
// an orbit camera.
#pragma once
#include <functional>
#include <string>

#include "support/render_scene.h"

namespace tsptest {

/// The scene; use from one thread (its GL context's).
struct FunctionScene : RenderScene {
  /// Builds `name`.tsp of f over dims (bricks of 16) and both renderers through tf, on a
  /// width × height offscreen context. Throws what building, opening and GL throw.
  FunctionScene(const std::string& name, const std::function<float(int, int, int, int)>& f,
                const tsp::TransferFunction& tf, tsp::Dims dims = {65, 65, 65}, int width = 200,
                int height = 150);
  /// The orbit camera at azimuth 30, elevation 20 (p's other fields as given).
  tsp::Camera camera(tsp::CameraParams p = {}) const;
};

}  // namespace tsptest

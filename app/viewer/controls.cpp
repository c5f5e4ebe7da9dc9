// The viewer's controls outside ImGui's widgets: keys (the seed's 1..9, 0, Return and the
// viewer's own), the camera (scene cameras, right-drag, ctrl+wheel, WASD/QE) and the lights
// (count, radius scale), applied to the live scene between frames.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>

#include "app/viewer/viewer.h"
#include "views/ui/compare_view.h"

namespace gb {

// Keys of the seed (1..9, 0, Return) and the viewer's own.
void handleKeys(Viewer& v) {
  ViewerModel& m = v.model;
  std::vector<int> keys;
  keys.swap(v.pressedKeys);
  if (ImGui::GetIO().WantTextInput) return;
  for (int k : keys) {
    bool ctrl = k & 0x10000;
    int key = k & 0xFFFF;
    if (ctrl && key == GLFW_KEY_Q) glfwSetWindowShouldClose(v.window, 1);
    if (ctrl && key == GLFW_KEY_S && !m.attach.draft.empty()) m.attach.saveDraftRequested = true;  // attach --suggest's draft
    if (ctrl) continue;
    if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) applyViewKey(m, key - GLFW_KEY_0);
    if (key >= GLFW_KEY_KP_0 && key <= GLFW_KEY_KP_9) applyViewKey(m, key - GLFW_KEY_KP_0);
    if (key == GLFW_KEY_ENTER || key == GLFW_KEY_KP_ENTER) applyViewKey(m, 0);
    if (key == GLFW_KEY_SPACE && m.source == FrameSource::Compare) flipCompareSide(m);  // A <-> B in place
    if (key == GLFW_KEY_SPACE && m.source != FrameSource::Compare) m.playing = !m.playing;
    if (key == GLFW_KEY_ESCAPE) m.referenceError.cancelRequested = true;
    if (key == GLFW_KEY_C && m.attach.on) m.captureRequested = true;  // an attached stream: capture the frame shown
    if (key == GLFW_KEY_PERIOD) m.stepForward = true;
    if (key == GLFW_KEY_COMMA) m.stepBack = true;
    if (key == GLFW_KEY_HOME) m.resetCamera = true;
    if (key == GLFW_KEY_G) m.grid = !m.grid;
    if (key == GLFW_KEY_Z) m.transform = ViewTransform{};
    glm::ivec2 step(key == GLFW_KEY_RIGHT ? 1 : key == GLFW_KEY_LEFT ? -1 : 0,
                    key == GLFW_KEY_DOWN ? 1 : key == GLFW_KEY_UP ? -1 : 0);
    if (step != glm::ivec2(0)) {
      glm::ivec2 from = m.probePixel ? *m.probePixel : glm::ivec2(viewImageSize(m, m.primary) / 2u);
      m.probeRequest = from + step;
    }
  }
}

// Camera: scene cameras, reset, right-drag, ctrl+wheel, WASD/QE held. Returns true while keys move it.
bool updateCamera(Viewer& v, double dt) {
  ViewerModel& m = v.model;
  bool changed = false;
  if (m.resetCamera || m.gltfCamera >= 0) {
    int index = m.gltfCamera >= 0 ? m.gltfCamera : v.args.render.camera;
    resetRig(v.rig, v.scene.cameras[size_t(index)], v.scene.bounds);
    m.resetCamera = false;
    m.gltfCamera = -1;
    changed = true;
  }
  if (m.cameraDrag != glm::dvec2(0.0)) {
    if (m.cameraMode == CameraMode::Orbit)
      orbitRig(v.rig, m.cameraDrag);
    else
      lookRig(v.rig, m.cameraDrag);
    m.cameraDrag = glm::dvec2(0.0);
    changed = true;
  }
  if (m.cameraDolly != 0.0) {
    dollyRig(v.rig, m.cameraDolly);
    m.cameraDolly = 0.0;
    changed = true;
  }
  glm::dvec3 move(0.0);
  const bool ctrl = glfwGetKey(v.window, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
                    glfwGetKey(v.window, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
  if (!ImGui::GetIO().WantTextInput && !ctrl) {
    auto held = [&](int key) { return glfwGetKey(v.window, key) == GLFW_PRESS; };
    move.x = double(held(GLFW_KEY_D)) - double(held(GLFW_KEY_A));
    move.y = double(held(GLFW_KEY_E)) - double(held(GLFW_KEY_Q));
    move.z = double(held(GLFW_KEY_S)) - double(held(GLFW_KEY_W));
    if (held(GLFW_KEY_LEFT_SHIFT)) move *= 4.0;
  }
  bool moving = move != glm::dvec3(0.0);
  if (moving) {
    moveRig(v.rig, move * (dt * m.moveSpeed * 0.25 * v.rig.sceneRadius));
    changed = true;
  }
  if (changed) {
    v.scene.cameras.back() = v.rig.desc;
    v.cameraVersion++;
  }
  return moving;
}

void updateLights(Viewer& v) {
  ViewerModel& m = v.model;
  if (v.scene.generatedLights && int(v.scene.lights.size()) != m.lightCount) {
    generateLights(v.scene, m.lightCount);
    v.baseRadius.clear();
  }
  if (v.baseRadius.size() != v.scene.lights.size()) {
    v.baseRadius.clear();
    for (const PointLightDesc& l : v.scene.lights) v.baseRadius.push_back(l.radius);
    v.lightsVersion++;
  }
  if (v.lightsVersion == 1 || m.lightRadiusScale != v.appliedRadiusScale) {
    for (size_t i = 0; i < v.scene.lights.size(); ++i) v.scene.lights[i].radius = v.baseRadius[i] * m.lightRadiusScale;
    v.appliedRadiusScale = m.lightRadiusScale;
    v.lightsVersion++;
  }
}

}  // namespace gb

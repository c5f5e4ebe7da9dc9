// The viewer's controls outside ImGui's widgets: keys (the seed's 1..9, 0, Return and the
// viewer's own, dispatched through views/ui/keys.h), the camera (scene cameras, right-drag, ctrl+wheel, WASD/QE) and the lights
// (count, radius scale), applied to the live scene between frames.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>

#include "app/viewer/viewer.h"
#include "views/ui/compare_view.h"
#include "views/ui/keys.h"

namespace gb {

// The table's name of a GLFW key (views/ui/keys.cpp), "" for keys the table does not name.
static std::string keyName(int key) {
  if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) return std::string(1, char('0' + key - GLFW_KEY_0));
  if (key >= GLFW_KEY_KP_0 && key <= GLFW_KEY_KP_9) return std::string(1, char('0' + key - GLFW_KEY_KP_0));
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return std::string(1, char('A' + key - GLFW_KEY_A));
  switch (key) {
    case GLFW_KEY_ENTER: case GLFW_KEY_KP_ENTER: return "Return";
    case GLFW_KEY_SPACE: return "Space";
    case GLFW_KEY_ESCAPE: return "Escape";
    case GLFW_KEY_PERIOD: return ".";
    case GLFW_KEY_COMMA: return ",";
    case GLFW_KEY_HOME: return "Home";
    case GLFW_KEY_LEFT: return "Left";
    case GLFW_KEY_RIGHT: return "Right";
    case GLFW_KEY_UP: return "Up";
    case GLFW_KEY_DOWN: return "Down";
    default: return "";
  }
}

// Keys, through the one table (views/ui/keys.h) that Help and the README show.
void handleKeys(Viewer& v) {
  ViewerModel& m = v.model;
  std::vector<int> keys;
  keys.swap(v.pressedKeys);
  if (ImGui::GetIO().WantTextInput) return;
  for (int k : keys) {
    const bool ctrl = k & 0x10000;
    const int key = k & 0xFFFF;
    const std::string name = keyName(key);
    const std::optional<KeyAction> action = keyAction(name, ctrl, keySession(m));
    if (!action) continue;
    switch (*action) {
      case KeyAction::Quit: glfwSetWindowShouldClose(v.window, 1); break;
      case KeyAction::SaveDraft:
        if (!m.attach.draft.empty()) m.attach.saveDraftRequested = true;
        break;
      case KeyAction::Grid: case KeyAction::FirstView: case KeyAction::ViewKey:
        applyViewKey(m, name == "Return" ? 0 : name[0] - '0');
        break;
      case KeyAction::FlipCompare: flipCompareSide(m); break;
      case KeyAction::PlayPause: case KeyAction::PauseStream: m.playing = !m.playing; break;
      case KeyAction::CancelReference: m.referenceError.cancelRequested = true; break;
      case KeyAction::CaptureShown: m.captureRequested = true; break;
      case KeyAction::StepForward: m.stepForward = true; break;
      case KeyAction::StepBack: m.stepBack = true; break;
      case KeyAction::ResetCamera: m.resetCamera = true; break;
      case KeyAction::TexelGrid: m.grid = !m.grid; break;
      case KeyAction::Fit: m.transform = ViewTransform{}; break;
      case KeyAction::ZoomToMarks: zoomToShadowMarks(m); break;
      case KeyAction::NextSample: showNextSample(v); break;
      case KeyAction::NextFrame: stepTimeline(m, +1); break;
      case KeyAction::PreviousFrame: stepTimeline(m, -1); break;
      case KeyAction::PlaySequence: m.timeline.playing = !m.timeline.playing, m.uiChanged = true; break;
      case KeyAction::MotionViews: cycleMotionViews(m); break;
      case KeyAction::FlickerView:
        if (!m.timeline.flickerOf.empty()) m.timeline.flickerRequested = true, m.uiChanged = true;
        break;
      case KeyAction::MoveProbe: {
        const glm::ivec2 step(name == "Right" ? 1 : name == "Left" ? -1 : 0, name == "Down" ? 1 : name == "Up" ? -1 : 0);
        // From the pixel asked for already in this frame: presses that arrive together all count.
        const glm::ivec2 from = m.probeRequest ? *m.probeRequest
                                : m.probePixel ? *m.probePixel
                                               : glm::ivec2(viewImageSize(m, m.primary) / 2u);
        m.probeRequest = from + step;
        break;
      }
      case KeyAction::CompareSwipe: m.compareMode = CompareMode::Swipe, m.uiChanged = true; break;
      case KeyAction::CompareDifference: m.compareMode = CompareMode::Difference, m.uiChanged = true; break;
      case KeyAction::CompareFlip: m.compareMode = CompareMode::Flip, m.uiChanged = true; break;
      case KeyAction::CompareRow: m.compareMode = CompareMode::Row, m.uiChanged = true; break;
      case KeyAction::MoveCamera: case KeyAction::Mouse: break;  // held keys and the mouse: elsewhere
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

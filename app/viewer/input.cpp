// The viewer's input queue: GLFW's callbacks queue every event, and each interface frame hands Dear
// ImGui (1.86 keeps no queue of its own and polls the cursor) the events up to and including one
// button transition, at the cursor position it happened at. A click, a ctrl + drag or a key pressed
// while a slow frame renders (lavapipe under load: seconds) is then seen whole, in order, where it
// happened, instead of collapsing into one frame that sees the release only.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui/backends/imgui_impl_glfw.h>

#include <algorithm>
#include <cfloat>
#include <cstdio>

#include "app/viewer/viewer.h"

namespace gb {

static Viewer& viewerOf(GLFWwindow* w) { return *static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }
static void wake(GLFWwindow* w) { viewerOf(w).uiFramesLeft = std::max(viewerOf(w).uiFramesLeft, 3); }
// Each event carries the cursor position of the last move reported before it (glfwGetCursorPos would
// say where the cursor is by the time the events are polled, not where it was).
static void queue(GLFWwindow* w, InputEvent e) {
  InputQueue& q = viewerOf(w).input;
  if (q.cursorX < 0.0) glfwGetCursorPos(w, &q.cursorX, &q.cursorY);
  e.x = q.cursorX, e.y = q.cursorY;
  q.events.push_back(e);
  wake(w);
}

void installInputCallbacks(Viewer& v) {
  glfwSetWindowUserPointer(v.window, &v);
  glfwSetKeyCallback(v.window, [](GLFWwindow* w, int key, int scancode, int action, int mods) {
    if (action != GLFW_RELEASE) viewerOf(w).pressedKeys.push_back(key | (mods & GLFW_MOD_CONTROL ? 0x10000 : 0));
    queue(w, {InputEvent::Key, key, scancode, action, mods});
  });
  glfwSetMouseButtonCallback(v.window, [](GLFWwindow* w, int button, int action, int mods) {
    if (button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_PRESS) {
      viewerOf(w).clickTime = std::chrono::steady_clock::now();  // click-to-dossier latency starts here
      viewerOf(w).clickPending = true;
    }
    queue(w, {InputEvent::Button, button, action, mods, 0});
  });
  glfwSetCursorPosCallback(v.window, [](GLFWwindow* w, double x, double y) {
    viewerOf(w).input.cursorX = x, viewerOf(w).input.cursorY = y;
    queue(w, {InputEvent::Move, 0, 0, 0, 0});
  });
  glfwSetScrollCallback(v.window, [](GLFWwindow* w, double dx, double dy) {
    InputEvent e{InputEvent::Scroll, 0, 0, 0, 0};
    e.dx = dx, e.dy = dy;
    queue(w, e);
  });
  glfwSetCharCallback(v.window, [](GLFWwindow* w, unsigned c) { queue(w, {InputEvent::Char, int(c), 0, 0, 0}); });
  glfwSetWindowRefreshCallback(v.window, [](GLFWwindow* w) { wake(w); });
  glfwSetFramebufferSizeCallback(v.window, [](GLFWwindow* w, int, int) { wake(w); });
  glfwSetWindowFocusCallback(v.window, [](GLFWwindow* w, int focused) {
    ImGui_ImplGlfw_WindowFocusCallback(w, focused);
    wake(w);
  });
  glfwSetCursorEnterCallback(v.window, [](GLFWwindow* w, int entered) {
    ImGui_ImplGlfw_CursorEnterCallback(w, entered);
    wake(w);
  });
}

void feedInput(Viewer& v) {
  InputQueue& q = v.input;
  while (!q.events.empty()) {
    const InputEvent e = q.events.front();
    q.events.pop_front();
    q.x = e.x, q.y = e.y;
    switch (e.kind) {
      case InputEvent::Move: break;
      case InputEvent::Scroll: ImGui_ImplGlfw_ScrollCallback(v.window, e.dx, e.dy); break;
      case InputEvent::Char: ImGui_ImplGlfw_CharCallback(v.window, unsigned(e.a)); break;
      case InputEvent::Key:
        ImGui_ImplGlfw_KeyCallback(v.window, e.a, e.b, e.c, e.d);
        if (e.c != GLFW_REPEAT) return;  // one transition a frame
        break;
      case InputEvent::Button:
        ImGui_ImplGlfw_MouseButtonCallback(v.window, e.a, e.b, e.c);
        if (e.a >= 0 && e.a < 5) q.down[size_t(e.a)] = e.b == GLFW_PRESS;
        return;  // the transition is seen alone, where it happened
    }
  }
}

void applyInputState(Viewer& v) {
  ImGuiIO& io = ImGui::GetIO();
  const InputQueue& q = v.input;
  // ImGui's backend polled the cursor and the buttons as they are now; the frame sees them as the
  // events delivered so far left them.
  if (q.x >= 0.0 && io.MousePos.x > -FLT_MAX) io.MousePos = ImVec2(float(q.x), float(q.y));
  for (size_t b = 0; b < 5; ++b) io.MouseDown[b] = q.down[b];
  if (!q.events.empty()) v.uiFramesLeft = std::max(v.uiFramesLeft, 2);  // more to deliver
}

}  // namespace gb

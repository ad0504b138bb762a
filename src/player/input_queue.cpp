#include "player/input_queue.h"

namespace tspplayer {

namespace {
// GLFW's Shift, Control, Alt and Super keys, left and right (GLFW_KEY_LEFT_SHIFT … RIGHT_SUPER).
constexpr int kFirstModifier = 340, kLastModifier = 347;
bool is_modifier(int key) { return key >= kFirstModifier && key <= kLastModifier; }
}  // namespace

const InputFrame& InputQueue::take() {
  bool button_changed = false;
  take_frame(button_changed);
  look_ahead(button_changed);
  return state_;
}

void InputQueue::take_frame(bool& button_changed) {
  state_.wheel_x = state_.wheel_y = 0;
  state_.text.clear();
  state_.pressed.clear();
  bool moved = false, key_changed = false, typed = false, scrolled = false;
  bool plain_key_changed = false;  // a key other than a modifier changed in this frame
  std::array<bool, InputFrame::kButtons> changed_button{};
  std::array<bool, InputFrame::kKeys> changed_key{};
  while (!events_.empty()) {
    const InputEvent& e = events_.front();
    switch (e.kind) {
      case InputEvent::Kind::cursor:
        if (button_changed) return;
        state_.x = e.x;
        state_.y = e.y;
        moved = true;
        break;
      case InputEvent::Kind::button: {
        if (e.code < 0 || e.code >= InputFrame::kButtons) break;
        const std::size_t b = std::size_t(e.code);
        if (changed_button[b] || scrolled || (!e.down && moved)) return;
        if (state_.buttons[b] != e.down) {
          state_.buttons[b] = e.down;
          changed_button[b] = button_changed = true;
        }
        break;
      }
      case InputEvent::Kind::key: {
        if (e.code < 0 || e.code >= InputFrame::kKeys) break;
        const std::size_t k = std::size_t(e.code);
        // A modifier's change waits for the next frame once another key or a button changed in
        // this one: Dear ImGui reads the modifiers per frame, so a Ctrl+A whose Ctrl is released
        // in the frame that sees A pressed reached it as a plain A (a quick tap at normal frame
        // rates: Ctrl down in one frame, A down and Ctrl up in the next).
        if (changed_key[k] || typed || button_changed || (is_modifier(e.code) && plain_key_changed))
          return;
        if (state_.keys[k] != e.down) {
          state_.keys[k] = e.down;
          changed_key[k] = key_changed = true;
          plain_key_changed = plain_key_changed || !is_modifier(e.code);
        }
        if (e.down && e.to_player) state_.pressed.push_back(e.code);
        break;
      }
      case InputEvent::Kind::text:
        if (key_changed) return;
        typed = true;
        state_.text.push_back(unsigned(e.code));
        break;
      case InputEvent::Kind::scroll:
        if (button_changed) return;
        state_.wheel_x += e.x;
        state_.wheel_y += e.y;
        scrolled = true;
        break;
    }
    events_.pop_front();
  }
  return;
}

void InputQueue::look_ahead(bool button_changed) {
  // The player's keys need no frame of their own: those waiting behind this frame's share go
  // now, up to the first button event (a click may give a text field the focus, and the keys
  // after it are the field's); none after a button changed in this frame.
  if (button_changed) return;
  for (InputEvent& e : events_) {
    if (e.kind == InputEvent::Kind::button) return;
    if (e.kind == InputEvent::Kind::key && e.down && e.to_player) {
      state_.pressed.push_back(e.code);
      e.to_player = false;  // (listed once)
    }
  }
}

bool InputQueue::player_key_waiting(int key) const {
  for (const InputEvent& e : events_) {
    if (e.kind == InputEvent::Kind::button) return false;
    if (e.kind == InputEvent::Kind::key && e.code == key && e.down && e.to_player) return true;
  }
  return false;
}

}  // namespace tspplayer

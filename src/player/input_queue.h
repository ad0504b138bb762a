// The window's input events in order, handed to Dear ImGui a frame's worth at a time, so that
// no press, release or keystroke is lost in a slow frame (docs/player.md "Input"): Dear ImGui
// 1.86 reads the mouse and keys as per-frame state, so a drag that presses, moves and releases
// within one slow frame, or a key pressed and released in one, never reached it. GL-, GLFW- and
// ImGui-free, so the tests feed it events directly.
#pragma once
#include <array>
#include <cfloat>
#include <cstdint>
#include <deque>
#include <vector>

namespace tspplayer {

/// One window input event as GLFW reports it.
struct InputEvent {
  /// What happened.
  enum class Kind { cursor, button, key, text, scroll } kind = Kind::cursor;
  float x = 0, y = 0;  ///< cursor: the position; scroll: the offsets
  int code = 0;        ///< button: 0..4; key: GLFW key code; text: the Unicode code point
  bool down = false;   ///< button, key: pressed (true) or released
  bool to_player = false;  ///< key: a press or a repeat the player's own keys may take
};

/// The input state a frame shows Dear ImGui, after the events it took.
struct InputFrame {
  /// Buttons tracked (GLFW's first five).
  static constexpr int kButtons = 5;
  /// Keys tracked (ImGuiIO::KeysDown's size in 1.86).
  static constexpr int kKeys = 512;
  float x = -FLT_MAX, y = -FLT_MAX;        ///< the cursor (-FLT_MAX: outside the window)
  std::array<bool, kButtons> buttons{};    ///< buttons held
  std::array<bool, kKeys> keys{};          ///< keys held
  float wheel_x = 0, wheel_y = 0;          ///< scrolled this frame
  std::vector<unsigned> text;              ///< characters typed this frame, in order
  std::vector<int> pressed;                ///< keys pressed or repeated for the player, in order
};

/// The queue: push() from GLFW's callbacks, take() once per frame.
class InputQueue {
 public:
  /// Appends an event (in the order GLFW reported them).
  void push(const InputEvent& e) { events_.push_back(e); }
  /// Takes the events of one frame in order, into the state it returns, stopping before an
  /// event Dear ImGui could not tell apart from an earlier one of the same frame: a second
  /// change of a button or key; a release after the cursor moved (the move must be drawn held);
  /// a move after a button changed (the press happened where it was); keys and text after each
  /// other; a scroll after a button changed; a key after a button changed (a click that gives a
  /// text field the focus is seen before the keys typed into it); a modifier (Shift, Ctrl, Alt,
  /// Super) after another key changed (that press keeps its modifiers). The rest waits for the
  /// next frames. A repeat changes no state; it is only listed in `pressed`. `pressed` also lists
  /// the player's presses waiting behind the frame's share, up to the first button event (none
  /// when a button changed in this frame), each once. Never throws.
  const InputFrame& take();
  /// True while events wait for later frames (the window keeps drawing until they are taken).
  bool pending() const { return !events_.empty(); }
  /// True when a press of key for the player waits in the queue where the next take() lists
  /// it in `pressed` (before any button event). Never throws.
  bool player_key_waiting(int key) const;
  /// The state after the last take().
  const InputFrame& state() const { return state_; }

 private:
  void take_frame(bool& button_changed);  // this frame's share of the events
  void look_ahead(bool button_changed);   // the player's keys waiting behind it
  std::deque<InputEvent> events_;
  InputFrame state_;
};

}  // namespace tspplayer

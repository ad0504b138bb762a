// The player's input queue (src/player/input_queue.h): what each frame hands Dear ImGui when a
// slow frame collected a whole drag or many keystrokes — every press, the moves while held and
// every release reach it, in order, each where it happened.
#include "player/input_queue.h"

#include <gtest/gtest.h>

namespace {

using namespace tspplayer;
using Kind = InputEvent::Kind;
constexpr int kBackspace = 259;  // GLFW_KEY_BACKSPACE

InputEvent cursor(float x, float y) { return {Kind::cursor, x, y}; }
InputEvent button(bool down) { return {Kind::button, 0, 0, 0, down}; }
InputEvent key(int k, bool down) { return {Kind::key, 0, 0, k, down}; }

// A slider drag from x = 200 to x = 10, pressed, moved and released within one slow frame: the
// press is seen at 200, the moves while held (ending at 10), then the release.
TEST(PlayerInputQueue, ADragWithinOneFrameIsSeenPressedMovedAndReleased) {
  InputQueue q;
  q.push(cursor(200, 50));
  q.push(button(true));
  for (float x = 180; x >= 10; x -= 10) q.push(cursor(x, 50));
  q.push(button(false));
  q.push(cursor(12, 51));
  InputFrame f = q.take();
  EXPECT_EQ(f.x, 200);
  EXPECT_TRUE(f.buttons[0]);
  ASSERT_TRUE(q.pending());
  f = q.take();
  EXPECT_EQ(f.x, 10);  // dragged there, still held
  EXPECT_TRUE(f.buttons[0]);
  f = q.take();
  EXPECT_FALSE(f.buttons[0]);  // released where it was
  EXPECT_EQ(f.x, 10);
  f = q.take();
  EXPECT_EQ(f.x, 12);
  EXPECT_FALSE(q.pending());
}

// 70 backspace taps typed during one slow frame: each press reaches a frame of its own, so a
// text field applies all 70 (Dear ImGui 1.86 saw one per frame at most: 18 of 70 applied).
TEST(PlayerInputQueue, EveryKeyTapReachesAFrameOfItsOwn) {
  InputQueue q;
  for (int i = 0; i < 70; ++i) {
    q.push(key(kBackspace, true));
    q.push(key(kBackspace, false));
  }
  int presses = 0, frames = 0;
  bool was = false;
  while (q.pending()) {
    const InputFrame& f = q.take();
    presses += f.keys[kBackspace] && !was;
    was = f.keys[kBackspace];
    ++frames;
  }
  EXPECT_EQ(presses, 70);
  EXPECT_EQ(frames, 140);
}

// Text and keys keep their order ("ab", backspace, "c"), and characters typed together share a
// frame; scrolls add up; a scroll after a press waits.
TEST(PlayerInputQueue, TextKeysAndScrollKeepTheirOrder) {
  InputQueue q;
  q.push({Kind::text, 0, 0, 'a'});
  q.push({Kind::text, 0, 0, 'b'});
  q.push(key(kBackspace, true));
  q.push(key(kBackspace, false));
  q.push({Kind::text, 0, 0, 'c'});
  InputFrame f = q.take();
  EXPECT_EQ(f.text, (std::vector<unsigned>{'a', 'b'}));
  f = q.take();
  EXPECT_TRUE(f.keys[kBackspace]);
  EXPECT_TRUE(f.text.empty());
  f = q.take();
  EXPECT_FALSE(f.keys[kBackspace]);
  f = q.take();
  EXPECT_EQ(f.text, (std::vector<unsigned>{'c'}));
  EXPECT_FALSE(q.pending());

  q.push({Kind::scroll, 0, 1});
  q.push({Kind::scroll, 0, 2});
  q.push(button(true));
  q.push({Kind::scroll, 0, -1});
  f = q.take();
  EXPECT_EQ(f.wheel_y, 3);
  f = q.take();
  EXPECT_TRUE(f.buttons[0]);
  EXPECT_EQ(f.wheel_y, 0);
  f = q.take();
  EXPECT_EQ(f.wheel_y, -1);
}

}  // namespace

namespace {

using namespace tspplayer;
constexpr int kCtrl = 341, kA = 65;  // GLFW_KEY_LEFT_CONTROL, GLFW_KEY_A

// A quick Ctrl+A as X delivers it (xdotool key ctrl+a: Ctrl down, A down, Ctrl up, A up, ~12 ms
// apart) to a window that took Ctrl down in one frame: the frame that sees A pressed still sees
// Ctrl held, so Dear ImGui reads Ctrl+A, not a plain A (issue 47's walk: select all was lost).
TEST(PlayerInputQueue, AKeyPressedWithCtrlKeepsCtrlInItsFrame) {
  InputQueue q;
  q.push({InputEvent::Kind::key, 0, 0, kCtrl, true});
  InputFrame f = q.take();
  EXPECT_TRUE(f.keys[kCtrl]);
  q.push({InputEvent::Kind::key, 0, 0, kA, true});
  q.push({InputEvent::Kind::key, 0, 0, kCtrl, false});
  q.push({InputEvent::Kind::key, 0, 0, kA, false});
  f = q.take();
  EXPECT_TRUE(f.keys[kA]);
  EXPECT_TRUE(f.keys[kCtrl]) << "A pressed while Ctrl was down";
  f = q.take();
  EXPECT_FALSE(f.keys[kCtrl]);
  EXPECT_FALSE(f.keys[kA]);
  EXPECT_FALSE(q.pending());
  // Pressed together in one frame (Ctrl first), they still share it.
  q.push({InputEvent::Kind::key, 0, 0, kCtrl, true});
  q.push({InputEvent::Kind::key, 0, 0, kA, true});
  f = q.take();
  EXPECT_TRUE(f.keys[kCtrl] && f.keys[kA]);
}

// The player's own keys come from the queue, in the frame Dear ImGui sees them: a key typed
// just after the click that focuses a text field waits for the frame after the click (so the
// field has the focus and takes it, issue 47's walk: an S typed into the colour range while
// tuning saved a PNG); a repeat is listed without changing any key; a shortcut is not listed.
TEST(PlayerInputQueue, PlayerKeysArriveInTheFrameImGuiSeesThem) {
  constexpr int kS = 83, kSpace = 32;  // GLFW_KEY_S, GLFW_KEY_SPACE
  InputQueue q;
  q.push({InputEvent::Kind::button, 0, 0, 0, true});
  q.push({InputEvent::Kind::button, 0, 0, 0, false});
  q.push({InputEvent::Kind::key, 0, 0, kS, true, true});
  InputFrame f = q.take();
  EXPECT_TRUE(f.buttons[0]);
  EXPECT_TRUE(f.pressed.empty()) << "a key pressed with the click's frame waits";
  f = q.take();  // the release
  EXPECT_FALSE(f.buttons[0]);
  EXPECT_TRUE(f.pressed.empty());
  f = q.take();
  EXPECT_EQ(f.pressed, std::vector<int>{kS});
  EXPECT_TRUE(f.keys[kS]);
  q.push({InputEvent::Kind::key, 0, 0, kS, true, true});  // a repeat of the held S
  q.push({InputEvent::Kind::key, 0, 0, kA, true, false});  // a shortcut's key: not the player's
  f = q.take();
  EXPECT_EQ(f.pressed, std::vector<int>{kS});
  EXPECT_TRUE(f.keys[kS] && f.keys[kA]);
  q.push({InputEvent::Kind::key, 0, 0, kSpace, true, true});
  f = q.take();
  EXPECT_EQ(f.pressed, std::vector<int>{kSpace}) << "each frame lists its own presses";
}

// Quick taps of one key while frames are slow: Dear ImGui gets one change a frame, but the
// player acts on every press in the first frame (five Rights in 40 ms are five steps at once).
TEST(PlayerInputQueue, QuickTapsReachThePlayerInOneFrame) {
  constexpr int kRight = 262;  // GLFW_KEY_RIGHT
  InputQueue q;
  for (int i = 0; i < 5; ++i) {
    q.push({InputEvent::Kind::key, 0, 0, kRight, true, true});
    q.push({InputEvent::Kind::key, 0, 0, kRight, false});
  }
  InputFrame f = q.take();
  EXPECT_EQ(f.pressed, std::vector<int>(5, kRight));
  int frames = 1;
  for (; q.pending(); ++frames) EXPECT_TRUE(q.take().pressed.empty()) << "listed once";
  EXPECT_EQ(frames, 10) << "Dear ImGui still sees each press and release in a frame of its own";
}

}  // namespace

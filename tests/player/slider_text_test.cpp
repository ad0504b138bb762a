// A slider's value text beside its grab (player/slider_text.h): the grab never covers it (issue
// 47 walk 5: the scrubber's wide grab over "step 2  t = 2005-08-28 18:00", centred by ImGui).
#include "player/slider_text.h"

#include <gtest/gtest.h>

namespace {

using namespace tspplayer;

TEST(PlayerSliderText, TheGrabNeverCoversTheValueText) {
  // ImGui 1.86's grab: 2 pixels of padding, the value's share of the rest less the grab.
  EXPECT_EQ(slider_grab(0, 104, 0, 10).lo, 2);
  EXPECT_EQ(slider_grab(0, 104, 1, 10).hi, 102);
  EXPECT_EQ(slider_grab(0, 104, 0.5, 10).lo, 47);
  // A 4-step scrubber 404 pixels wide: a grab of 100 pixels.
  EXPECT_EQ(int_slider_grab_width(0, 404, 0, 3, 10), 100);
  EXPECT_EQ(int_slider_grab_width(0, 404, 0, 999, 10), 10);
  // At every step of it, a 180-pixel text lies beside the grab, inside the frame.
  for (int step = 0; step <= 3; ++step) {
    const GrabSpan g = slider_grab(0, 404, step / 3.0, 100);
    const float x = text_beside_grab(0, 404, g, 180);
    EXPECT_TRUE(x + 180 <= g.lo || x >= g.hi) << step;
    EXPECT_GE(x, 0);
    EXPECT_LE(x + 180, 404);
  }
  // The grab in the middle (step 2 of 5 shown): the text goes to the wider side, centred there.
  const GrabSpan mid{150, 250};
  EXPECT_EQ(text_beside_grab(0, 404, mid, 100), 250 + 4 + (404 - 250 - 8 - 100) / 2.f);
  // Too long for either side: against the edge, beside the grab (drawn clipped at it).
  EXPECT_EQ(text_beside_grab(0, 404, mid, 300), 254);
  EXPECT_EQ(text_beside_grab(0, 400, {200, 300}, 300), 4);
}

TEST(PlayerSliderText, AOneValueSliderDrawsItsTextOverTheGrab) {
  // The sixth walk: a one-step input's scrubber, whose grab fills the frame, hid its text.
  const GrabSpan one = slider_grab(0, 404, 0, int_slider_grab_width(0, 404, 0, 0, 10));
  EXPECT_EQ(one.lo, 2);
  EXPECT_EQ(one.hi, 402);
  EXPECT_FALSE(room_beside_grab(0, 404, one, 180));
  // Two or more steps leave room beside the grab: the text goes there.
  for (int last : {1, 3, 999}) {
    const float g = int_slider_grab_width(0, 404, 0, last, 10);
    EXPECT_TRUE(room_beside_grab(0, 404, slider_grab(0, 404, 0, g), 180)) << last;
  }
}

}  // namespace

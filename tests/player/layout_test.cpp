// The player's window layout and the TF editor's opacity axis, against hand-computed answers.
#include "player/layout.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace tspplayer;

TEST(PlayerLayout, LargeWindowDocksThePanelsBesideTheVolume) {
  const Layout l = compute_layout(1280, 800, true, 19);
  ASSERT_TRUE(l.docked);
  EXPECT_EQ(l.view, (WindowRect{0, 19, 1280 - kSidePanelWidth, 800 - 19 - kTimelineHeight}));
  EXPECT_EQ(l.side, (WindowRect{1280 - kSidePanelWidth, 19, kSidePanelWidth, 800 - 19}));
  EXPECT_EQ(l.timeline, (WindowRect{0, 800 - kTimelineHeight, 1280 - kSidePanelWidth,
                                    kTimelineHeight}));
  // The three cover the window below the menu bar without overlap: areas add up.
  const long area = long(l.view.w) * l.view.h + long(l.side.w) * l.side.h +
                    long(l.timeline.w) * l.timeline.h;
  EXPECT_EQ(area, 1280L * (800 - 19));
}

TEST(PlayerLayout, SmallWindowOrHiddenPanelsGiveTheVolumeTheWholeWindow) {
  for (const Layout& l : {compute_layout(640, 480, true, 19), compute_layout(1280, 800, false, 19),
                          compute_layout(kDockMinWidth, kDockMinHeight - 1, true, 19)}) {
    EXPECT_FALSE(l.docked);
    EXPECT_EQ(l.view.x, 0);
    EXPECT_EQ(l.view.y, 0);
    EXPECT_EQ(l.side.w, 0);
  }
  EXPECT_EQ(compute_layout(640, 480, true, 19).view, (WindowRect{0, 0, 640, 480}));
  EXPECT_TRUE(compute_layout(kDockMinWidth, kDockMinHeight, true, 19).docked);
  EXPECT_EQ(compute_layout(0, -3, true, 19).view, (WindowRect{0, 0, 1, 1}));  // minimised
}

TEST(PlayerLayout, OpacityAxisIsLinearOrLogarithmicAndInvertible) {
  for (double a : {0.0, 0.01, 0.5, 1.0}) {
    EXPECT_DOUBLE_EQ(opacity_to_axis(a, false), a);
    EXPECT_DOUBLE_EQ(axis_to_opacity(a, false), a);
  }
  // Log: decades equally spaced above the floor; 0 (and anything under the floor) at the bottom.
  EXPECT_DOUBLE_EQ(opacity_to_axis(1.0, true), 1.0);
  EXPECT_DOUBLE_EQ(opacity_to_axis(0.0, true), 0.0);
  EXPECT_DOUBLE_EQ(opacity_to_axis(kLogOpacityFloor / 2, true), 0.0);
  const double d1 = opacity_to_axis(1e-2, true) - opacity_to_axis(1e-3, true);
  const double d2 = opacity_to_axis(1e-1, true) - opacity_to_axis(1e-2, true);
  EXPECT_NEAR(d1, d2, 1e-12);
  EXPECT_GT(opacity_to_axis(1e-3, true), 0.2);  // low opacities get room to edit
  for (double a : {kLogOpacityFloor, 1e-3, 0.02, 0.3, 1.0})
    EXPECT_NEAR(axis_to_opacity(opacity_to_axis(a, true), true), a, 1e-12 * (1 + a));
  EXPECT_EQ(axis_to_opacity(0.0, true), 0.0);
  EXPECT_EQ(axis_to_opacity(-5, true), 0.0);
  EXPECT_EQ(axis_to_opacity(7, true), 1.0);
}

}  // namespace

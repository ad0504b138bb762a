// Step times as text, against dates worked by hand (and `date -u -d` for the leap years).
#include "tsp/core/time_text.h"

#include <gtest/gtest.h>

namespace tsp {
namespace {

TEST(TimeText, CfUnitsSinceADateGiveTheDate) {
  EXPECT_EQ(format_time(0, {"hours since 2005-08-28 12:00:00", ""}), "2005-08-28 12:00");
  EXPECT_EQ(format_time(9, {"hours since 2005-08-28 12:00:00", "standard"}), "2005-08-28 21:00");
  EXPECT_EQ(format_time(12, {"hours since 2005-08-28 12:00:00", "gregorian"}), "2005-08-29 00:00");
  // Across a leap day and a year end; minutes, seconds and days; a date without a time.
  EXPECT_EQ(format_time(2, {"days since 2004-02-28", ""}), "2004-03-01 00:00");
  EXPECT_EQ(format_time(1, {"days since 1999-12-31", ""}), "2000-01-01 00:00");
  EXPECT_EQ(format_time(90, {"minutes since 2000-01-01 00:00:00", ""}), "2000-01-01 01:30");
  EXPECT_EQ(format_time(32400, {"seconds since 2005-08-28 12:00:00", ""}), "2005-08-28 21:00");
  EXPECT_EQ(format_time(5, {"seconds since 2005-08-28T12:00:00", ""}), "2005-08-28 12:00:05");
  EXPECT_EQ(format_time(1.5, {"s since 2000-01-01 00:00:00", ""}), "2000-01-01 00:00:01.500");
  // Before the reference date, and before 1970.
  EXPECT_EQ(format_time(-1, {"days since 1970-01-01", ""}), "1969-12-31 00:00");
  EXPECT_EQ(format_time(0, {"days since 1850-01-01 00:00:00", "proleptic_gregorian"}),
            "1850-01-01 00:00");
}

TEST(TimeText, OtherUnitsAndCalendarsKeepTheNumber) {
  EXPECT_EQ(format_time(0.25, {}), "0.25");
  EXPECT_EQ(format_time(0.25, {"s", ""}), "0.25 s");
  EXPECT_EQ(format_time(3, {"days since 2000-01-01", "noleap"}), "3 days (noleap since 2000-01-01)");
  EXPECT_EQ(format_time(3, {"fortnights since 2000-01-01", ""}), "3 fortnights");
  EXPECT_EQ(format_time(3, {"days since the beginning", ""}), "3 days");
  EXPECT_EQ(format_time(1e300, {"days since 2000-01-01", ""}), "1e+300 days");
}

}  // namespace
}  // namespace tsp

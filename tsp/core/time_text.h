// A step's time as a person reads it: a date where the file gives CF-style units ("hours since
// 2005-08-28 12:00:00", standard calendar), else the number with its unit.
#pragma once
#include <string>

namespace tsp {

/// The units a file gives its step times: CF's `units` ("UNIT since DATE" or a plain unit) and
/// `calendar` (empty: standard). Both empty when the input named none.
struct TimeUnits {
  std::string units;
  std::string calendar;
};

/// value as text: with units "UNIT since YYYY-MM-DD[ HH:MM[:SS]]" (UNIT seconds, minutes,
/// hours or days, in CF's spellings) in the standard, gregorian or proleptic_gregorian calendar,
/// the date and time "YYYY-MM-DD HH:MM[:SS]" (UTC; seconds shown when not 0); in another
/// calendar or with another unit, "VALUE UNIT" (the reference date dropped for another
/// calendar: "3 days (noleap since 2000-01-01)"); with plain units "VALUE UNITS"; with none,
/// the number alone (%g). Never throws.
std::string format_time(double value, const TimeUnits& units);

}  // namespace tsp

#include "tsp/core/time_text.h"

#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string_view>

namespace tsp {

namespace {

constexpr double kSecondsPerDay = 86400;
constexpr double kMaxDays = 1e8;  // about 270,000 years either way: beyond, the number alone

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Seconds in one UNIT (CF's udunits spellings of the common ones); 0 when unknown.
double unit_seconds(const std::string& unit) {
  struct U {
    std::string_view name;
    double seconds;
  };
  static constexpr std::array<U, 17> kUnits{{{"seconds", 1},  {"second", 1},  {"secs", 1},
                                             {"sec", 1},      {"s", 1},       {"minutes", 60},
                                             {"minute", 60},  {"mins", 60},   {"min", 60},
                                             {"hours", 3600}, {"hour", 3600}, {"hrs", 3600},
                                             {"hr", 3600},    {"h", 3600},    {"days", 86400},
                                             {"day", 86400},  {"d", 86400}}};
  for (const U& u : kUnits)
    if (unit == u.name) return u.seconds;
  return 0;
}

// Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's days_from_civil).
std::int64_t days_from_civil(std::int64_t y, int m, int d) {
  y -= m <= 2;
  const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
  const std::int64_t yoe = y - era * 400;
  const std::int64_t doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const std::int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

// The date of days since 1970-01-01 (its inverse, civil_from_days).
void civil_from_days(std::int64_t z, std::int64_t& y, int& m, int& d) {
  z += 719468;
  const std::int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const std::int64_t doe = z - era * 146097;
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const std::int64_t mp = (5 * doy + 2) / 153;
  d = int(doy - (153 * mp + 2) / 5 + 1);
  m = int(mp < 10 ? mp + 3 : mp - 9);
  y = yoe + era * 400 + (m <= 2);
}

}  // namespace

std::string format_time(double value, const TimeUnits& u) {
  if (!std::isfinite(value)) return number(value);
  const std::string units = u.units;
  if (units.empty()) return number(value);
  const std::size_t since = lower(units).find(" since ");
  if (since == std::string::npos) return number(value) + " " + units;
  const std::string unit = units.substr(0, since);
  const std::string date = units.substr(since + 7);
  const std::string cal = lower(u.calendar);
  const bool standard = cal.empty() || cal == "standard" || cal == "gregorian" ||
                        cal == "proleptic_gregorian";
  const double per = unit_seconds(lower(unit));
  long long y = 0;
  int mo = 0, d = 0, h = 0, mi = 0;
  double s = 0;
  const int n = std::sscanf(date.c_str(), "%lld-%d-%d%*1[ T_]%d:%d:%lf", &y, &mo, &d, &h, &mi, &s);
  const bool parsed = n == 3 || n >= 5;
  if (!standard || per == 0 || !parsed || mo < 1 || mo > 12 || d < 1 || d > 31 || h < 0 ||
      h > 23 || mi < 0 || mi > 59 || !(s >= 0 && s < 61))
    return number(value) + " " + unit + (standard ? "" : " (" + u.calendar + " since " + date + ")");
  const double days = double(days_from_civil(y, mo, d)) +
                      (double(h) * 3600 + double(mi) * 60 + s + value * per) / kSecondsPerDay;
  if (!(std::fabs(days) < kMaxDays)) return number(value) + " " + unit;
  // Rounded to the millisecond, then split into the day and the time of day.
  const double ms = std::round(days * kSecondsPerDay * 1000);
  const auto total_ms = static_cast<std::int64_t>(ms);
  constexpr std::int64_t kMsPerDay = 86400000;
  std::int64_t day = total_ms / kMsPerDay, rest = total_ms % kMsPerDay;
  if (rest < 0) {
    rest += kMsPerDay;
    --day;
  }
  std::int64_t yy = 0;
  int mm = 0, dd = 0;
  civil_from_days(day, yy, mm, dd);
  const int hh = int(rest / 3600000), mn = int(rest / 60000 % 60);
  const double sec = double(rest % 60000) / 1000;
  char b[64];
  if (sec == 0)
    std::snprintf(b, sizeof b, "%04lld-%02d-%02d %02d:%02d", static_cast<long long>(yy), mm, dd, hh, mn);
  else if (sec == std::floor(sec))
    std::snprintf(b, sizeof b, "%04lld-%02d-%02d %02d:%02d:%02d", static_cast<long long>(yy), mm, dd,
                  hh, mn, int(sec));
  else
    std::snprintf(b, sizeof b, "%04lld-%02d-%02d %02d:%02d:%06.3f", static_cast<long long>(yy), mm,
                  dd, hh, mn, sec);
  return b;
}

}  // namespace tsp

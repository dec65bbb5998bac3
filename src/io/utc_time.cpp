#include "utc_time.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "tumble/error.hpp"

namespace tumble::io {
namespace {

constexpr std::int64_t kDayNs = 86'400'000'000'000;

/// Reads `count` decimal digits at `at` (advancing it); −1 when they are not all digits.
int digits(std::string_view s, size_t& at, size_t count) {
  if (at + count > s.size()) return -1;
  int v = 0;
  for (size_t k = 0; k < count; ++k, ++at) {
    const char c = s[at];
    if (c < '0' || c > '9') return -1;
    v = 10 * v + (c - '0');
  }
  return v;
}

}  // namespace

CalendarTime parse_calendar_time(std::string_view text, std::string_view what) {
  const auto fail = [&](std::string_view why) -> CalendarTime {
    throw InvalidArgument(
        fmt::format("{} {}: {}; give a date as YYYY-MM-DDThh:mm:ss[.fff], e.g. "
                    "2026-12-03T15:00:00.000 (UTC)",
                    what, text, why));
  };
  size_t at = 0;
  const int year = digits(text, at, 4);
  if (year < 0 || at >= text.size() || text[at++] != '-') return fail("the year is not 4 digits and '-'");
  const int month = digits(text, at, 2);
  if (month < 0 || at >= text.size() || text[at++] != '-') return fail("the month is not 2 digits and '-'");
  const int day = digits(text, at, 2);
  if (day < 0 || at >= text.size() || text[at++] != 'T') return fail("the day is not 2 digits and 'T'");
  const int hour = digits(text, at, 2);
  if (hour < 0 || at >= text.size() || text[at++] != ':') return fail("the hour is not 2 digits and ':'");
  const int minute = digits(text, at, 2);
  if (minute < 0 || at >= text.size() || text[at++] != ':') return fail("the minute is not 2 digits and ':'");
  const int second = digits(text, at, 2);
  if (second < 0) return fail("the seconds are not 2 digits");
  std::int64_t fraction_ns = 0;
  if (at < text.size() && text[at] == '.') {
    ++at;
    std::int64_t scale = 100'000'000;
    size_t n = 0;
    for (; at < text.size() && text[at] >= '0' && text[at] <= '9'; ++at, ++n, scale /= 10) {
      if (n == 9) return fail("more than 9 decimals of a second");
      fraction_ns += (text[at] - '0') * scale;
    }
    if (n == 0) return fail("no digit after the decimal point");
  }
  if (at < text.size() && text[at] == 'Z') ++at;
  if (at != text.size()) return fail(fmt::format("unexpected '{}' after the seconds", text.substr(at)));
  const std::chrono::year_month_day date{std::chrono::year(year),
                                         std::chrono::month(static_cast<unsigned>(month)),
                                         std::chrono::day(static_cast<unsigned>(day))};
  if (year < 1 || !date.ok()) return fail("no such day");
  if (hour > 23 || minute > 59 || second > 59) return fail("the time of day is out of range");
  const std::int64_t days = std::chrono::sys_days(date).time_since_epoch().count();
  return {days, ((hour * 60 + minute) * 60 + second) * 1'000'000'000LL + fraction_ns};
}

std::string format_calendar_time(const CalendarTime& epoch, double t) {
  if (!(std::abs(t) <= 9e9)) {
    throw InvalidArgument(
        fmt::format("a time of {} s from the epoch is beyond 285 years: no date is written "
                    "for it",
                    t));
  }
  const std::int64_t total = epoch.ns + std::llround(t * 1e9);
  std::int64_t day = total / kDayNs, ns = total % kDayNs;
  if (ns < 0) {
    ns += kDayNs;
    --day;
  }
  const std::chrono::year_month_day date{std::chrono::sys_days(std::chrono::days(epoch.days + day))};
  const int year = static_cast<int>(date.year());
  if (year < 1 || year > 9999) {
    throw InvalidArgument(
        fmt::format("the date {} s from the epoch falls in the year {}: dates are "
                    "written for the years 1 to 9999",
                    t, year));
  }
  const std::int64_t seconds = ns / 1'000'000'000, fraction = ns % 1'000'000'000;
  std::string decimals = fmt::format("{:09d}", fraction);
  while (decimals.size() > 3 && decimals.back() == '0') decimals.pop_back();
  return fmt::format("{:04d}-{:02d}-{:02d}T{:02d}:{:02d}:{:02d}.{}", year,
                     static_cast<unsigned>(date.month()), static_cast<unsigned>(date.day()), seconds / 3600,
                     seconds / 60 % 60, seconds % 60, decimals);
}

}  // namespace tumble::io

#pragma once
// Calendar dates for files that label samples with them (CCSDS messages): an epoch given as
// YYYY-MM-DDThh:mm:ss[.fff…][Z], and the date `t` seconds after it, as the same kind of string. Days
// are 86400 s: no leap second is inserted (tumble's t is uniform time; a run that spans a leap second
// would have its later labels 1 s early in UTC).
#include <cstdint>
#include <string>
#include <string_view>

namespace tumble::io {

/// A date as whole days since 1970-01-01 and nanoseconds into the day (0 ≤ ns < 86400·10⁹).
struct CalendarTime {
  std::int64_t days = 0;
  std::int64_t ns = 0;
};

/// Parses YYYY-MM-DDThh:mm:ss with an optional fraction of up to 9 digits and an optional Z. Throws
/// InvalidArgument saying what is wrong (`what` names the value in the message, e.g. "--epoch").
[[nodiscard]] CalendarTime parse_calendar_time(std::string_view text, std::string_view what);

/// `epoch` + t seconds (t rounded to the nanosecond), as YYYY-MM-DDThh:mm:ss.fff with 3 to 9 decimals
/// (as many as the nanoseconds need). Throws InvalidArgument for |t| > 9·10⁹ s (285 years) or a date
/// outside the years 0001–9999.
[[nodiscard]] std::string format_calendar_time(const CalendarTime& epoch, double t);

}  // namespace tumble::io

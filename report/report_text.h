#pragma once
// Text helpers of the HTML run report: escaping, number formatting, axis ticks.
#include <cstdint>
#include <string>
#include <vector>

namespace sacfuse {

// Escapes & < > " ' for HTML/SVG text and attribute values.
std::string EscapeHtml(const std::string& text);

// 1234567 -> "1,234,567".
std::string GroupedInteger(uint64_t value);
// 1234567 -> "1.23 M", 45600 -> "45.6 k", 999 -> "999" (three significant digits).
std::string ShortCount(double value);
// printf-style "%.*f".
std::string Fixed(double value, int decimals);
// 83.5 -> "83.5 %" from a fraction 0.835 (decimals after the point).
std::string Percent(double fraction, int decimals = 1);
// Seconds as "12.3 s", "4 min 05 s" or "1 h 02 min".
std::string Duration(double seconds);

// "Nice" tick values (1, 2, 5 x 10^k steps) covering [lo, hi] with about `target` ticks, each within [lo, hi].
std::vector<double> NiceTicks(double lo, double hi, int target);
// Shortest decimal text of a tick value at the ticks' step (e.g. 0.5 -> "0.5", 20 -> "20").
std::string TickLabel(double value, double step);

// "#rrggbb".
std::string HexColour(uint8_t r, uint8_t g, uint8_t b);

}  // namespace sacfuse

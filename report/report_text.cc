#include "report/report_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sacfuse {

std::string EscapeHtml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string GroupedInteger(uint64_t value) {
  std::string digits = std::to_string(value), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string ShortCount(double value) {
  const double a = std::abs(value);
  const char* suffix = "";
  double v = value;
  if (a >= 1e9) {
    v = value / 1e9;
    suffix = " G";
  } else if (a >= 1e6) {
    v = value / 1e6;
    suffix = " M";
  } else if (a >= 1e3) {
    v = value / 1e3;
    suffix = " k";
  }
  const double av = std::abs(v);
  const int decimals = *suffix == '\0' ? (av == std::floor(av) ? 0 : 2) : (av >= 100 ? 0 : av >= 10 ? 1 : 2);
  return Fixed(v, decimals) + suffix;
}

std::string Fixed(double value, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", std::max(0, decimals), value);
  return buf;
}

std::string Percent(double fraction, int decimals) { return Fixed(100.0 * fraction, decimals) + " %"; }

std::string Duration(double seconds) {
  char buf[64];
  if (seconds < 60.0) {
    std::snprintf(buf, sizeof(buf), "%.1f s", seconds);
  } else if (seconds < 3600.0) {
    const int s = static_cast<int>(std::lround(seconds));
    std::snprintf(buf, sizeof(buf), "%d min %02d s", s / 60, s % 60);
  } else {
    const int m = static_cast<int>(std::lround(seconds / 60.0));
    std::snprintf(buf, sizeof(buf), "%d h %02d min", m / 60, m % 60);
  }
  return buf;
}

namespace {
double NiceStep(double range, int target) {
  const double raw = range / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    if (raw <= m * mag) return m * mag;
  }
  return 10.0 * mag;
}
}  // namespace

std::vector<double> NiceTicks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  const double step = NiceStep(hi - lo, target);
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step) {
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  }
  return ticks;
}

std::string TickLabel(double value, double step) {
  int decimals = 0;
  while (decimals < 6 && std::abs(step * std::pow(10.0, decimals) - std::round(step * std::pow(10.0, decimals))) >
                             1e-6 * std::pow(10.0, decimals)) {
    ++decimals;
  }
  return Fixed(value, decimals);
}

std::string HexColour(uint8_t r, uint8_t g, uint8_t b) {
  char buf[8];
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", r, g, b);
  return buf;
}

}  // namespace sacfuse

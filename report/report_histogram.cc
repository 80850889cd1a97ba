#include "report/report_histogram.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "report/report_text.h"

namespace sacfuse {
namespace {
constexpr double kLeft = 64.0, kTop = 28.0, kRight = 12.0, kLabelSpace = 132.0;
}  // namespace

std::vector<ViewCounts> SortedByAfter(std::vector<ViewCounts> counts) {
  std::stable_sort(counts.begin(), counts.end(), [](const ViewCounts& a, const ViewCounts& b) {
    return a.after != b.after ? a.after > b.after : a.view < b.view;
  });
  return counts;
}

HistogramLayout LayoutHistogram(const std::vector<ViewCounts>& unsorted, double width_px, double plot_height_px) {
  const std::vector<ViewCounts> counts = SortedByAfter(unsorted);
  HistogramLayout l;
  l.width = width_px;
  l.plot_left = kLeft;
  l.plot_top = kTop;
  l.plot_width = std::max(10.0, width_px - kLeft - kRight);
  l.plot_height = plot_height_px;
  l.height = kTop + plot_height_px + kLabelSpace;
  l.slot = counts.empty() ? l.plot_width : l.plot_width / counts.size();
  uint64_t max_count = 0;
  for (const ViewCounts& c : counts) max_count = std::max({max_count, c.before, c.after});
  const std::vector<double> ticks = NiceTicks(0.0, std::max<double>(1.0, max_count) * 1.0000001, 5);
  // Top of the axis: the first tick step at or above the largest count.
  const double step = ticks.size() >= 2 ? ticks[1] - ticks[0] : std::max<double>(1.0, max_count);
  l.max_count = std::max(step, std::ceil(std::max<double>(1.0, max_count) / step) * step);
  for (double t = 0.0; t <= l.max_count + 1e-9 * step; t += step) l.ticks.push_back(t);
  for (size_t i = 0; i < counts.size(); ++i) {
    HistogramBar b;
    b.view = counts[i].view;
    b.x = l.plot_left + i * l.slot;
    b.before_height = counts[i].before / l.max_count * l.plot_height;
    b.after_height = counts[i].after / l.max_count * l.plot_height;
    l.bars.push_back(b);
  }
  return l;
}

std::string HistogramSvg(const std::vector<ViewCounts>& unsorted, const std::vector<Rgb>& colours, double width_px,
                         double plot_height_px) {
  const std::vector<ViewCounts> counts = SortedByAfter(unsorted);
  const HistogramLayout l = LayoutHistogram(counts, width_px, plot_height_px);
  std::ostringstream s;
  const double base = l.plot_top + l.plot_height;
  s << "<svg class='chart' width='" << Fixed(l.width, 0) << "' height='"
    << Fixed(l.height, 0) << "' viewBox='0 0 " << Fixed(l.width, 0) << " " << Fixed(l.height, 0) << "'>\n";
  // Legend.
  s << "<rect x='" << Fixed(l.plot_left, 1) << "' y='6' width='12' height='12' fill='#d9d9d9' stroke='#9a9a9a'/>"
    << "<text x='" << Fixed(l.plot_left + 17, 1) << "' y='16' class='lbl'>before: valid depth pixels</text>"
    << "<rect x='" << Fixed(l.plot_left + 190, 1) << "' y='6' width='12' height='12' fill='#4a78c2'/>"
    << "<text x='" << Fixed(l.plot_left + 207, 1) << "' y='16' class='lbl'>after: fused points (view colour)</text>\n";
  // Axis and ticks.
  for (const double t : l.ticks) {
    const double y = base - t / l.max_count * l.plot_height;
    s << "<line x1='" << Fixed(l.plot_left, 1) << "' x2='" << Fixed(l.plot_left + l.plot_width, 1) << "' y1='"
      << Fixed(y, 1) << "' y2='" << Fixed(y, 1) << "' stroke='#ececec'/>"
      << "<text x='" << Fixed(l.plot_left - 6, 1) << "' y='" << Fixed(y + 4, 1) << "' class='tick' text-anchor='end'>"
      << EscapeHtml(t == 0 ? "0" : ShortCount(t)) << "</text>\n";
  }
  // Bars: before (wide, light), after (narrower, view colour) in front.
  const double gap = std::min(2.0, 0.15 * l.slot);
  const bool labels = l.slot >= 9.0;
  const int font = static_cast<int>(std::clamp(l.slot * 0.8, 7.0, 11.0));
  for (size_t i = 0; i < l.bars.size(); ++i) {
    const HistogramBar& b = l.bars[i];
    const ViewCounts& c = counts[i];
    const Rgb rgb = b.view < colours.size() ? colours[b.view] : kUnknownViewColour;
    const double w = std::max(0.5, l.slot - gap);
    s << "<g><title>" << EscapeHtml(c.name) << " (view " << c.view << ", source ID " << c.view + 1
      << "): before " << GroupedInteger(c.before) << ", after " << GroupedInteger(c.after) << "</title>"
      << "<rect x='" << Fixed(b.x + gap / 2, 2) << "' y='" << Fixed(base - b.before_height, 2) << "' width='"
      << Fixed(w, 2) << "' height='" << Fixed(b.before_height, 2) << "' fill='#d9d9d9' stroke='#b5b5b5' "
      << "stroke-width='0.5' class='before'/>"
      << "<rect x='" << Fixed(b.x + gap / 2 + 0.2 * w, 2) << "' y='" << Fixed(base - b.after_height, 2)
      << "' width='" << Fixed(0.6 * w, 2) << "' height='" << Fixed(b.after_height, 2) << "' fill='"
      << HexColour(rgb[0], rgb[1], rgb[2]) << "' class='after'/></g>\n";
    if (labels) {
      std::string label = c.name;
      if (label.size() > 22) label = "…" + label.substr(label.size() - 21);
      const double x = b.x + l.slot / 2 + font / 3.0;
      s << "<text transform='translate(" << Fixed(x, 1) << "," << Fixed(base + 6, 1)
        << ") rotate(-60)' text-anchor='end' class='tick' style='font-size:" << font << "px'>" << EscapeHtml(label)
        << "</text>\n";
    }
  }
  s << "<line x1='" << Fixed(l.plot_left, 1) << "' x2='" << Fixed(l.plot_left + l.plot_width, 1) << "' y1='"
    << Fixed(base, 1) << "' y2='" << Fixed(base, 1) << "' stroke='#555'/>\n";
  if (!labels) {
    s << "<text x='" << Fixed(l.plot_left + l.plot_width / 2, 1) << "' y='" << Fixed(base + 20, 1)
      << "' text-anchor='middle' class='lbl'>" << counts.size()
      << " views, sorted by points after fusion (hover a bar for its view)</text>\n";
  }
  s << "</svg>";
  return s.str();
}

size_t ViewsForHalfOfPoints(const std::vector<ViewCounts>& unsorted) {
  const std::vector<ViewCounts> counts = SortedByAfter(unsorted);
  uint64_t total = 0, running = 0;
  for (const ViewCounts& c : counts) total += c.after;
  size_t n = 0;
  while (n < counts.size() && running * 2 < total) running += counts[n++].after;
  return n;
}

}  // namespace sacfuse

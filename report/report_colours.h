#pragma once
// Colours of the run report: one distinct colour per view (the map, the histogram and the cross-section use the
// same one), grouped by camera when the image names tell nadir from oblique.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sacfuse {

using Rgb = std::array<uint8_t, 3>;

enum class ViewKind { kNadir, kOblique, kUnknown };

// From the image name (case-insensitive): "nadir" -> nadir; "obl" (oblique, obl_left, ...) -> oblique;
// otherwise unknown.
ViewKind ClassifyViewName(const std::string& name);

// Whether every view is nadir or oblique by its name (and both kinds occur or at least one is named): then
// the report groups the legend by kind.
bool ViewKindsKnown(const std::vector<ViewKind>& kinds);

// One colour per view, in view order. When the kinds are known, nadir views get cool hues (cyan to violet) and
// oblique views warm ones (red to yellow-green), so the map reads as nadir vs oblique at a glance; otherwise
// hues go round the whole circle. Within a group consecutive views are spread apart (golden-ratio hue steps,
// alternating brightness), so neighbouring views of a flight line differ.
std::vector<Rgb> ViewColours(const std::vector<ViewKind>& kinds);

// HSV (h in [0, 1), s, v in [0, 1]) to 8-bit RGB.
Rgb HsvToRgb(double h, double s, double v);

// Colour of points with no known view (source ID 0 or beyond the views).
constexpr Rgb kUnknownViewColour = {128, 128, 128};

}  // namespace sacfuse

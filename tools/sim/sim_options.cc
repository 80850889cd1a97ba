#include "tools/sim/sim_options.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace sacfuse {

std::vector<std::string> SimPresetNames() { return {"tiny", "small", "medium", "dortmund"}; }

SimOptions SimPreset(const std::string& name) {
  SimOptions o;
  o.preset = name;
  if (name == "tiny") {
    // Unit tests: 60 x 60 m, 20 views (4 nadir + 16 oblique) of 320 x 240 px at 20 cm GSD from 100 m (a small
    // 3 mm / 4.8 mm camera), every ground point inside >= 5 footprints; runs in about a second.
    o.area_width_m = 60.0;
    o.area_height_m = 60.0;
    o.nadir_width_px = 320;
    o.nadir_height_px = 240;
    o.gsd_m = 0.20;
    o.nadir_focal_mm = 3.0;
    o.oblique_focal_mm = 4.8;
    o.forward_overlap = 0.6;
    o.side_overlap = 0.5;
    o.max_nadir_views = 4;
    o.max_oblique_views = 16;
  } else if (name == "small") {
    // The demo: 130 x 130 m (a few city blocks), 56 views (16 nadir + 40 oblique) of 800 x 600 px at 10 cm GSD
    // from 200 m (12 mm / 19.2 mm), 60/40 overlap; every ground point inside >= 3 footprints.
    o.area_width_m = 130.0;
    o.area_height_m = 130.0;
    o.nadir_width_px = 800;
    o.nadir_height_px = 600;
    o.gsd_m = 0.10;
    o.nadir_focal_mm = 12.0;
    o.oblique_focal_mm = 19.2;
    o.forward_overlap = 0.6;
    o.side_overlap = 0.4;
    o.max_nadir_views = 16;
    o.max_oblique_views = 40;
    o.write_consistency_graphs = false;  // 1.1 GB and ~14 s the demo does not need; --consistency-graphs for it
  } else if (name == "medium") {
    // 400 x 400 m, 100 views (25 nadir + 75 oblique) of 2000 x 1500 px at 10 cm GSD with the Dortmund optics
    // (50 / 80 mm, 6 um, 833 m above ground), 60/50 overlap.
    o.area_width_m = 400.0;
    o.area_height_m = 400.0;
    o.nadir_width_px = 2000;
    o.nadir_height_px = 1500;
    o.gsd_m = 0.10;
    o.forward_overlap = 0.6;
    o.side_overlap = 0.5;
    o.max_nadir_views = 25;
    o.max_oblique_views = 75;
    o.write_consistency_graphs = false;  // cost, see sim_options.h
  } else if (name == "dortmund") {
    // Table II of the paper: 16 nadir + 43 oblique views, 6132 x 8176 px (obliques 8176 x 6132), 50/80 mm,
    // 6 um pixels, 75/80 overlap, 10 cm GSD (833 m above ground), ~1 km2. Not for tests: hours, < 3 GB.
    o.area_width_m = 1000.0;
    o.area_height_m = 1000.0;
    o.nadir_width_px = 6132;
    o.nadir_height_px = 8176;
    o.gsd_m = 0.10;
    o.forward_overlap = 0.75;
    o.side_overlap = 0.80;
    o.max_nadir_views = 16;
    o.max_oblique_views = 43;
    o.write_consistency_graphs = false;  // cost, see sim_options.h
  } else {
    std::string names;
    for (const auto& n : SimPresetNames()) names += (names.empty() ? "" : ", ") + n;
    throw ConfigError("--preset = \"" + name + "\": unknown preset; must be one of {" + names + "}");
  }
  return o;
}

void ScaleSimPixels(double factor, SimOptions* o) {
  o->nadir_width_px = std::max(1, static_cast<int>(std::lround(o->nadir_width_px * factor)));
  o->nadir_height_px = std::max(1, static_cast<int>(std::lround(o->nadir_height_px * factor)));
  o->pixel_size_um /= factor;
  o->gsd_m /= factor;
}

}  // namespace sacfuse

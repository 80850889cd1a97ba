#include "tools/sim/sim_options.h"

#include "core/error.h"

namespace sacfuse {

std::vector<std::string> SimPresetNames() { return {"tiny", "small", "medium", "dortmund"}; }

SimOptions SimPreset(const std::string& name) {
  SimOptions o;
  o.preset = name;
  if (name == "tiny") {
    // ~60 x 60 m, small images, a handful of views: runs in seconds.
    o.area_width_m = 60.0;
    o.area_height_m = 60.0;
    o.nadir_width_px = 320;
    o.nadir_height_px = 240;
    o.gsd_m = 0.10;
  } else if (name == "small") {
    // The demo block: a few city blocks, ~150 x 150 m.
    o.area_width_m = 150.0;
    o.area_height_m = 150.0;
    o.nadir_width_px = 800;
    o.nadir_height_px = 600;
    o.gsd_m = 0.10;
  } else if (name == "medium") {
    o.area_width_m = 400.0;
    o.area_height_m = 400.0;
    o.nadir_width_px = 2000;
    o.nadir_height_px = 1500;
    o.gsd_m = 0.10;
  } else if (name == "dortmund") {
    // Table II of the paper: 16 nadir + 43 oblique views, 6132 x 8176 px, 50/80 mm, 6 um pixels, 75/80 overlap,
    // 10 cm GSD, ~1 km2.
    o.area_width_m = 1000.0;
    o.area_height_m = 1000.0;
    o.nadir_width_px = 6132;
    o.nadir_height_px = 8176;
    o.gsd_m = 0.10;
    o.max_nadir_views = 16;
    o.max_oblique_views = 43;
  } else {
    std::string names;
    for (const auto& n : SimPresetNames()) names += (names.empty() ? "" : ", ") + n;
    throw ConfigError("--preset = \"" + name + "\": unknown preset; must be one of {" + names + "}");
  }
  return o;
}

}  // namespace sacfuse

#pragma once
// The cross-section of the run report (the paper's Fig. 5/6): a thin vertical strip through a building, its
// points shown as distance along the strip vs height. Pure geometry here: choosing the strip on the fused cloud's
// top surface, testing points against it, and a bounded sample of the points drawn. Reading the points (LAS
// files, depth windows) is report/report_profile_sources.h.
//
// Strip rule (PickProfileStrip): on the top grid (report/report_top_grid.h), each cell's height above local ground
// is its top z minus the lowest top z within ground_radius_m. Among "roof" cells (all 3x3 neighbours filled, their
// top z spread <= max(flat_tolerance_m, flat_slope x cell size), so tree crowns and wall edges do not qualify)
// that are surrounded by data (each quadrant of the ground_radius_m square around them at least min_fill
// filled, so not at the block's border), the highest above ground wins (ties: first in row order); without such
// cells, the highest roof cell, else the highest cell. Candidates may be restricted to a box (`within`). The strip runs
// through that cell's centre along x or along y, whichever crosses the building (cells at least half as high
// above ground; gaps of empty cells up to max(3 cells, max_gap_m) and single low cells bridged) in the shorter
// distance, and extends beyond both building
// edges by max(margin_m, half the crossing), within [min_length_m, max_length_m] (centred on the cell when
// capped) and the grid. Its height range is that of the top surface along it, padded by max(2 m, 15 %).
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "report/report_top_grid.h"
#include "tiling/footprint.h"

namespace sacfuse {

struct ProfileStrip {
  Eigen::Vector2d start_xy = Eigen::Vector2d::Zero();  // centreline start, world metres
  Eigen::Vector2d end_xy = Eigen::Vector2d::Zero();    // centreline end
  double half_width_m = 0.1;                           // points within this distance of the centreline count
  double z_min_m = 0.0, z_max_m = 0.0;                 // top-surface height range along the strip, padded
  double relief_m = 0.0;                               // height of the chosen cell above its local ground
  Eigen::Vector2d peak_xy = Eigen::Vector2d::Zero();   // centre of the chosen cell

  double Length() const { return (end_xy - start_xy).norm(); }
  // Distance along the centreline from start_xy of a point within half_width_m of the centreline and between
  // the ends; nullopt for any other point.
  std::optional<double> Along(double x, double y) const;
  // XY bounding box of the strip (centreline grown by half_width_m).
  Box2d Box() const;
};

struct StripPickOptions {
  double half_width_m = 0.1;       // strip half width, metres (the report uses 1 GSD)
  double ground_radius_m = 15.0;   // local ground: lowest top z within this radius, metres
  double flat_tolerance_m = 0.5;   // roof cells: 3x3 top-z spread at most max(this, flat_slope x cell), metres
  double flat_slope = 1.0;         // ... i.e. slopes up to ~45 degrees count as roof
  double margin_m = 10.0;          // ground shown beyond each building edge, metres (at least)
  double max_gap_m = 2.0;          // empty cells bridged when walking across the building, metres
  double min_fill = 0.5;           // "surrounded by data": filled fraction of each quadrant around the cell
  // When not empty, only cells inside this XY box are candidates (the report passes the reference cloud's
  // bounds, so the section can be compared with it); ignored when no filled cell lies inside.
  Box2d within;
  double min_length_m = 20.0;
  double max_length_m = 150.0;
};

// Picks the strip by the rule above; nullopt for a grid without a filled cell.
std::optional<ProfileStrip> PickProfileStrip(const TopGrid& grid, const StripPickOptions& options);

// Lowest top z within `radius_cells` (a square window) of each cell, ignoring empty cells; NaN where the window
// has no filled cell. O(cells), independent of the radius.
std::vector<float> LocalMinimum(const TopGrid& grid, int radius_cells);

struct ProfilePoint {
  float along_m = 0.0f;      // distance along the strip
  float z_m = 0.0f;          // world height
  uint16_t source_id = 0;    // LAS point source ID (view index + 1); 0 = none (reference)
};

// A uniform random sample of at most `capacity` points of a stream (reservoir sampling, seeded, so the same
// stream gives the same sample), plus the number of points seen.
class ProfileSample {
 public:
  explicit ProfileSample(size_t capacity, uint64_t seed = 1);
  void Add(const ProfilePoint& p);
  const std::vector<ProfilePoint>& points() const { return points_; }
  uint64_t seen() const { return seen_; }
  size_t capacity() const { return capacity_; }

 private:
  size_t capacity_;
  uint64_t seen_ = 0;
  std::vector<ProfilePoint> points_;
  std::mt19937_64 rng_;
};

}  // namespace sacfuse

#pragma once
// Writes the HTML report of a run: DIR/report/index.html (DIR = output.dir) with its pictures (map.png,
// profile_before.png, profile_after.png) and figures.json, from the files the run left in DIR (report/report_data.h)
// plus the input views for the "before" cross-section. Bounded at block scale: fused.las is streamed once into a
// fixed-size top grid (at most max_map_cells per side), the cross-section reads only the points and depth windows
// of its strip (tile files instead of fused.las when the run was tiled), and at most max_profile_points per series
// are kept. Every file is written atomically; index.html last. On every thread: the top grid is filled in bands
// of rows, the strip's series are gathered side by side (each in a fixed order), and the pictures are drawn and
// encoded as tasks beside each other; the pictures and the page are the same for any thread count.
#include <functional>
#include <memory>
#include <string>

#include "config/job_config.h"
#include "config/output_layout.h"
#include "io/depth_block.h"
#include "report/report_figures.h"

namespace sacfuse {

struct ReportOptions {
  std::string report_dir;               // "" = <output.dir>/report
  int max_map_cells = 1200;             // top grid cells along the longer side
  double min_cell_m = 0.05;             // finest top grid cell, metres
  int map_target_px = 1000;             // cells are enlarged up to this many pixels along the longer side
  size_t max_profile_points = 60000;    // per series (before, after, reference) drawn
  int profile_max_width_px = 470;       // each of the two cross-section panels (side by side)
  int profile_min_width_px = 300;
  int profile_min_height_px = 170;
  int profile_max_height_px = 460;
  bool before_profile = true;           // read the input's depth windows for the "before" panel
  // Opens the run's input when the report needs it (the "before" panel; the per-view counts of an old
  // run_report.json). Empty or throwing: those parts are left out and a warning says why. jobs/job_report.h
  // opens config.input.
  std::function<std::unique_ptr<DepthBlock>()> open_input;
};

// The report folder of a config and options (ReportDir(config), config/output_layout.h, unless options.report_dir).
std::string ReportDir(const JobConfig& config, const ReportOptions& options);

// Writes the whole report; returns the figures' description (also in figures.json). A missing fused.las or input
// leaves the pictures that need them out (said on the page); throws only when the report folder cannot be written.
ReportFigures WriteHtmlReport(const JobConfig& config, const ReportOptions& options = {});

// Rewrites index.html alone from the current files (e.g. once eval.json exists), reusing the pictures described
// by figures.json; falls back to WriteHtmlReport when there is none.
void RewriteHtmlReportPage(const JobConfig& config, const ReportOptions& options = {});

// For the end of `sacfuse run`: WriteHtmlReport, logging the outcome; a failure is logged as a warning and never
// thrown (the report is not the run's result).
void WriteHtmlReportOrWarn(const JobConfig& config, const ReportOptions& options);

}  // namespace sacfuse

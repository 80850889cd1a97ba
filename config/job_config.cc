#include "config/job_config.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "config/config_schema.h"
#include "config/option_table.h"
#include "config/version.h"
#include "core/cell_window.h"
#include "core/error.h"
#include "io/crs.h"
#include "io/input_file.h"
#include "io/las_crs.h"
#include "io/yaml_keys.h"

namespace sacfuse {
namespace {

std::string ResolvePath(const std::string& path, const std::string& base_dir) {
  if (path.empty() || base_dir.empty()) return path;
  std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(base_dir) / p).lexically_normal().string();
}

bool IsAllowedLasScale(double scale) {
  if (!(scale > 0)) return false;
  for (double mantissa : {1.0, 0.5, 0.25}) {
    const double k = std::log10(scale / mantissa);
    if (std::abs(k - std::round(k)) < 1e-9) return true;
  }
  return false;
}

std::string Number(double v) { return OptionValueText(v); }

// input.cameras, input.depth_kind and input.cameras_crs belong to format rasters.
void CheckRasterInputKeys(const InputOptions& in, std::vector<OptionError>* errors) {
  if (in.format != "rasters") {
    if (!in.cameras.empty()) errors->push_back({"input.cameras", in.cameras, "only read by input.format: rasters"});
    if (in.depth_kind != "z") {
      errors->push_back({"input.depth_kind", in.depth_kind, "only read by input.format: rasters"});
    }
    if (!in.cameras_crs.empty()) {
      errors->push_back({"input.cameras_crs", in.cameras_crs,
                         "only read by input.format: rasters (COLMAP and OpenMVS workspaces are in crs, shifted by "
                         "input.origin_m)"});
    }
    return;
  }
  if (in.cameras.empty()) return;
  std::string ext = std::filesystem::path(in.cameras).extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext != ".yaml" && ext != ".yml" && ext != ".csv") {
    errors->push_back({"input.cameras", in.cameras, "must be a .yaml, .yml or .csv camera file"});
  }
}

// The rules a key's range cannot say: between keys, or on a key's form (CRS, LAS scale, camera file). Like the
// table's ranges, only for the keys of the method in use.
void CheckCrossKeyRules(const JobConfig& c, std::vector<OptionError>* errors) {
  // A CRS's message starts with "<key> \"<text>\": "; the error repeats key and value itself.
  auto crs_error = [&](const std::string& key, const std::string& text, const Error& e) {
    std::string why = e.what();
    const std::string prefix = key + " \"" + text + "\": ";
    if (why.rfind(prefix, 0) == 0) why = why.substr(prefix.size());
    errors->push_back({key, "\"" + text + "\"", why});
  };
  try {
    const Crs crs = ParseProjectCrs(c.crs);
    const int minor = c.output.las_version == "1.2" ? 2 : 4;
    const std::string problem = LasCrsProblem(crs, minor);
    if (!problem.empty()) {
      errors->push_back({"output.las_version", c.output.las_version,
                         problem + ": use output.las_version 1.4 (WKT) for crs \"" + c.crs + "\""});
    }
  } catch (const Error& e) {
    crs_error("crs", c.crs, e);
  }
  try {
    ParseInputCrs(c.input.cameras_crs);
    if (!c.input.cameras_crs.empty() && c.crs.empty()) {
      errors->push_back({"input.cameras_crs", "\"" + c.input.cameras_crs + "\"",
                         "positions in another CRS need the project CRS to transform them into: set crs"});
    }
  } catch (const Error& e) {
    crs_error("input.cameras_crs", c.input.cameras_crs, e);
  }
  if (c.input.origin_m.size() != 3) {
    errors->push_back({"input.origin_m", std::to_string(c.input.origin_m.size()) + " numbers",
                       "must be [east, north, height]: 3 numbers, metres"});
  }
  CheckRasterInputKeys(c.input, errors);
  if (c.output.format == "copc" && c.output.las_version != "1.4") {
    errors->push_back({"output.las_version", c.output.las_version,
                       "must be 1.4 with output.format copc (COPC is LAS 1.4, point format 7)"});
  }
  if (!IsAllowedLasScale(c.output.scale_m)) {
    errors->push_back({"output.scale_m", Number(c.output.scale_m),
                       "must be 10^k x {1, 0.5, 0.25} (e.g. 0.001, 0.0025, 0.01)"});
  }
  const FusionMethodKind method = c.fusion.method;
  const SuperpixelOptions& sp = c.fusion.sac.superpixels;
  if (method == FusionMethodKind::kSac && sp.block_size_px < 2 * std::max(sp.region_size_px, 1)) {
    errors->push_back({"superpixels.block_size_px", std::to_string(sp.block_size_px),
                       "must be >= 2 * superpixels.region_size_px (" + std::to_string(2 * sp.region_size_px) + ")"});
  }
  const TsdfOptions& ts = c.fusion.tsdf;
  if (method == FusionMethodKind::kTsdf && !(ts.truncation_gsd > ts.voxel_size_gsd)) {
    errors->push_back({"tsdf.truncation_gsd", Number(ts.truncation_gsd),
                       "must be > tsdf.voxel_size_gsd (" + Number(ts.voxel_size_gsd) + ")"});
  }
  if (!(c.tiling.z_max_m > c.tiling.z_min_m)) {
    errors->push_back(
        {"tiling.z_max_m", Number(c.tiling.z_max_m), "must be > tiling.z_min_m (" + Number(c.tiling.z_min_m) + ")"});
  }
  if (DsmWanted(c) && c.output.dsm_cell_m > 0 && c.tiling.tile_size_m > 0 &&
      !IsWholeNumberOfCells(c.tiling.tile_size_m, c.output.dsm_cell_m)) {
    errors->push_back({"output.dsm_cell_m", Number(c.output.dsm_cell_m),
                       "must divide tiling.tile_size_m (" + Number(c.tiling.tile_size_m) +
                           ") into whole cells, so that tiles share the DSM's cells"});
  }
  if (c.output.ortho == "on" && !DsmWanted(c)) {
    errors->push_back({"output.ortho", c.output.ortho,
                       "the true orthophoto is made on the DSM: set output.dsm on (or crs, for output.dsm auto), or "
                       "output.ortho auto | off"});
  }
  if (c.tiling.tile_size_m > 0 && method == FusionMethodKind::kSac && c.fusion.sac.correspondence == "dense") {
    errors->push_back({"fusion.correspondence", c.fusion.sac.correspondence,
                       "dense is not supported by tiled runs yet (tiling.tile_size_m > 0); use reprojection or "
                       "proximity"});
  }
}

// Every broken rule of `c`: the table's ranges of the keys its method reads, then the cross-key rules.
std::vector<OptionError> JobConfigErrors(const JobConfig& c) {
  JobConfig copy = c;
  std::vector<OptionError> errors = MakeOptionTable(&copy).Check(MethodScope(c.fusion.method));
  CheckCrossKeyRules(c, &errors);
  return errors;
}

// `text` as one YAML comment line (line breaks of a path or --set value shown as \\n, so they cannot end it).
std::string CommentLine(const std::string& text) {
  std::string line = "# ";
  for (const char c : text) line += c == '\n' ? "\\n" : c == '\r' ? "\\r" : std::string(1, c);
  return line + "\n";
}

// The path keys, resolved against the config file's folder when given in the file and against the current
// directory when given on the command line (ConfigOverride), as a user typing a path there means.
std::vector<std::pair<const char*, std::string*>> PathFields(JobConfig* c) {
  return {{"input.path", &c->input.path},
          {"input.cameras", &c->input.cameras},
          {"output.dir", &c->output.dir},
          {"evaluation.reference", &c->evaluation.reference},
          {"evaluation.mask", &c->evaluation.mask},
          {"fusion.superpixel_cache_dir", &c->fusion.superpixel_cache_dir}};
}

bool Overridden(const std::vector<ConfigOverride>& overrides, const std::string& key) {
  for (const ConfigOverride& o : overrides) {
    if (o.key == key) return true;
  }
  return false;
}

}  // namespace

bool DsmWanted(const JobConfig& config) {
  if (config.output.dsm == "on") return true;
  if (config.output.dsm == "off") return false;
  return config.crs.find_first_not_of(" \t") != std::string::npos;
}

bool OrthoWanted(const JobConfig& config) { return config.output.ortho != "off" && DsmWanted(config); }

void ValidateJobConfig(const JobConfig& c) {
  const std::vector<OptionError> errors = JobConfigErrors(c);
  if (!errors.empty()) throw ConfigError(OptionErrorsMessage(errors, c.source_file.empty() ? "config" : c.source_file));
}

JobConfig ParseJobConfig(const std::string& yaml_text, const std::string& source_name, const std::string& base_dir,
                         const std::vector<ConfigOverride>& overrides) {
  JobConfig config;
  config.source_file = source_name;
  config.overrides = overrides;
  YAML::Node root;
  int second_document_line = 0;
  try {
    root = LoadOneYamlDocument(yaml_text, &second_document_line);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source_name + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  if (second_document_line > 0) {
    throw ConfigError(source_name + ":" + std::to_string(second_document_line) + ": " +
                      YamlSecondDocumentProblem("a sacfuse config"));
  }
  KeyPlaces key_places;
  MakeOptionTable(&config).Parse(root, source_name, overrides, &key_places);
  const std::string cwd = overrides.empty() ? "" : std::filesystem::current_path().string();
  for (const auto& [key, field] : PathFields(&config)) {
    *field = ResolvePath(*field, Overridden(overrides, key) ? cwd : base_dir);
  }
  const std::vector<OptionError> errors = JobConfigErrors(config);
  if (!errors.empty()) throw ConfigError(OptionErrorsMessage(errors, source_name, key_places));
  return config;
}

JobConfig LoadJobConfig(const std::string& path, const std::vector<ConfigOverride>& overrides) {
  std::ifstream in;
  try {
    in = OpenInputStream(path, "config file");
  } catch (const InputError& e) {
    throw ConfigError(e.what());
  }
  std::stringstream text;
  text << in.rdbuf();
  const auto base = std::filesystem::absolute(path).parent_path().string();
  return ParseJobConfig(text.str(), path, base, overrides);
}

std::string DumpJobConfig(const JobConfig& config, bool with_comments) {
  JobConfig copy = config;
  std::string header;
  if (with_comments) {
    std::string origin = "The defaults";
    if (!config.source_file.empty()) {
      origin = "The configuration of " + config.source_file;
      for (const ConfigOverride& o : config.overrides) {
        origin += (&o == &config.overrides.front() ? " with " : " ") + o.Describe();
      }
      origin += ", every key as a run uses it";
    }
    header = CommentLine("sacfuse run configuration, written by " + FullVersionString() + ".") +
             CommentLine(origin + ".") +
             CommentLine("Every key is optional except input.path. Relative paths are resolved against the folder "
                         "of this file.");
  }
  return header + MakeOptionTable(&copy).Dump(with_comments);
}

std::vector<std::pair<std::string, std::string>> JobConfigValues(const JobConfig& config) {
  JobConfig copy = config;
  return MakeOptionTable(&copy).Values();
}

}  // namespace sacfuse

#include "tools/bench/aerial_bench_plan.h"

#include <algorithm>
#include <filesystem>

#include "core/error.h"
#include "tools/bench/child_process.h"

namespace sacfuse::bench {
namespace {

namespace fs = std::filesystem;

struct AerialDefinition {
  const char* name;
  const char* lidar_folder;   // below the LiDAR folder
  const char* lidar_pattern;  // file name, or prefix* + suffix (one '*')
  std::vector<std::string> options;
};

const std::vector<AerialDefinition>& Definitions() {
  static const std::vector<AerialDefinition> d = {
      {"montpellier", "ign_montpellier", "test_data_*.las", {"--gsd", "0.25"}},
      {"montpellier_e25", "ign_montpellier", "test_data_*.las", {"--gsd", "0.25", "--error-scale", "2.5"}},
      {"zurich", "lastools", "zurich.las", {"--gsd", "0.125", "--cell", "0.25"}},
      {"zurich_e25", "lastools", "zurich.las", {"--gsd", "0.125", "--cell", "0.25", "--error-scale", "2.5"}},
      // The third city: Saint-Barthelemy (IGN, 100 x 100 m of a built-up area, ~25 points/m2), shared as LAZ only.
      {"stbarth", "ign_tiles", "St_Barth_RGAF09_UTM20N_IGN_1988_SB_subset_100m.laz", {"--gsd", "0.125", "--cell", "0.25"}},
      {"stbarth_e25", "ign_tiles", "St_Barth_RGAF09_UTM20N_IGN_1988_SB_subset_100m.laz",
       {"--gsd", "0.125", "--cell", "0.25", "--error-scale", "2.5"}},
  };
  return d;
}

// The files of `folder` matching `pattern` (at most one '*'), sorted as the shell's glob.
std::vector<std::string> Glob(const fs::path& folder, const std::string& pattern) {
  std::vector<std::string> files;
  const size_t star = pattern.find('*');
  std::error_code ec;
  if (star == std::string::npos) {
    if (fs::is_regular_file(folder / pattern, ec)) files.push_back((folder / pattern).string());
    return files;
  }
  const std::string prefix = pattern.substr(0, star), suffix = pattern.substr(star + 1);
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() >= prefix.size() + suffix.size() && name.compare(0, prefix.size(), prefix) == 0 &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0 && it->is_regular_file(ec)) {
      files.push_back(it->path().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Why no aerial block can run ("" = they can): the folder and the interpreter.
std::string FolderProblem(const QualityBenchOptions& o, std::string* python) {
  if (o.aerial_bench_dir.empty()) {
    return "aerial-bench not found ($SACFUSE_SHARED/aerial-bench or ../shared/aerial-bench; --aerial-bench DIR)";
  }
  std::error_code ec;
  if (!fs::is_regular_file(fs::path(o.aerial_bench_dir) / "make_block.py", ec)) {
    return "aerial-bench not found: " + (fs::path(o.aerial_bench_dir) / "make_block.py").string() + " is missing";
  }
  *python = FindExecutable(o.python);
  if (python->empty()) return "no Python interpreter " + o.python + " for the aerial-bench scripts";
  return "";
}

}  // namespace

std::vector<std::string> AerialBlockNames() {
  std::vector<std::string> names;
  for (const AerialDefinition& d : Definitions()) names.push_back(d.name);
  return names;
}

std::string DefaultAerialBenchDir() { return DefaultSharedFolder("aerial-bench"); }

AerialPlan BuildAerialPlan(const QualityBenchOptions& o) {
  AerialPlan plan;
  plan.bench_dir = o.aerial_bench_dir;
  std::vector<const AerialDefinition*> wanted;
  for (const std::string& name : o.aerial_blocks) {
    const auto it = std::find_if(Definitions().begin(), Definitions().end(),
                                 [&](const AerialDefinition& d) { return name == d.name; });
    if (it == Definitions().end()) {
      std::string known;
      for (const std::string& n : AerialBlockNames()) known += (known.empty() ? "" : ", ") + n;
      throw ConfigError("--aerial-blocks: unknown block '" + name + "' (known: " + known + ")");
    }
    wanted.push_back(&*it);
  }
  const std::string problem = wanted.empty() ? "" : FolderProblem(o, &plan.python);
  for (const AerialDefinition* d : wanted) {
    const std::string scene = std::string("aerial ") + d->name;
    if (!problem.empty()) {
      plan.skipped.push_back({scene, problem});
      continue;
    }
    const fs::path folder = fs::path(o.lidar_dir) / d->lidar_folder;
    const std::vector<std::string> files = o.lidar_dir.empty() ? std::vector<std::string>{} : Glob(folder, d->lidar_pattern);
    if (files.empty()) {
      plan.skipped.push_back({scene, "LiDAR file not found: " + (folder / d->lidar_pattern).string()});
      continue;
    }
    AerialBlockSpec spec{d->name, files, {}};
    for (const std::string& file : files) {
      if (fs::path(file).extension() == ".laz") spec.laz_inputs.push_back(file);
    }
    spec.make_args.insert(spec.make_args.end(), d->options.begin(), d->options.end());
    plan.blocks.push_back(std::move(spec));
  }
  return plan;
}

}  // namespace sacfuse::bench

#include "tools/bench/aerial_bench_score.h"

#include <cmath>
#include <sstream>

#include "core/error.h"

namespace sacfuse::bench {
namespace {

using nlohmann::json;

double NumberOr(const json& j, const char* key, double fallback) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

json Number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

}  // namespace

AerialScore AerialScoreFromJson(const json& j, const std::string& source) {
  AerialScore s;
  if (!j.is_object()) throw InputError(source, "the score is not a JSON object");
  if (!j.contains("scores")) {  // our own form (AerialScoreToJson)
    s.f1_2gsd = NumberOr(j, "f1_2gsd", kNoValue);
    s.f1_5gsd = NumberOr(j, "f1_5gsd", kNoValue);
    s.points_in_mask = NumberOr(j, "points_in_mask", kNoValue);
    s.density_per_m2 = NumberOr(j, "density_per_m2", kNoValue);
    s.above_top = NumberOr(j, "above_top", kNoValue);
    return s;
  }
  try {
    const double gsd = j.at("gsd").get<double>();
    for (const json& t : j.at("scores")) {
      const double k = t.at("tau").get<double>() / gsd;
      if (std::abs(k - 2.0) < 1e-6) s.f1_2gsd = t.at("f1").get<double>();
      if (std::abs(k - 5.0) < 1e-6) s.f1_5gsd = t.at("f1").get<double>();
    }
    s.points_in_mask = j.at("points_in_mask").get<double>();
    s.density_per_m2 = j.at("density_per_m2").get<double>();
    s.above_top = j.at("diagnostics_v2").at("above_top").get<double>();
  } catch (const json::exception& e) {
    throw InputError(source, std::string("unexpected aerial-bench score: ") + e.what());
  }
  if (!std::isfinite(s.f1_2gsd) || !std::isfinite(s.f1_5gsd)) {
    throw InputError(source, "no score at 2 and 5 x GSD");
  }
  return s;
}

json AerialScoreToJson(const AerialScore& s) {
  return {{"f1_2gsd", Number(s.f1_2gsd)},
          {"f1_5gsd", Number(s.f1_5gsd)},
          {"points_in_mask", Number(s.points_in_mask)},
          {"density_per_m2", Number(s.density_per_m2)},
          {"above_top", Number(s.above_top)}};
}

AerialScore ParseScoreOutput(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] != '{') continue;
    json j;
    try {
      j = json::parse(line);
    } catch (const json::exception& e) {
      throw InputError(source, std::string("score.py's JSON line is not valid JSON: ") + e.what());
    }
    return AerialScoreFromJson(j, source);
  }
  throw InputError(source, "no JSON line from score.py");
}

AerialDsmScore AerialDsmScoreFromJson(const json& j, const std::string& source) {
  if (!j.is_object()) throw InputError(source, "the DSM score is not a JSON object");
  const json& all = j.contains("all") ? j["all"] : j;
  if (!all.is_object()) throw InputError(source, "the DSM score has no \"all\" object");
  AerialDsmScore s;
  s.completeness = NumberOr(all, "completeness", kNoValue);
  s.median_m = NumberOr(all, "median_m", kNoValue);
  s.nmad_m = NumberOr(all, "nmad_m", kNoValue);
  s.rmse_m = NumberOr(all, "rmse_m", kNoValue);
  if (j.contains("all") && !std::isfinite(s.completeness)) throw InputError(source, "no DSM completeness");
  return s;
}

json AerialDsmScoreToJson(const AerialDsmScore& s) {
  return {{"completeness", Number(s.completeness)},
          {"median_m", Number(s.median_m)},
          {"nmad_m", Number(s.nmad_m)},
          {"rmse_m", Number(s.rmse_m)}};
}

AerialDsmScore ParseScoreDsmOutput(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] != '{') continue;
    try {
      return AerialDsmScoreFromJson(json::parse(line), source);
    } catch (const json::exception& e) {
      throw InputError(source, std::string("score_dsm.py's JSON line is not valid JSON: ") + e.what());
    }
  }
  throw InputError(source, "no JSON line from score_dsm.py");
}

std::map<std::string, AerialPeer> ParsePeersJson(const json& j, const std::string& source) {
  std::map<std::string, AerialPeer> peers;
  if (!j.is_object() || !j.contains("peers") || !j["peers"].is_array()) {
    throw InputError(source, "no \"peers\" array");
  }
  for (const json& row : j["peers"]) {
    const std::string method = row.value("method", std::string());
    if (method.empty()) throw InputError(source, "a peer row without \"method\"");
    AerialPeer p;
    p.wall_s = NumberOr(row, "wall_s", kNoValue);
    p.peak_rss_mib = NumberOr(row, "peak_rss_mb", kNoValue);
    const double rc = NumberOr(row, "returncode", 0.0);
    if (rc != 0.0) {
      p.error = "peers.py " + method + " failed (returncode " + std::to_string(static_cast<int>(rc)) + ")";
    } else if (!row.contains("score") || !row["score"].is_object()) {
      p.error = "peers.py " + method + " has no score";
    } else {
      p.score = AerialScoreFromJson(row["score"], source + " (" + method + ")");
      p.ok = true;
    }
    peers[method] = p;
  }
  return peers;
}

}  // namespace sacfuse::bench

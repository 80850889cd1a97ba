#include "io/las_crs.h"

#include <algorithm>

#include "core/error.h"
#include "io/crs_impl.h"
#include "io/las_format.h"
#include "io/wkt1.h"

namespace sacfuse {
namespace lf = las_format;
namespace {

constexpr uint16_t kModelTypeProjected = 1;
constexpr uint16_t kModelTypeGeographic = 2;
constexpr uint16_t kUserDefined = 32767;
constexpr uint16_t kEpsgMetre = 9001;

LasVlr ProjectionVlr(uint16_t record_id, const std::string& description, std::vector<uint8_t> data) {
  LasVlr vlr;
  vlr.user_id = lf::kProjectionUserId;
  vlr.record_id = record_id;
  vlr.description = description;
  vlr.data = std::move(data);
  return vlr;
}

// GeoKeyDirectory payload: {1, 1, 0, n} then {id, location, count, value} per key, ascending ids.
std::vector<uint8_t> GeoKeyDirectory(std::vector<GeoKey> keys) {
  std::sort(keys.begin(), keys.end(), [](const GeoKey& a, const GeoKey& b) { return a.id < b.id; });
  std::vector<uint8_t> out(8 * (keys.size() + 1), 0);
  const uint16_t head[4] = {1, 1, 0, static_cast<uint16_t>(keys.size())};
  for (int i = 0; i < 4; ++i) lf::PutU16(&out[2 * i], head[i]);
  for (size_t k = 0; k < keys.size(); ++k) {
    const uint16_t entry[4] = {keys[k].id, keys[k].location, keys[k].count, keys[k].value};
    for (int i = 0; i < 4; ++i) lf::PutU16(&out[8 * (k + 1) + 2 * i], entry[i]);
  }
  return out;
}

GeoKey Inline(uint16_t id, uint16_t value) {
  GeoKey k;
  k.id = id;
  k.count = 1;
  k.value = value;
  return k;
}

std::string GeoKeyName(uint16_t id) {
  switch (id) {
    case kGeoKeyModelType: return "GTModelTypeGeoKey";
    case kGeoKeyCitation: return "GTCitationGeoKey";
    case kGeoKeyGeographicType: return "GeographicTypeGeoKey";
    case kGeoKeyProjectedCsType: return "ProjectedCSTypeGeoKey";
    case kGeoKeyProjLinearUnits: return "ProjLinearUnitsGeoKey";
    case kGeoKeyVerticalCsType: return "VerticalCSTypeGeoKey";
    case kGeoKeyVerticalUnits: return "VerticalUnitsGeoKey";
    default: return "GeoKey " + std::to_string(id);
  }
}

const LasVlr* FindProjectionRecord(const LasHeader& header, uint16_t record_id) {
  for (const LasVlr& vlr : header.vlrs) {
    if (vlr.user_id == lf::kProjectionUserId && vlr.record_id == record_id) return &vlr;
  }
  return nullptr;
}

int CountProjectionRecords(const LasHeader& header, uint16_t record_id) {
  int n = 0;
  for (const LasVlr& vlr : header.vlrs) n += vlr.user_id == lf::kProjectionUserId && vlr.record_id == record_id;
  return n;
}

}  // namespace

std::string LasCrsProblem(const Crs& crs, int version_minor) {
  if (version_minor != 2 && version_minor != 4) {
    return "LAS 1." + std::to_string(version_minor) + " is not written (1.2 or 1.4)";
  }
  return version_minor == 2 ? crs.impl().las12_problem : std::string();
}

LasCrsRecords LasCrsVlrs(const Crs& crs, int version_minor) {
  if (version_minor != 2 && version_minor != 4) throw Error("LAS CRS records: " + LasCrsProblem(crs, version_minor));
  LasCrsRecords out;
  if (!crs.georeferenced()) return out;
  if (version_minor == 4) {
    const std::string& wkt = crs.impl().wkt1_las;
    if (wkt.empty()) throw Error("LAS CRS records: " + crs.key() + " \"" + crs.text() + "\" has no WKT1");
    std::vector<uint8_t> data(wkt.begin(), wkt.end());
    data.push_back('\0');  // NUL-terminated, as the spec asks
    out.vlrs.push_back(ProjectionVlr(lf::kWktRecordId, "OGC coordinate system WKT", std::move(data)));
    out.global_encoding_bits = kLasGlobalEncodingWktBit;
    return out;
  }
  const std::string problem = LasCrsProblem(crs, version_minor);
  if (!problem.empty()) throw Error("LAS CRS records: " + crs.key() + " \"" + crs.text() + "\": " + problem);
  const bool projected = crs.kind() == Crs::Kind::kProjected;
  const std::string citation =
      projected ? crs.Name() + " (" + crs.Code() + "), " +
                      (crs.orthometric() ? crs.HeightName() : std::string("ellipsoidal heights")) + ", metre"
                : "sacfuse " + crs.Name() + " (WGS 84 ellipsoid), metre";
  std::vector<GeoKey> keys;
  GeoKey cite;
  cite.id = kGeoKeyCitation;
  cite.location = kLasGeoAsciiParamsRecordId;
  cite.count = static_cast<uint16_t>(citation.size() + 1);  // including the '|' terminator
  cite.value = 0;
  keys.push_back(cite);
  if (projected) {
    keys.push_back(Inline(kGeoKeyModelType, kModelTypeProjected));
    keys.push_back(Inline(kGeoKeyProjectedCsType, static_cast<uint16_t>(crs.horizontal_epsg())));
    keys.push_back(Inline(kGeoKeyProjLinearUnits, kEpsgMetre));
    if (crs.orthometric()) keys.push_back(Inline(kGeoKeyVerticalCsType, static_cast<uint16_t>(crs.vertical_epsg())));
  } else {
    keys.push_back(Inline(kGeoKeyModelType, kUserDefined));
  }
  keys.push_back(Inline(kGeoKeyVerticalUnits, kEpsgMetre));
  out.vlrs.push_back(ProjectionVlr(kLasGeoKeyDirectoryRecordId, "GeoTiff GeoKeyDirectoryTag", GeoKeyDirectory(keys)));
  std::string ascii = citation + "|";
  std::vector<uint8_t> ascii_data(ascii.begin(), ascii.end());
  ascii_data.push_back('\0');
  out.vlrs.push_back(ProjectionVlr(kLasGeoAsciiParamsRecordId, "GeoTiff GeoAsciiParamsTag", std::move(ascii_data)));
  return out;
}

void AddCrsToLasOptions(const Crs& crs, LasWriterOptions* options) {
  for (const LasVlr& vlr : options->vlrs) {
    if (vlr.user_id == lf::kProjectionUserId) {
      throw Error("LAS writer options already carry a CRS record (LASF_Projection/" + std::to_string(vlr.record_id) +
                  ")");
    }
  }
  LasCrsRecords records = LasCrsVlrs(crs, options->version_minor);
  for (LasVlr& vlr : records.vlrs) options->vlrs.push_back(std::move(vlr));
  options->global_encoding_extra_bits |= records.global_encoding_bits;
}

std::vector<GeoKey> ParseLasGeoKeys(const LasHeader& header) {
  std::vector<GeoKey> keys;
  const LasVlr* dir = FindProjectionRecord(header, kLasGeoKeyDirectoryRecordId);
  if (dir == nullptr) return keys;
  const std::vector<uint8_t>& d = dir->data;
  if (d.size() < 8) throw Error("GeoKeyDirectory: " + std::to_string(d.size()) + " bytes, shorter than its header");
  const uint16_t version = lf::GetU16(&d[0]);
  const uint16_t n = lf::GetU16(&d[6]);
  if (version != 1) throw Error("GeoKeyDirectory: KeyDirectoryVersion " + std::to_string(version) + ", expected 1");
  if (d.size() < 8u * (n + 1u)) {
    throw Error("GeoKeyDirectory: " + std::to_string(n) + " keys need " + std::to_string(8 * (n + 1)) +
                " bytes, the record has " + std::to_string(d.size()));
  }
  const LasVlr* doubles = FindProjectionRecord(header, kLasGeoDoubleParamsRecordId);
  const LasVlr* ascii = FindProjectionRecord(header, kLasGeoAsciiParamsRecordId);
  for (uint16_t k = 0; k < n; ++k) {
    const uint8_t* e = &d[8 * (k + 1)];
    GeoKey key;
    key.id = lf::GetU16(e);
    key.location = lf::GetU16(e + 2);
    key.count = lf::GetU16(e + 4);
    key.value = lf::GetU16(e + 6);
    const std::string what = "GeoKeyDirectory: " + GeoKeyName(key.id);
    if (key.location == kLasGeoDoubleParamsRecordId) {
      if (doubles == nullptr) throw Error(what + " refers to a missing GeoDoubleParamsTag (34736) record");
      if ((static_cast<size_t>(key.value) + key.count) * 8 > doubles->data.size()) {
        throw Error(what + ": doubles " + std::to_string(key.value) + "+" + std::to_string(key.count) +
                    " beyond the 34736 record");
      }
      for (uint16_t i = 0; i < key.count; ++i) key.doubles.push_back(lf::GetF64(&doubles->data[8 * (key.value + i)]));
    } else if (key.location == kLasGeoAsciiParamsRecordId) {
      if (ascii == nullptr) throw Error(what + " refers to a missing GeoAsciiParamsTag (34737) record");
      if (static_cast<size_t>(key.value) + key.count > ascii->data.size()) {
        throw Error(what + ": characters " + std::to_string(key.value) + "+" + std::to_string(key.count) +
                    " beyond the 34737 record");
      }
      key.ascii.assign(ascii->data.begin() + key.value, ascii->data.begin() + key.value + key.count);
      while (!key.ascii.empty() && (key.ascii.back() == '|' || key.ascii.back() == '\0')) key.ascii.pop_back();
    } else if (key.location != 0) {
      throw Error(what + ": unknown TIFF tag location " + std::to_string(key.location));
    }
    keys.push_back(std::move(key));
  }
  return keys;
}

LasCrsInfo ReadLasCrs(const LasHeader& header) {
  LasCrsInfo info;
  info.wkt_records = CountProjectionRecords(header, lf::kWktRecordId);
  info.geokey_records = CountProjectionRecords(header, kLasGeoKeyDirectoryRecordId);
  info.wkt = header.Wkt();
  info.geokeys = ParseLasGeoKeys(header);
  std::string definition, structure;
  if (!info.wkt.empty()) {
    const WktNode root = ParseWkt1(info.wkt);
    info.epsg = WktHorizontalEpsg(root);
    definition = info.wkt;
    structure = "WKT1 " + root.keyword + (root.values.empty() ? "" : " \"" + root.values[0] + "\"");
  } else if (!info.geokeys.empty()) {
    int model = 0, projected = 0, geographic = 0, vertical = 0;
    std::string citation;
    for (const GeoKey& k : info.geokeys) {
      if (k.location != 0) {
        if (k.id == kGeoKeyCitation) citation = k.ascii;
        continue;
      }
      if (k.id == kGeoKeyModelType) model = k.value;
      if (k.id == kGeoKeyProjectedCsType) projected = k.value;
      if (k.id == kGeoKeyGeographicType) geographic = k.value;
      if (k.id == kGeoKeyVerticalCsType) vertical = k.value;
    }
    // Some writers omit GTModelType; a code is taken unless the model type says otherwise.
    if (model != kModelTypeGeographic && projected > 0 && projected < kUserDefined) {
      info.epsg = projected;
    } else if (model != kModelTypeProjected && geographic > 0 && geographic < kUserDefined) {
      info.epsg = geographic;
    }
    if (info.epsg > 0) {
      definition = "EPSG:" + std::to_string(info.epsg) +
                   (vertical > 0 && vertical < kUserDefined ? "+" + std::to_string(vertical) : std::string());
    }
    structure = "GeoTIFF keys, model type " + std::to_string(model) +
                (citation.empty() ? "" : ", citation \"" + citation + "\"");
  } else {
    info.description = "none";
    return info;
  }
  std::string complaint;
  if (!definition.empty()) {
    try {
      const CrsLabel label = LabelCrs(definition);
      info.name = label.name;
      info.code = label.code;
    } catch (const Error& e) {
      complaint = e.what();
    }
  }
  const std::string code = !info.code.empty() ? info.code
                           : info.epsg > 0    ? "EPSG:" + std::to_string(info.epsg)
                                              : std::string();
  info.description = (code.empty() ? std::string() : code + " ") +
                     (info.name.empty() ? std::string() : "\"" + info.name + "\" ") + "(" + structure +
                     (complaint.empty() ? std::string() : "; " + complaint) + ")";
  return info;
}

}  // namespace sacfuse

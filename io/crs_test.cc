#include "io/crs.h"

#include <cmath>
#include <functional>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "io/crs_impl.h"
#include "io/crs_transform.h"
#include "tests/support/gtx_grid.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kWgs84A = 6378137.0;
constexpr double kWgs84F = 1.0 / 298.257223563;
constexpr double kGrs80F = 1.0 / 298.257222101;

// Independent reference: the Krueger series of the transverse Mercator projection to third order in n
// (K. Krueger 1912, as given by Karney 2011, "Transverse Mercator with an accuracy of a few nanometers",
// eqs. 9, 35; the form used by the Wikipedia article on UTM). Written here from the formulas, without
// PROJ; its truncation error is far below 1 mm within a UTM zone.
Eigen::Vector2d KruegerUtm(double lat_deg, double lon_deg, int zone, bool north, double f) {
  const double n = f / (2.0 - f);
  const double big_a = kWgs84A / (1.0 + n) * (1.0 + n * n / 4.0 + n * n * n * n / 64.0);
  const double alpha[3] = {n / 2.0 - 2.0 * n * n / 3.0 + 5.0 * n * n * n / 16.0,
                           13.0 * n * n / 48.0 - 3.0 * n * n * n / 5.0, 61.0 * n * n * n / 240.0};
  const double phi = lat_deg * kDeg;
  const double dlam = (lon_deg - (6.0 * zone - 183.0)) * kDeg;
  const double c = 2.0 * std::sqrt(n) / (1.0 + n);
  const double t = std::sinh(std::atanh(std::sin(phi)) - c * std::atanh(c * std::sin(phi)));
  const double xi = std::atan2(t, std::cos(dlam));
  const double eta = std::atanh(std::sin(dlam) / std::sqrt(1.0 + t * t));
  double e = eta, nn = xi;
  for (int j = 1; j <= 3; ++j) {
    e += alpha[j - 1] * std::cos(2 * j * xi) * std::sinh(2 * j * eta);
    nn += alpha[j - 1] * std::sin(2 * j * xi) * std::cosh(2 * j * eta);
  }
  return {500000.0 + 0.9996 * big_a * e, (north ? 0.0 : 10000000.0) + 0.9996 * big_a * nn};
}

// Independent reference for ENU: geodetic -> ECEF on the WGS 84 ellipsoid (textbook formula).
Eigen::Vector3d Ecef(double lat_deg, double lon_deg, double h) {
  const double e2 = kWgs84F * (2.0 - kWgs84F);
  const double sp = std::sin(lat_deg * kDeg), cp = std::cos(lat_deg * kDeg);
  const double big_n = kWgs84A / std::sqrt(1.0 - e2 * sp * sp);
  return {(big_n + h) * cp * std::cos(lon_deg * kDeg), (big_n + h) * cp * std::sin(lon_deg * kDeg),
          (big_n * (1.0 - e2) + h) * sp};
}

// Independent reference for Lambert-93 (EPSG:2154): the Lambert conformal conic projection with two standard
// parallels on the GRS 1980 ellipsoid (J. P. Snyder, "Map Projections: A Working Manual", 1987, eqs. 15-1 to 15-10
// and 14-15), written here from the formulas. Returns (E, N) and the grid convergence n (lon - lon0) in degrees.
Eigen::Vector3d Lambert93(double lat_deg, double lon_deg) {
  const double e = std::sqrt(kGrs80F * (2.0 - kGrs80F));
  const auto m = [&](double phi) { return std::cos(phi) / std::sqrt(1.0 - e * e * std::sin(phi) * std::sin(phi)); };
  const auto t = [&](double phi) {
    return std::tan(M_PI / 4.0 - phi / 2.0) / std::pow((1.0 - e * std::sin(phi)) / (1.0 + e * std::sin(phi)), e / 2.0);
  };
  const double phi1 = 49.0 * kDeg, phi2 = 44.0 * kDeg, phi0 = 46.5 * kDeg, lam0 = 3.0 * kDeg;
  const double n = (std::log(m(phi1)) - std::log(m(phi2))) / (std::log(t(phi1)) - std::log(t(phi2)));
  const double big_f = m(phi1) / (n * std::pow(t(phi1), n));
  const double rho = kWgs84A * big_f * std::pow(t(lat_deg * kDeg), n);
  const double rho0 = kWgs84A * big_f * std::pow(t(phi0), n);
  const double theta = n * (lon_deg * kDeg - lam0);
  return {700000.0 + rho * std::sin(theta), 6600000.0 + rho0 - rho * std::cos(theta), theta / kDeg};
}

Eigen::Matrix3d EnuRowsAt(double lat_deg, double lon_deg) {
  const double sp = std::sin(lat_deg * kDeg), cp = std::cos(lat_deg * kDeg);
  const double sl = std::sin(lon_deg * kDeg), cl = std::cos(lon_deg * kDeg);
  Eigen::Matrix3d m;
  m << -sl, cl, 0, -sp * cl, -sp * sl, cp, cp * cl, cp * sl, sp;
  return m;
}

// Metres between two geodetic positions that are close (for round-trip checks).
double GeodeticGapM(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double dn = (a[0] - b[0]) * kDeg * 6.4e6;
  const double de = (a[1] - b[1]) * kDeg * 6.4e6 * std::cos(a[0] * kDeg);
  return std::sqrt(dn * dn + de * de + (a[2] - b[2]) * (a[2] - b[2]));
}

void ExpectThrowsWith(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no exception";
  } catch (const Error& e) {
    for (const auto& p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
}


// What the Montpellier LiDAR tiles in ../shared carry (read with our LAS reader): Lambert-93 as WKT1.
const char* kMontpellierWkt =
    "PROJCS[\"RGF93 v1 / Lambert-93\",GEOGCS[\"RGF93 v1\",DATUM[\"Reseau_Geodesique_Francais_1993_v1\",SPHEROID["
    "\"GRS 1980\",6378137,298.257222101,AUTHORITY[\"EPSG\",\"7019\"]],AUTHORITY[\"EPSG\",\"6171\"]],PRIMEM["
    "\"Greenwich\",0,AUTHORITY[\"EPSG\",\"8901\"]],UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],"
    "AUTHORITY[\"EPSG\",\"4171\"]],PROJECTION[\"Lambert_Conformal_Conic_2SP\"],PARAMETER[\"latitude_of_origin\","
    "46.5],PARAMETER[\"central_meridian\",3],PARAMETER[\"standard_parallel_1\",49],PARAMETER["
    "\"standard_parallel_2\",44],PARAMETER[\"false_easting\",700000],PARAMETER[\"false_northing\",6600000],UNIT["
    "\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]],AXIS[\"Easting\",EAST],AXIS[\"Northing\",NORTH],AUTHORITY[\"EPSG\","
    "\"2154\"]]";

TEST(Crs, ParsesTheFormerValuesWithTheirMeaning) {
  const Crs none = ParseProjectCrs("");
  EXPECT_EQ(none.kind(), Crs::Kind::kNone);
  EXPECT_FALSE(none.georeferenced());
  EXPECT_EQ(none.Name(), "");

  const Crs etrs = ParseProjectCrs("EPSG:25832");
  EXPECT_EQ(etrs.kind(), Crs::Kind::kProjected);
  EXPECT_EQ(etrs.horizontal_epsg(), 25832);
  EXPECT_EQ(etrs.vertical_epsg(), 0);
  EXPECT_FALSE(etrs.orthometric());
  EXPECT_EQ(etrs.text(), "EPSG:25832");
  EXPECT_EQ(etrs.Code(), "EPSG:25832");
  EXPECT_EQ(etrs.Name(), "ETRS89 / UTM zone 32N");
  EXPECT_EQ(etrs.HeightName(), "ellipsoidal height");

  const Crs south = ParseProjectCrs(" epsg:32733 ");
  EXPECT_EQ(south.horizontal_epsg(), 32733);
  EXPECT_EQ(south.Name(), "WGS 84 / UTM zone 33S");
  for (const int code : {32601, 32660, 32701, 32760, 25828, 25838}) {
    EXPECT_EQ(ParseProjectCrs("EPSG:" + std::to_string(code)).horizontal_epsg(), code);
  }

  const Crs enu = ParseProjectCrs("ENU:51.5, 7.46,120");
  EXPECT_EQ(enu.kind(), Crs::Kind::kLocalEnu);
  EXPECT_EQ(enu.horizontal_epsg(), 0);
  EXPECT_EQ(enu.Code(), "");
  EXPECT_EQ(enu.enu_origin(), Eigen::Vector3d(51.5, 7.46, 120.0));
  EXPECT_EQ(enu.Name(), "local ENU at 51.5, 7.46, 120 m");
  EXPECT_EQ(ParseProjectCrs("enu:-33.9,18.4,-5").enu_origin().z(), -5.0);
}

TEST(Crs, AcceptsAnyMetricProjectedOrCompoundCrsPROJKnows) {
  const Crs lambert = ParseProjectCrs("EPSG:2154+5720");
  EXPECT_EQ(lambert.kind(), Crs::Kind::kProjected);
  EXPECT_EQ(lambert.Name(), "RGF93 v1 / Lambert-93 + NGF-IGN69 height");
  EXPECT_EQ(lambert.Code(), "EPSG:2154+5720");
  EXPECT_EQ(lambert.horizontal_epsg(), 2154);
  EXPECT_EQ(lambert.vertical_epsg(), 5720);
  EXPECT_TRUE(lambert.orthometric());
  EXPECT_EQ(lambert.HeightName(), "NGF-IGN69 height");
  // The same CRS under its own code, written out as "+EPSG:", and as a URN.
  EXPECT_EQ(ParseProjectCrs("EPSG:5698").Code(), "EPSG:5698");
  EXPECT_EQ(ParseProjectCrs("EPSG:5698").vertical_epsg(), 5720);
  EXPECT_EQ(ParseProjectCrs("EPSG:2154+EPSG:5720").Code(), "EPSG:2154+5720");
  EXPECT_EQ(ParseProjectCrs("urn:ogc:def:crs:EPSG::2154").Code(), "EPSG:2154");
  // WKT1 (the Montpellier files'), WKT2, PROJJSON, a PROJ string.
  const Crs wkt1 = ParseProjectCrs(kMontpellierWkt);
  EXPECT_EQ(wkt1.horizontal_epsg(), 2154);
  EXPECT_EQ(wkt1.Name(), "RGF93 v1 / Lambert-93");
  EXPECT_FALSE(wkt1.orthometric());
  const Crs wkt2 = ParseProjectCrs(lambert.impl().wkt2);
  EXPECT_EQ(wkt2.Code(), "EPSG:2154+5720");
  EXPECT_EQ(wkt2.vertical_epsg(), 5720);
  const Crs json = ParseProjectCrs(lambert.impl().definition);  // PROJJSON
  EXPECT_EQ(json.Name(), lambert.Name());
  EXPECT_EQ(json.vertical_epsg(), 5720);
  const Crs proj_string = ParseProjectCrs("+proj=utm +zone=32 +ellps=GRS80 +units=m +type=crs");
  EXPECT_EQ(proj_string.kind(), Crs::Kind::kProjected);
  EXPECT_EQ(proj_string.Code(), "");
  EXPECT_LT((ProjectFromGeodetic(proj_string, 51.5, 7.5, 100.0) - ProjectFromGeodetic(ParseProjectCrs("EPSG:25832"),
                                                                                       51.5, 7.5, 100.0))
                .norm(),
            1e-6);
  // A national grid whose EPSG axis order is northing first (Gauss-Krueger): coordinates stay easting, northing.
  const Eigen::Vector3d gk = ProjectFromGeodetic(ParseProjectCrs("EPSG:31467"), 51.0, 9.0, 0.0);
  EXPECT_NEAR(gk.x(), 3500000.0, 1.0);
  EXPECT_GT(gk.y(), 5.6e6);
}

TEST(Crs, RefusesWhatIsNotMetricEastNorthNamingKeyTextAndWhy) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"EPSG:4326", "geographic"},
      {"EPSG:4326+5773", "geographic"},
      {"EPSG:4978", "geocentric"},
      {"EPSG:5720", "vertical CRS"},
      {"EPSG:2263", "US survey foot"},
      {"EPSG:3413", "easting and northing"},
      {"EPSG:99999", "PROJ cannot read it"},
      {"EPSG:", "PROJ cannot read it"},
      {"UTM32N", "not a CRS definition"},
      {"WGS 84 / UTM zone 32N", "name is not accepted"},
      {"25832", "not a CRS definition"},
      {"+proj=utm +zone=32 +ellps=GRS80", "+type=crs"},
      {"ENU:51,7", "three numbers"},
      {"ENU:51,7,1,2", "three numbers"},
      {"ENU:91,7,0", "latitude"},
      {"ENU:51,181,0", "longitude"},
      {"ENU:a,7,0", "not a finite number"},
      {"ENU:nan,7,0", "not a finite number"},
  };
  for (const auto& [bad, why] : cases) {
    ExpectThrowsWith([&] { ParseProjectCrs(bad); }, {"crs \"" + bad + "\": ", why, "crs takes", "EPSG:2154+5720"});
  }
  // An input CRS may be geographic; its messages name its key.
  EXPECT_EQ(ParseInputCrs("EPSG:4979").kind(), Crs::Kind::kGeographic);
  EXPECT_EQ(ParseInputCrs("EPSG:4326").Name(), "WGS 84");
  EXPECT_EQ(ParseInputCrs("").kind(), Crs::Kind::kNone);
  ExpectThrowsWith([] { ParseInputCrs("EPSG:4978"); }, {"input.cameras_crs \"EPSG:4978\": ", "geocentric"});
}

TEST(Crs, UtmMatchesAnIndependentKruegerSeriesOverTheZone) {
  const Crs wgs = ParseProjectCrs("EPSG:32632");
  const Crs etrs = ParseProjectCrs("EPSG:25832");
  const Crs south = ParseProjectCrs("EPSG:32733");
  for (double lat = 0.0; lat <= 84.0; lat += 6.0) {
    for (double dlon = -5.5; dlon <= 5.5; dlon += 1.1) {
      const Eigen::Vector2d ref = KruegerUtm(lat, 9.0 + dlon, 32, true, kWgs84F);
      const Eigen::Vector3d p = ProjectFromGeodetic(wgs, lat, 9.0 + dlon, 12.5);
      EXPECT_LT((p.head<2>() - ref).norm(), 1e-3) << lat << " " << dlon;
      EXPECT_EQ(p.z(), 12.5);  // ellipsoidal heights pass through
      if (lat >= 36.0) {  // ETRS89's area of use (Europe) plus 3 degrees
        const Eigen::Vector2d ref_grs = KruegerUtm(lat, 9.0 + dlon, 32, true, kGrs80F);
        EXPECT_LT((ProjectFromGeodetic(etrs, lat, 9.0 + dlon, 0.0).head<2>() - ref_grs).norm(), 1e-3);
      }
      const double slat = -std::min(lat, 80.0);
      const Eigen::Vector2d ref_s = KruegerUtm(slat, 15.0 + dlon, 33, false, kWgs84F);
      EXPECT_LT((ProjectFromGeodetic(south, slat, 15.0 + dlon, 0.0).head<2>() - ref_s).norm(), 1e-3);
    }
  }
  // The equator on the central meridian is the false origin.
  EXPECT_LT((ProjectFromGeodetic(south, 0.0, 15.0, 7.0) - Eigen::Vector3d(500000.0, 10000000.0, 7.0)).norm(), 1e-6);
}

TEST(Crs, Lambert93MatchesAnIndependentLambertConicAndItsConvergence) {
  const Crs lambert = ParseProjectCrs("EPSG:2154");
  for (double lat = 42.0; lat <= 51.0; lat += 1.5) {
    for (double lon = -4.0; lon <= 8.0; lon += 2.0) {
      const Eigen::Vector3d ref = Lambert93(lat, lon);
      const Eigen::Vector3d p = ProjectFromGeodetic(lambert, lat, lon, 50.0);
      EXPECT_LT((p.head<2>() - ref.head<2>()).norm(), 1e-3) << lat << " " << lon;
      EXPECT_NEAR(GridConvergenceDeg(lambert, lat, lon), ref.z(), 1e-7) << lat << " " << lon;
      const Eigen::Vector2d back = LatLonFromProject(lambert, p);
      EXPECT_NEAR(back.x(), lat, 1e-9);
      EXPECT_NEAR(back.y(), lon, 1e-9);
    }
  }
}

TEST(Crs, UtmRoundTripsBelowAMillimetre) {
  for (const char* name : {"EPSG:25832", "EPSG:32632", "EPSG:32733"}) {
    const Crs crs = ParseProjectCrs(name);
    const bool north = crs.horizontal_epsg() != 32733;
    const double lon0 = north ? 9.0 : 15.0;
    for (double lat = north ? 36.0 : 1.0; lat < 80.0; lat += 7.3) {
      for (double dlon = -5.9; dlon <= 5.9; dlon += 1.3) {
        const Eigen::Vector3d g(north ? lat : -lat, lon0 + dlon, 123.456);
        const Eigen::Vector3d p = ProjectFromGeodetic(crs, g[0], g[1], g[2]);
        const Eigen::Vector3d back = GeodeticFromProject(crs, p);
        EXPECT_LT(GeodeticGapM(g, back), 1e-3) << name << " " << g.transpose();
        EXPECT_LT((LatLonFromProject(crs, p) - back.head<2>()).norm(), 1e-12);
        const Eigen::Vector3d again = ProjectFromGeodetic(crs, back[0], back[1], back[2]);
        EXPECT_LT((again - p).norm(), 1e-3);
      }
    }
  }
}

TEST(Crs, RefusesPointsFarOutsideTheAreaOfUse) {
  const Crs north = ParseProjectCrs("EPSG:32632");  // area of use 6..12 E, 0..84 N
  const Crs south = ParseProjectCrs("EPSG:32733");
  EXPECT_NO_THROW(ProjectFromGeodetic(north, 50.0, 14.9, 0.0));   // in zone 33, still usable with 32
  EXPECT_NO_THROW(ProjectFromGeodetic(north, 50.0, 3.1, 0.0));
  EXPECT_NO_THROW(ProjectFromGeodetic(north, -2.9, 9.0, 0.0));
  EXPECT_NO_THROW(ProjectFromGeodetic(south, -80.0, 21.0, 0.0));
  ExpectThrowsWith([&] { ProjectFromGeodetic(north, 50.0, 15.1, 0.0); },
                   {"crs \"EPSG:32632\"", "outside the area of use", "WGS 84 / UTM zone 32N", "longitude 6..12"});
  ExpectThrowsWith([&] { ProjectFromGeodetic(north, 50.0, 2.9, 0.0); }, {"area of use"});
  ExpectThrowsWith([&] { ProjectFromGeodetic(north, 50.0, -171.0, 0.0); }, {"area of use"});
  ExpectThrowsWith([&] { ProjectFromGeodetic(north, -3.1, 9.0, 0.0); }, {"area of use", "latitude 0..84"});
  ExpectThrowsWith([&] { ProjectFromGeodetic(south, 3.1, 15.0, 0.0); }, {"area of use"});
  ExpectThrowsWith([&] { ProjectFromGeodetic(north, NAN, 9.0, 0.0); }, {"not finite"});
  // Zone 1 and the antimeridian: 179 E is 4 degrees west of its central meridian (177 W), area 180..174 W.
  EXPECT_NO_THROW(ProjectFromGeodetic(ParseProjectCrs("EPSG:32601"), 10.0, 179.0, 0.0));
  EXPECT_THROW(ProjectFromGeodetic(ParseProjectCrs("EPSG:32601"), 10.0, 170.0, 0.0), Error);
}

TEST(Crs, NotGeoreferencedRefusesConversions) {
  const Crs none = ParseProjectCrs("");
  ExpectThrowsWith([&] { ProjectFromGeodetic(none, 50.0, 7.0, 0.0); }, {"crs", "empty"});
  ExpectThrowsWith([&] { GeodeticFromProject(none, Eigen::Vector3d::Zero()); }, {"crs"});
  ExpectThrowsWith([&] { ProjectFromLocalEnuRotation(none, 50.0, 7.0); }, {"crs"});
}

TEST(Crs, LocalEnuMatchesAnIndependentEcefComputation) {
  const Crs enu = ParseProjectCrs("ENU:51.5,7.46,120");
  EXPECT_LT(ProjectFromGeodetic(enu, 51.5, 7.46, 120.0).norm(), 1e-9);  // the origin
  const Eigen::Vector3d origin_ecef = Ecef(51.5, 7.46, 120.0);
  const Eigen::Matrix3d enu_from_ecef = EnuRowsAt(51.5, 7.46);
  for (const Eigen::Vector3d& g : {Eigen::Vector3d(51.501, 7.46, 120.0), Eigen::Vector3d(51.5, 7.47, 80.0),
                                  Eigen::Vector3d(51.45, 7.52, 300.0), Eigen::Vector3d(52.0, 8.0, 0.0)}) {
    const Eigen::Vector3d ref = enu_from_ecef * (Ecef(g[0], g[1], g[2]) - origin_ecef);
    const Eigen::Vector3d p = ProjectFromGeodetic(enu, g[0], g[1], g[2]);
    EXPECT_LT((p - ref).norm(), 1e-6) << g.transpose();
    EXPECT_LT(GeodeticGapM(GeodeticFromProject(enu, p), g), 1e-3);
    EXPECT_LT((LatLonFromProject(enu, p) - g.head<2>()).norm(), 1e-9);
  }
  // 0.001 degrees due north is ~111 m north, a little below the tangent plane.
  const Eigen::Vector3d north = ProjectFromGeodetic(enu, 51.501, 7.46, 120.0);
  EXPECT_NEAR(north.x(), 0.0, 1e-6);
  EXPECT_NEAR(north.y(), 111.26, 0.05);
  EXPECT_LT(north.z(), 0.0);
}

// Direction of a small geodetic step, in CRS axes (numerical, from ProjectFromGeodetic alone).
Eigen::Vector3d StepDirection(const Crs& crs, double lat, double lon, double dlat, double dlon, double dh) {
  const Eigen::Vector3d a = ProjectFromGeodetic(crs, lat, lon, 100.0);
  const Eigen::Vector3d b = ProjectFromGeodetic(crs, lat + dlat, lon + dlon, 100.0 + dh);
  return (b - a).normalized();
}

TEST(Crs, GridConvergenceHasTheRightSignAndMatchesTheGrid) {
  const Crs north = ParseProjectCrs("EPSG:25832");
  // East of the central meridian in the north: grid north is east of true north, gamma > 0, and true north
  // points to grid north-west (negative x).
  EXPECT_GT(GridConvergenceDeg(north, 51.5, 11.0), 0.0);
  EXPECT_LT(GridConvergenceDeg(north, 51.5, 7.0), 0.0);
  EXPECT_NEAR(GridConvergenceDeg(north, 51.5, 9.0), 0.0, 1e-12);
  // Spherical approximation gamma = atan(tan(dlon) sin(lat)) to 0.01 degree.
  EXPECT_NEAR(GridConvergenceDeg(north, 51.5, 11.0), std::atan(std::tan(2.0 * kDeg) * std::sin(51.5 * kDeg)) / kDeg,
              0.01);
  const Eigen::Matrix3d r = ProjectFromLocalEnuRotation(north, 51.5, 11.0);
  EXPECT_LT((r * r.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  EXPECT_LT((r * Eigen::Vector3d::UnitY()).x(), 0.0);
  // The rotation maps local east / north / up onto the directions the projection itself gives.
  for (const auto& [crs_name, lat, lon] : {std::tuple<const char*, double, double>{"EPSG:25832", 51.5, 11.0},
                                           {"EPSG:25832", 51.5, 6.5}, {"EPSG:32733", -33.0, 18.0},
                                           {"EPSG:2154+5720", 43.6, 3.87}, {"EPSG:2154", 48.8, -3.0}}) {
    const Crs crs = ParseProjectCrs(crs_name);
    if (crs.orthometric()) continue;  // StepDirection needs heights; the horizontal part is the 2D case below
    const Eigen::Matrix3d rot = ProjectFromLocalEnuRotation(crs, lat, lon);
    const double d = 1e-5;
    const Eigen::Vector3d north_dir = StepDirection(crs, lat, lon, d, 0.0, 0.0);
    const Eigen::Vector3d east_dir = StepDirection(crs, lat, lon, 0.0, d / std::cos(lat * kDeg), 0.0);
    EXPECT_LT((rot * Eigen::Vector3d::UnitY() - north_dir).norm(), 1e-6) << crs_name << " " << lon;
    EXPECT_LT((rot * Eigen::Vector3d::UnitX() - east_dir).norm(), 1e-6) << crs_name << " " << lon;
    EXPECT_LT((rot * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  }
  // A compound CRS turns attitudes like its projected part (no geoid grid needed for that).
  EXPECT_EQ(GridConvergenceDeg(ParseProjectCrs("EPSG:2154+5720"), 43.6, 3.87),
            GridConvergenceDeg(ParseProjectCrs("EPSG:2154"), 43.6, 3.87));
  // South of the equator, east of the central meridian: gamma < 0.
  EXPECT_LT(GridConvergenceDeg(ParseProjectCrs("EPSG:32733"), -33.0, 18.0), 0.0);
  EXPECT_THROW(GridConvergenceDeg(ParseProjectCrs("ENU:51,7,0"), 51.0, 7.0), Error);
}

TEST(Crs, LocalEnuRotationIsIdentityAtTheOriginAndFollowsTheTangentPlanes) {
  const Crs enu = ParseProjectCrs("ENU:51.5,7.46,120");
  EXPECT_LT((ProjectFromLocalEnuRotation(enu, 51.5, 7.46) - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  // 0.05 degrees east of the origin the local up tilts east by ~0.05 * cos(lat) degrees.
  const Eigen::Matrix3d r = ProjectFromLocalEnuRotation(enu, 51.5, 7.51);
  const Eigen::Vector3d up = r * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(std::asin(up.x()) / kDeg, 0.05 * std::cos(51.5 * kDeg), 1e-4);
  const double lat = 51.45, lon = 7.55, d = 1e-5;
  const Eigen::Matrix3d rot = ProjectFromLocalEnuRotation(enu, lat, lon);
  EXPECT_LT((rot * Eigen::Vector3d::UnitY() - StepDirection(enu, lat, lon, d, 0.0, 0.0)).norm(), 1e-6);
  EXPECT_LT((rot * Eigen::Vector3d::UnitX() - StepDirection(enu, lat, lon, 0.0, d / std::cos(lat * kDeg), 0.0))
                .norm(),
            1e-6);
  EXPECT_LT((rot * Eigen::Vector3d::UnitZ() - StepDirection(enu, lat, lon, 0.0, 0.0, 1.0)).norm(), 1e-6);
}

// A geoid model as a hand-made GTX grid (tests/support/gtx_grid.h) under RAF18's old file name: PROJ's operation
// RGF93 v1 -> NGF-IGN69 (fr_ign_RAF18.tif) finds it and applies it; without it the conversion fails naming it.
class GeoidGridTest : public ::testing::Test {
 protected:
  void TearDown() override { SetExtraProjSearchPaths({}); }
};

TEST_F(GeoidGridTest, OrthometricHeightsComeFromTheGeoidGridOrTheErrorNamesIt) {
  testing::TempDir grids;
  // Geoid heights 50 m at 42 N rising 1 m per degree of latitude, over 42..46 N, 1..6 E.
  testing::WriteGtxGrid(grids / "RAF18.gtx", 42.0, 1.0, 0.5, 9, 11, 50.0, 1.0);
  SetExtraProjSearchPaths({});
  const Crs without = ParseProjectCrs("EPSG:2154+5720");
  try {
    ProjectFromGeodetic(without, 43.6, 3.87, 150.0);
    GTEST_SKIP() << "PROJ finds a real RAF18 grid on this machine; the missing-grid message is not tested";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("crs \"EPSG:2154+5720\""), std::string::npos) << m;
    EXPECT_NE(m.find("fr_ign_RAF18.tif"), std::string::npos) << m;
    EXPECT_NE(m.find("search path"), std::string::npos) << m;
    EXPECT_NE(m.find("never downloads"), std::string::npos) << m;
  }
  // Horizontal conversions and rotations need no grid.
  EXPECT_NO_THROW(LatLonFromProject(without, Eigen::Vector3d(770500.0, 6277500.0, 40.0)));
  EXPECT_NO_THROW(ProjectFromLocalEnuRotation(without, 43.6, 3.87));

  SetExtraProjSearchPaths({grids.path().string()});
  const Crs with = ParseProjectCrs("EPSG:2154+5720");
  const Crs lambert_2d = ParseProjectCrs("EPSG:2154");
  for (const auto& [lat, lon] : {std::pair{43.6, 3.87}, std::pair{42.75, 2.2}, std::pair{45.9, 5.5}}) {
    const Eigen::Vector3d p = ProjectFromGeodetic(with, lat, lon, 150.0);
    const double geoid_m = 50.0 + (lat - 42.0);
    EXPECT_NEAR(p.z(), 150.0 - geoid_m, 1e-3) << lat << " " << lon;  // H = h - N
    EXPECT_LT((p.head<2>() - ProjectFromGeodetic(lambert_2d, lat, lon, 150.0).head<2>()).norm(), 1e-6);
    const Eigen::Vector3d back = GeodeticFromProject(with, p);
    EXPECT_LT(GeodeticGapM(back, Eigen::Vector3d(lat, lon, 150.0)), 1e-3);
  }
  // Outside the grid PROJ cannot convert: an error naming the point, never the ellipsoidal height passed on.
  ExpectThrowsWith([&] { ProjectFromGeodetic(with, 48.0, 3.0, 150.0); }, {"48", "cannot be transformed"});
}

TEST(CrsTransformTest, PositionsBetweenProjectedCrssRoundTripAndIdentityIsExact) {
  const Crs utm31 = ParseInputCrs("EPSG:32631");
  const Crs lambert = ParseProjectCrs("EPSG:2154");
  const CrsTransform t(utm31, lambert);
  EXPECT_NE(t.description().find("Lambert-93"), std::string::npos) << t.description();
  // Through the geodetic coordinates of each side (WGS 84 and RGF93 v1 differ by less than the 1 m accuracy EPSG
  // gives their null transformation, exactly 0 in PROJ).
  const Eigen::Vector3d p(570000.0, 4830000.0, 50.0);
  const Eigen::Vector3d q = t.Apply(p);
  const Eigen::Vector3d g = GeodeticFromProject(ParseProjectCrs("EPSG:32631"), p);
  EXPECT_LT((q - ProjectFromGeodetic(lambert, g.x(), g.y(), g.z())).norm(), 1e-6);
  EXPECT_LT((t.ApplyInverse(q) - p).norm(), 1e-6);
  const CrsTransform same(lambert, ParseProjectCrs("EPSG:2154"));
  EXPECT_EQ(same.description(), "identity");
  EXPECT_EQ(same.Apply(q), q);
  // Geographic positions are (lat, lon, h).
  const CrsTransform from_geo(ParseInputCrs("EPSG:4326"), lambert);
  EXPECT_LT((from_geo.Apply(Eigen::Vector3d(g.x(), g.y(), 50.0)) - q).norm(), 1e-6);
  // Into and out of a local ENU frame.
  const Crs enu = ParseProjectCrs("ENU:43.6,3.87,100");
  const CrsTransform to_enu(lambert, enu);
  const Eigen::Vector3d origin = ProjectFromGeodetic(lambert, 43.6, 3.87, 100.0);
  EXPECT_LT(to_enu.Apply(origin).norm(), 1e-6);
  EXPECT_LT((to_enu.ApplyInverse(Eigen::Vector3d(10, 20, 5)) - origin).norm(), 30.0);
}

TEST(CrsLabelTest, NamesWhatPROJReadsAndRefusesWhatItCannot) {
  const CrsLabel montpellier = LabelCrs(kMontpellierWkt);
  EXPECT_EQ(montpellier.code, "EPSG:2154");
  EXPECT_EQ(montpellier.name, "RGF93 v1 / Lambert-93");
  const CrsLabel compound = LabelCrs(ParseProjectCrs("EPSG:2154+5720").impl().wkt1_las);
  EXPECT_EQ(compound.code, "EPSG:2154+5720");
  EXPECT_EQ(compound.name, "RGF93 v1 / Lambert-93 + NGF-IGN69 height");
  EXPECT_THROW(LabelCrs("PROJCS[\"x\""), Error);
  // Labels are kept per definition (a merge labels every tile's record): asked again, from several threads at
  // once, the same answer; a definition PROJ cannot read fails every time.
  std::vector<CrsLabel> again(8);
  tbb::parallel_for(size_t{0}, again.size(), [&](size_t i) { again[i] = LabelCrs(kMontpellierWkt); });
  for (const CrsLabel& label : again) {
    EXPECT_EQ(label.code, montpellier.code);
    EXPECT_EQ(label.name, montpellier.name);
  }
  EXPECT_THROW(LabelCrs("PROJCS[\"x\""), Error);
}

}  // namespace
}  // namespace sacfuse

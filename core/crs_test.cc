#include "core/crs.h"

#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "core/error.h"

namespace sacfuse {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kWgs84A = 6378137.0;
constexpr double kWgs84F = 1.0 / 298.257223563;
constexpr double kGrs80F = 1.0 / 298.257222101;

// Independent reference: the Krueger series of the transverse Mercator projection to third order in n
// (K. Krueger 1912, as given by Karney 2011, "Transverse Mercator with an accuracy of a few nanometers",
// eqs. 9, 35; the form used by the Wikipedia article on UTM). Written here from the formulas, without
// GeographicLib; its truncation error is far below 1 mm within a UTM zone.
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

TEST(ProjectCrs, ParsesTheSupportedForms) {
  const ProjectCrs none = ParseProjectCrs("");
  EXPECT_EQ(none.kind, ProjectCrs::Kind::kNone);
  EXPECT_FALSE(none.georeferenced());

  const ProjectCrs etrs = ParseProjectCrs("EPSG:25832");
  EXPECT_EQ(etrs.kind, ProjectCrs::Kind::kUtm);
  EXPECT_EQ(etrs.epsg, 25832);
  EXPECT_EQ(etrs.utm_zone, 32);
  EXPECT_TRUE(etrs.north);
  EXPECT_EQ(etrs.datum, "ETRS89");
  EXPECT_EQ(etrs.text, "EPSG:25832");
  EXPECT_EQ(etrs.Name(), "ETRS89 / UTM zone 32N");

  const ProjectCrs south = ParseProjectCrs(" epsg:32733 ");
  EXPECT_EQ(south.epsg, 32733);
  EXPECT_EQ(south.utm_zone, 33);
  EXPECT_FALSE(south.north);
  EXPECT_EQ(south.datum, "WGS84");
  EXPECT_EQ(south.Name(), "WGS 84 / UTM zone 33S");

  EXPECT_EQ(ParseProjectCrs("EPSG:32601").utm_zone, 1);
  EXPECT_EQ(ParseProjectCrs("EPSG:32660").utm_zone, 60);
  EXPECT_EQ(ParseProjectCrs("EPSG:25828").utm_zone, 28);
  EXPECT_EQ(ParseProjectCrs("EPSG:25838").utm_zone, 38);

  const ProjectCrs enu = ParseProjectCrs("ENU:51.5, 7.46,120");
  EXPECT_EQ(enu.kind, ProjectCrs::Kind::kLocalEnu);
  EXPECT_EQ(enu.epsg, 0);
  EXPECT_DOUBLE_EQ(enu.origin_lat_deg, 51.5);
  EXPECT_DOUBLE_EQ(enu.origin_lon_deg, 7.46);
  EXPECT_DOUBLE_EQ(enu.origin_h_m, 120.0);
  EXPECT_EQ(ParseProjectCrs("enu:-33.9,18.4,-5").origin_h_m, -5.0);
}

TEST(ProjectCrs, RejectsEverythingElseNamingTheTextAndTheSupportedForms) {
  for (const std::string bad : {"EPSG:4326", "EPSG:25827", "EPSG:25839", "EPSG:32600", "EPSG:32661", "EPSG:32761",
                                "EPSG:", "EPSG:2583x", "UTM32N", "ENU:51,7", "ENU:51,7,1,2", "ENU:91,7,0",
                                "ENU:51,181,0", "ENU:a,7,0", "ENU:nan,7,0", "25832"}) {
    ExpectThrowsWith([&] { ParseProjectCrs(bad); }, {"\"" + bad + "\"", "supported", "EPSG:258zz", "ENU:lat,lon,h"});
  }
}

// Reference values from PROJ 9.1.1 (`cs2cs -f %.6f EPSG:4326 EPSG:32632`, EPSG:4258 -> EPSG:25832,
// EPSG:4326 -> EPSG:32734), an implementation independent of GeographicLib.
TEST(ProjectCrs, UtmMatchesProjToAMillimetre) {
  struct Case {
    const char* crs;
    double lat, lon, h, e, n;
  };
  const Case cases[] = {
      {"EPSG:32632", 51.5, 7.5, 100.0, 395883.554105, 5706495.877205},
      {"EPSG:32632", 51.5, 9.0, 0.0, 500000.0, 5705429.166770},
      {"EPSG:32632", 0.0, 9.0, 0.0, 500000.0, 0.0},
      {"EPSG:32632", 48.137, 11.575, 520.0, 691567.326384, 5334734.330482},
      {"EPSG:32632", 54.0, 3.2, 0.0, 120013.798482, 5999103.920182},
      {"EPSG:32632", 83.9, 9.0, 0.0, 500000.0, 9316930.154067},
      {"EPSG:25832", 51.5, 7.5, 100.0, 395883.554104, 5706495.877082},
      {"EPSG:25832", 48.137, 11.575, 520.0, 691567.326386, 5334734.330360},
      {"EPSG:32734", -33.9249, 18.4241, 0.0, 261881.598524, 6243182.354518},
  };
  for (const Case& c : cases) {
    const Eigen::Vector3d p = ProjectFromGeodetic(ParseProjectCrs(c.crs), c.lat, c.lon, c.h);
    EXPECT_NEAR(p.x(), c.e, 1e-3) << c.crs << " " << c.lat << " " << c.lon;
    EXPECT_NEAR(p.y(), c.n, 1e-3) << c.crs << " " << c.lat << " " << c.lon;
    EXPECT_EQ(p.z(), c.h);
  }
}

TEST(ProjectCrs, UtmMatchesAnIndependentKruegerSeriesOverTheZone) {
  const ProjectCrs wgs = ParseProjectCrs("EPSG:32632");
  const ProjectCrs etrs = ParseProjectCrs("EPSG:25832");
  const ProjectCrs south = ParseProjectCrs("EPSG:32733");
  for (double lat = 0.0; lat <= 84.0; lat += 6.0) {
    for (double dlon = -5.5; dlon <= 5.5; dlon += 1.1) {
      const Eigen::Vector2d ref = KruegerUtm(lat, 9.0 + dlon, 32, true, kWgs84F);
      const Eigen::Vector3d p = ProjectFromGeodetic(wgs, lat, 9.0 + dlon, 0.0);
      EXPECT_LT((p.head<2>() - ref).norm(), 1e-3) << lat << " " << dlon;
      const Eigen::Vector2d ref_grs = KruegerUtm(lat, 9.0 + dlon, 32, true, kGrs80F);
      EXPECT_LT((ProjectFromGeodetic(etrs, lat, 9.0 + dlon, 0.0).head<2>() - ref_grs).norm(), 1e-3);
      const double slat = -std::min(lat, 80.0);
      const Eigen::Vector2d ref_s = KruegerUtm(slat, 15.0 + dlon, 33, false, kWgs84F);
      EXPECT_LT((ProjectFromGeodetic(south, slat, 15.0 + dlon, 0.0).head<2>() - ref_s).norm(), 1e-3);
    }
  }
  // The equator on the central meridian is the false origin.
  EXPECT_LT((ProjectFromGeodetic(south, 0.0, 15.0, 7.0) - Eigen::Vector3d(500000.0, 10000000.0, 7.0)).norm(), 1e-6);
}

TEST(ProjectCrs, UtmRoundTripsBelowAMillimetre) {
  for (const char* name : {"EPSG:25832", "EPSG:32632", "EPSG:32733"}) {
    const ProjectCrs crs = ParseProjectCrs(name);
    const double lon0 = 6.0 * crs.utm_zone - 183.0;
    for (double lat = 1.0; lat < 80.0; lat += 7.3) {
      for (double dlon = -5.9; dlon <= 5.9; dlon += 1.3) {
        const Eigen::Vector3d g(crs.north ? lat : -lat, lon0 + dlon, 123.456);
        const Eigen::Vector3d p = ProjectFromGeodetic(crs, g[0], g[1], g[2]);
        const Eigen::Vector3d back = GeodeticFromProject(crs, p);
        EXPECT_LT(GeodeticGapM(g, back), 1e-3) << name << " " << g.transpose();
        const Eigen::Vector3d again = ProjectFromGeodetic(crs, back[0], back[1], back[2]);
        EXPECT_LT((again - p).norm(), 1e-3);
      }
    }
  }
}

TEST(ProjectCrs, UtmRefusesPointsOutsideTheZoneBand) {
  const ProjectCrs north = ParseProjectCrs("EPSG:25832");
  const ProjectCrs south = ParseProjectCrs("EPSG:32733");
  EXPECT_NO_THROW(ProjectFromGeodetic(north, 0.0, 9.0, 0.0));
  EXPECT_NO_THROW(ProjectFromGeodetic(north, 84.0, 3.0, 0.0));
  EXPECT_NO_THROW(ProjectFromGeodetic(north, 50.0, 14.9, 0.0));   // in zone 33, still usable with 32
  EXPECT_NO_THROW(ProjectFromGeodetic(south, -80.0, 21.0, 0.0));
  ExpectThrowsWith([&] { ProjectFromGeodetic(north, -0.5, 9.0, 0.0); }, {"EPSG:25832", "valid band", "0..84 N"});
  ExpectThrowsWith([&] { ProjectFromGeodetic(north, 84.5, 9.0, 0.0); }, {"valid band"});
  ExpectThrowsWith([&] { ProjectFromGeodetic(north, 50.0, 15.1, 0.0); }, {"valid band", "central meridian 9"});
  ExpectThrowsWith([&] { ProjectFromGeodetic(north, 50.0, 2.9, 0.0); }, {"valid band"});
  ExpectThrowsWith([&] { ProjectFromGeodetic(north, 50.0, -171.0, 0.0); }, {"valid band"});
  ExpectThrowsWith([&] { ProjectFromGeodetic(south, 0.5, 15.0, 0.0); }, {"valid band", "80 S..0"});
  ExpectThrowsWith([&] { ProjectFromGeodetic(south, -80.5, 15.0, 0.0); }, {"valid band"});
  ExpectThrowsWith([&] { ProjectFromGeodetic(north, NAN, 9.0, 0.0); }, {"not finite"});
  // Zone 1 wraps around the antimeridian: 179 E is 4 degrees west of its central meridian (177 W).
  EXPECT_NO_THROW(ProjectFromGeodetic(ParseProjectCrs("EPSG:32601"), 10.0, 179.0, 0.0));
}

TEST(ProjectCrs, NotGeoreferencedRefusesConversions) {
  const ProjectCrs none = ParseProjectCrs("");
  ExpectThrowsWith([&] { ProjectFromGeodetic(none, 50.0, 7.0, 0.0); }, {"crs", "empty"});
  ExpectThrowsWith([&] { GeodeticFromProject(none, Eigen::Vector3d::Zero()); }, {"crs"});
  ExpectThrowsWith([&] { ProjectFromLocalEnuRotation(none, 50.0, 7.0); }, {"crs"});
}

TEST(ProjectCrs, LocalEnuMatchesAnIndependentEcefComputation) {
  const ProjectCrs enu = ParseProjectCrs("ENU:51.5,7.46,120");
  EXPECT_LT(ProjectFromGeodetic(enu, 51.5, 7.46, 120.0).norm(), 1e-9);  // the origin
  const Eigen::Vector3d origin_ecef = Ecef(51.5, 7.46, 120.0);
  const Eigen::Matrix3d enu_from_ecef = EnuRowsAt(51.5, 7.46);
  for (const Eigen::Vector3d& g : {Eigen::Vector3d(51.501, 7.46, 120.0), Eigen::Vector3d(51.5, 7.47, 80.0),
                                  Eigen::Vector3d(51.45, 7.52, 300.0), Eigen::Vector3d(52.0, 8.0, 0.0)}) {
    const Eigen::Vector3d ref = enu_from_ecef * (Ecef(g[0], g[1], g[2]) - origin_ecef);
    const Eigen::Vector3d p = ProjectFromGeodetic(enu, g[0], g[1], g[2]);
    EXPECT_LT((p - ref).norm(), 1e-6) << g.transpose();
    EXPECT_LT(GeodeticGapM(GeodeticFromProject(enu, p), g), 1e-3);
  }
  // 0.001 degrees due north is ~111 m north, a little below the tangent plane.
  const Eigen::Vector3d north = ProjectFromGeodetic(enu, 51.501, 7.46, 120.0);
  EXPECT_NEAR(north.x(), 0.0, 1e-6);
  EXPECT_NEAR(north.y(), 111.26, 0.05);
  EXPECT_LT(north.z(), 0.0);
}

// Direction of a small geodetic step, in project axes (numerical, from ProjectFromGeodetic alone).
Eigen::Vector3d StepDirection(const ProjectCrs& crs, double lat, double lon, double dlat, double dlon, double dh) {
  const Eigen::Vector3d a = ProjectFromGeodetic(crs, lat, lon, 100.0);
  const Eigen::Vector3d b = ProjectFromGeodetic(crs, lat + dlat, lon + dlon, 100.0 + dh);
  return (b - a).normalized();
}

TEST(ProjectCrs, UtmConvergenceHasTheRightSignAndMatchesTheGrid) {
  const ProjectCrs north = ParseProjectCrs("EPSG:25832");
  // East of the central meridian in the north: grid north is east of true north, gamma > 0, and true north
  // points to grid north-west (negative x).
  EXPECT_GT(UtmConvergenceDeg(north, 51.5, 11.0), 0.0);
  EXPECT_LT(UtmConvergenceDeg(north, 51.5, 7.0), 0.0);
  EXPECT_NEAR(UtmConvergenceDeg(north, 51.5, 9.0), 0.0, 1e-12);
  // Spherical approximation gamma = atan(tan(dlon) sin(lat)) to 0.01 degree.
  EXPECT_NEAR(UtmConvergenceDeg(north, 51.5, 11.0), std::atan(std::tan(2.0 * kDeg) * std::sin(51.5 * kDeg)) / kDeg,
              0.01);
  const Eigen::Matrix3d r = ProjectFromLocalEnuRotation(north, 51.5, 11.0);
  EXPECT_LT((r * r.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  EXPECT_LT((r * Eigen::Vector3d::UnitY()).x(), 0.0);
  // The rotation maps local east / north / up onto the directions the projection itself gives.
  for (const auto& [crs_name, lat, lon] : {std::tuple<const char*, double, double>{"EPSG:25832", 51.5, 11.0},
                                           {"EPSG:25832", 51.5, 6.5}, {"EPSG:32733", -33.0, 18.0}}) {
    const ProjectCrs crs = ParseProjectCrs(crs_name);
    const Eigen::Matrix3d rot = ProjectFromLocalEnuRotation(crs, lat, lon);
    const double d = 1e-5;
    const Eigen::Vector3d north_dir = StepDirection(crs, lat, lon, d, 0.0, 0.0);
    const Eigen::Vector3d east_dir = StepDirection(crs, lat, lon, 0.0, d / std::cos(lat * kDeg), 0.0);
    EXPECT_LT((rot * Eigen::Vector3d::UnitY() - north_dir).norm(), 1e-6) << crs_name << " " << lon;
    EXPECT_LT((rot * Eigen::Vector3d::UnitX() - east_dir).norm(), 1e-6) << crs_name << " " << lon;
    EXPECT_LT((rot * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  }
  // South of the equator, east of the central meridian: gamma < 0.
  EXPECT_LT(UtmConvergenceDeg(ParseProjectCrs("EPSG:32733"), -33.0, 18.0), 0.0);
  EXPECT_THROW(UtmConvergenceDeg(ParseProjectCrs("ENU:51,7,0"), 51.0, 7.0), Error);
}

TEST(ProjectCrs, LocalEnuRotationIsIdentityAtTheOriginAndFollowsTheTangentPlanes) {
  const ProjectCrs enu = ParseProjectCrs("ENU:51.5,7.46,120");
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

}  // namespace
}  // namespace sacfuse

// The slide's shape and motion along the base (morphology.hpp) on particle
// sets built by hand with known geometry, locate_on_base (base.hpp)
// itself, and the at-rest test that reads them (rest_detector.hpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "runout/measure/basal_fill.hpp"
#include "runout/measure/morphology.hpp"
#include "runout/measure/remoulded_mass.hpp"
#include "runout/mpm/base.hpp"
#include "runout/run/rest_detector.hpp"

namespace fs = std::filesystem;
using namespace runout;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSpacing = 0.25;
constexpr double kMass = 2.0;

struct Seed {
  double x, y, vx = 0.0, vy = 0.0;
};

Particles make_particles(const std::vector<Seed>& seeds) {
  Particles P;
  P.resize(static_cast<int>(seeds.size()));
  for (int p = 0; p < P.size(); ++p) {
    P.x[p] = seeds[p].x;
    P.y[p] = seeds[p].y;
    P.vx[p] = seeds[p].vx;
    P.vy[p] = seeds[p].vy;
    P.mass[p] = kMass;
    P.id[p] = p;
  }
  return P;
}

// A local frame on the base: origin, unit tangent (u) and normal (v).
struct Frame {
  double ox, oy, tx, ty;
  double nx() const { return -ty; }
  double ny() const { return tx; }
  Seed at(double u, double v) const {
    return Seed{ox + u * tx + v * nx(), oy + u * ty + v * ny()};
  }
};

Frame planar_frame(double y0) { return Frame{0.0, y0, 1.0, 0.0}; }

// Particle centres on a kSpacing lattice over u in [u0, u1], v in [0, top(u)):
// a column at each u0 + (i + 1/2) spacing holds the centres below top(u).
std::vector<Seed> lattice(const Frame& f, double u0, double u1,
                          const std::function<double(double)>& top) {
  std::vector<Seed> out;
  for (double u = u0 + 0.5 * kSpacing; u < u1; u += kSpacing)
    for (double v = 0.5 * kSpacing; v < top(u); v += kSpacing) out.push_back(f.at(u, v));
  return out;
}

std::vector<Seed> rectangle(const Frame& f, double u0, double u1, double height) {
  return lattice(f, u0, u1, [height](double) { return height; });
}

std::vector<Seed> joined(std::vector<Seed> a, const std::vector<Seed>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

BaseView planar_base(double y0) {
  BaseView b;
  b.kind = BaseKind::Planar;
  b.y0 = y0;
  return b;
}

Base polyline_base(const std::vector<Eigen::Vector2d>& points) {
  BaseSpec spec;
  spec.kind = BaseKind::Polyline;
  spec.points = points;
  return Base(spec, 0.0);
}

Eigen::Vector2d along(double length, double dip_deg) {
  const double a = dip_deg * kPi / 180.0;
  return length * Eigen::Vector2d(std::cos(a), -std::sin(a));
}

// The escarpment's transect: 100 m at 13.75 degrees, then 100 m at 1 degree.
Base escarpment() {
  const Eigen::Vector2d p0(0.0, 50.0), p1 = p0 + along(100.0, 13.75), p2 = p1 + along(100.0, 1.0);
  return polyline_base({p0, p1, p2});
}

Frame segment_frame(const BaseView& b, int k) {
  const double ex = b.px[k + 1] - b.px[k], ey = b.py[k + 1] - b.py[k];
  const double len = std::hypot(ex, ey);
  return Frame{b.px[k], b.py[k], ex / len, ey / len};
}

// ---------------------------------------------------------------- base.hpp

TEST(LocateOnBase, PlanarIsXAndHeightAboveTheLine) {
  const BasePoint b = locate_on_base(planar_base(1.0), 3.0, 5.0);
  EXPECT_DOUBLE_EQ(b.s, 3.0);
  EXPECT_DOUBLE_EQ(b.d, 4.0);
  EXPECT_DOUBLE_EQ(b.nx, 0.0);
  EXPECT_DOUBLE_EQ(b.ny, 1.0);
  EXPECT_DOUBLE_EQ(locate_on_base(planar_base(1.0), 3.0, -1.0).d, -2.0);
}

// Points at distance +-d along the normal of each segment, including the
// extensions beyond both ends, come back with their arc length and signed
// distance.
TEST(LocateOnBase, PolylineGivesArcLengthAndSignedDistance) {
  const Base base = escarpment();
  const BaseView b = base.view();
  ASSERT_NEAR(b.ps[1], 100.0, 1e-12);
  ASSERT_NEAR(b.ps[2], 200.0, 1e-12);
  for (const double s : {-20.0, 5.0, 60.0, 97.0, 103.0, 150.0, 199.0, 240.0}) {
    for (const double d : {2.0, -2.0, 0.5, -0.5}) {
      const Frame f = segment_frame(b, s < 100.0 ? 0 : 1);
      const double u = s < 100.0 ? s : s - 100.0;
      const Seed p = f.at(u, d);
      const BasePoint bp = locate_on_base(b, p.x, p.y);
      EXPECT_NEAR(bp.s, s, 1e-9) << "s " << s << " d " << d;
      EXPECT_NEAR(bp.d, d, 1e-9) << "s " << s << " d " << d;
      EXPECT_NEAR(bp.nx, f.nx(), 1e-12);
      EXPECT_NEAR(bp.ny, f.ny(), 1e-12);
    }
  }
}

// Above a convex corner (flat, then dipping 30 degrees) the closest base
// point is the corner itself for a whole fan of directions.
TEST(LocateOnBase, AboveAConvexCornerIsTheCorner) {
  const Eigen::Vector2d p0(0.0, 0.0), p1(50.0, 0.0), p2 = p1 + along(50.0, 30.0);
  const Base base = polyline_base({p0, p1, p2});
  const double a = 15.0 * kPi / 180.0;  // bisector of the two normals
  const BasePoint bp = locate_on_base(base.view(), 50.0 + 3.0 * std::sin(a), 3.0 * std::cos(a));
  EXPECT_NEAR(bp.s, 50.0, 1e-9);
  EXPECT_NEAR(bp.d, 3.0, 1e-9);
}

TEST(BaseFrameAt, IsTheInverseOfLocateOnBase) {
  const Base base = escarpment();
  const BaseView b = base.view();
  // Not at the concave corner s = 100: the point above it is closer to the
  // first segment (docs/morphology.md, "Corners of a polyline base").
  for (const double s : {-10.0, 0.0, 42.0, 99.0, 101.0, 130.0, 200.0, 230.0}) {
    const BaseFrame f = base_frame_at(b, s);
    EXPECT_NEAR(f.tx * f.tx + f.ty * f.ty, 1.0, 1e-12);
    EXPECT_NEAR(f.nx, -f.ty, 1e-15);
    EXPECT_NEAR(f.ny, f.tx, 1e-15);
    const BasePoint bp = locate_on_base(b, f.x + 1.5 * f.nx, f.y + 1.5 * f.ny);
    EXPECT_NEAR(bp.s, s, 1e-9) << s;
    EXPECT_NEAR(bp.d, 1.5, 1e-9) << s;
  }
  const BaseFrame corner = base_frame_at(b, 100.0);
  EXPECT_NEAR(corner.x, b.px[1], 1e-12);
  EXPECT_NEAR(corner.y, b.py[1], 1e-12);
  const BaseFrame planar = base_frame_at(planar_base(2.0), 7.0);
  EXPECT_DOUBLE_EQ(planar.x, 7.0);
  EXPECT_DOUBLE_EQ(planar.y, 2.0);
  EXPECT_DOUBLE_EQ(planar.ny, 1.0);
}

// ---------------------------------------------------------- measure_slide

TEST(MeasureSlide, RectangleOnAPlanarBase) {
  const double y0 = 0.5;
  const Particles P = make_particles(rectangle(planar_frame(y0), 2.0, 12.0, 3.0));
  const SlideMorphology m = measure_slide(P, planar_base(y0), kSpacing);
  const double tol = 0.5 * kSpacing;
  EXPECT_NEAR(m.toe_s, 12.0, tol);
  EXPECT_NEAR(m.rear_s, 2.0, tol);
  EXPECT_NEAR(m.length, 10.0, tol);
  EXPECT_NEAR(m.centroid_x, 7.0, tol);
  EXPECT_NEAR(m.centroid_y, y0 + 1.5, tol);
  EXPECT_NEAR(m.centroid_s, 7.0, tol);
  EXPECT_NEAR(m.max_thickness, 3.0, tol);
  EXPECT_EQ(m.particles, P.size());
  EXPECT_EQ(m.outside_mass, 0.0);

  // Thickness reaches the top particles' upper edge: exactly the height.
  for (const ProfileBin& bin : slide_profile(P, planar_base(y0), kSpacing, kSpacing).bins) {
    EXPECT_NEAR(bin.thickness, 3.0, 1e-12) << bin.s;
    EXPECT_NEAR(bin.y_surface, y0 + 3.0, 1e-12) << bin.s;
  }
}

TEST(MeasureSlide, AStrayParticleFarAheadIsOutsideTheMainBody) {
  const Frame f = planar_frame(0.0);
  const std::vector<Seed> body = rectangle(f, 0.0, 10.0, 2.0);
  const SlideMorphology alone = measure_slide(make_particles(body), planar_base(0.0), kSpacing);

  // 20 spacings ahead of the front particle: beyond any bridged gap.
  const Particles with_stray = make_particles(joined(body, {f.at(10.0 + 20 * kSpacing, 0.1)}));
  const SlideMorphology m = measure_slide(with_stray, planar_base(0.0), kSpacing);
  EXPECT_EQ(m.toe_s, alone.toe_s);
  EXPECT_EQ(m.particles, alone.particles);
  EXPECT_EQ(m.centroid_s, alone.centroid_s);
  EXPECT_EQ(m.outside_mass, kMass);

  // 5 spacings ahead: within the bridged gap, so part of the main body.
  const double near_s = 10.0 - 0.5 * kSpacing + 5 * kSpacing;
  const Particles with_near = make_particles(joined(body, {f.at(near_s, 0.1)}));
  const SlideMorphology n = measure_slide(with_near, planar_base(0.0), kSpacing);
  EXPECT_DOUBLE_EQ(n.toe_s, near_s + 0.5 * kSpacing);
  EXPECT_EQ(n.outside_mass, 0.0);
}

// The mass front: 95 % of a uniform 12.5 m layer's mass lies behind the
// column at 95 % of its length (the 48th of 50 columns, centre 11.875 m).
// When the front column (2 % of the mass) breaks away, the main body's toe
// steps back a column and the mass front stays where it was.
TEST(MeasureSlide, TheMassFrontDoesNotJumpWhenAFrontBlockBreaksAway) {
  const Frame f = planar_frame(0.0);
  const std::vector<Seed> body = rectangle(f, 0.0, 12.5, 2.0);
  const SlideMorphology whole = measure_slide(make_particles(body), planar_base(0.0), kSpacing);
  EXPECT_NEAR(whole.mass_front_s, 47.5 * kSpacing, 1e-9);
  EXPECT_NEAR(whole.toe_s, 12.5, 1e-9);

  std::vector<Seed> parted = body;
  for (Seed& p : parted)
    if (p.x > 12.5 - kSpacing) p.x += 20.0;
  const SlideMorphology m = measure_slide(make_particles(parted), planar_base(0.0), kSpacing);
  EXPECT_NEAR(m.toe_s, 12.5 - kSpacing, 1e-9);
  EXPECT_NEAR(m.outside_mass, 0.02 * 400 * kMass, 1e-9);
  EXPECT_EQ(m.mass_front_s, whole.mass_front_s);
}

// A heavy block at rest and a light one 10 m ahead of it moving at 2 m/s:
// the blocks' speed is 2 sqrt(m_light / M), though the main body (the heavy
// block) is still. Noise inside a block (alternate particles at +-1 m/s)
// carries no mean momentum and adds nothing.
TEST(MeasureSlide, TheBlocksSpeedSeesABlockThatRunsOnAndNotNoise) {
  const Frame f = planar_frame(0.0);
  std::vector<Seed> heavy = rectangle(f, 0.0, 6.0, 2.0);
  std::vector<Seed> light = rectangle(f, 16.0, 18.0, 2.0);
  for (Seed& p : light) p.vx = 2.0;
  const double share = static_cast<double>(light.size()) / (heavy.size() + light.size());
  const SlideMorphology m =
      measure_slide(make_particles(joined(heavy, light)), planar_base(0.0), kSpacing);
  EXPECT_NEAR(m.toe_s, 6.0, 1e-9);  // the main body: the heavy block
  EXPECT_EQ(m.toe_velocity, 0.0);
  EXPECT_NEAR(m.block_speed, 2.0 * std::sqrt(share), 1e-12);

  for (std::size_t p = 0; p < heavy.size(); ++p) heavy[p].vx = p % 2 == 0 ? 1.0 : -1.0;
  const SlideMorphology noisy = measure_slide(make_particles(heavy), planar_base(0.0), kSpacing);
  EXPECT_GT(noisy.max_speed, 0.99);
  EXPECT_NEAR(noisy.block_speed, 0.0, 1e-12);
}

// The at-rest test: the main body's toe and mean speed have fallen to zero,
// but a block that broke away still runs: not at rest until it stops too,
// and then only after rest_duration.
TEST(RestDetector, ABlockThatRunsOnKeepsTheRunGoing) {
  RestDetector rest(1e-3, 2.0);
  EXPECT_FALSE(rest.at_rest(0.0, 5.0, 4.0, 3.0));  // the peak: 25 (m/s)^2
  for (double t = 1.0; t <= 10.0; t += 1.0) EXPECT_FALSE(rest.at_rest(t, 0.0, 0.0, 1.0)) << t;
  EXPECT_FALSE(rest.at_rest(11.0, 0.0, 0.0, 0.1));  // 0.01 < 0.025: rest starts
  EXPECT_FALSE(rest.at_rest(12.0, 0.0, 0.0, 0.1));
  EXPECT_TRUE(rest.at_rest(13.0, 0.0, 0.0, 0.1));
  EXPECT_EQ(rest.since(), 11.0);
  EXPECT_EQ(rest.peak(), 25.0);
}

// Two blocks 10 m (40 spacings) apart: the heavier, though the shorter, is
// the main body, whichever comes first.
TEST(MeasureSlide, TheHeavierOfTwoSeparateBlocksIsTheMainBody) {
  const Frame f = planar_frame(0.0);
  struct Case {
    double light_u0, heavy_u0;
  };
  for (const Case c : {Case{0.0, 20.0}, Case{15.0, 0.0}}) {
    const std::vector<Seed> light = rectangle(f, c.light_u0, c.light_u0 + 10.0, 1.0);
    const std::vector<Seed> heavy = rectangle(f, c.heavy_u0, c.heavy_u0 + 5.0, 4.0);
    const SlideMorphology m =
        measure_slide(make_particles(joined(light, heavy)), planar_base(0.0), kSpacing);
    EXPECT_NEAR(m.rear_s, c.heavy_u0, 1e-9);
    EXPECT_NEAR(m.toe_s, c.heavy_u0 + 5.0, 1e-9);
    EXPECT_NEAR(m.max_thickness, 4.0, 1e-9);
    EXPECT_EQ(m.particles, static_cast<int>(heavy.size()));
    EXPECT_NEAR(m.outside_mass, kMass * static_cast<double>(light.size()), 1e-9);
  }
}

// A layer of uniform thickness parallel to each segment of the escarpment.
TEST(MeasureSlide, UniformLayerOnAnInclinedPolyline) {
  const Base base = escarpment();
  const BaseView b = base.view();
  const double thickness = 3.0;
  struct Case {
    int segment;
    double u0, u1, s0;  // along the segment, and the arc length at its start
  };
  for (const Case c : {Case{0, 20.0, 80.0, 0.0}, Case{1, 10.0, 60.0, 100.0}}) {
    const Frame f = segment_frame(b, c.segment);
    const Particles P = make_particles(rectangle(f, c.u0, c.u1, thickness));
    for (int p = 0; p < P.size(); p += 37) {
      const double u = (P.x[p] - f.ox) * f.tx + (P.y[p] - f.oy) * f.ty;
      EXPECT_NEAR(locate_on_base(b, P.x[p], P.y[p]).s, c.s0 + u, 1e-9);
    }
    const SlideMorphology m = measure_slide(P, b, kSpacing);
    EXPECT_NEAR(m.rear_s, c.s0 + c.u0, kSpacing);
    EXPECT_NEAR(m.toe_s, c.s0 + c.u1, kSpacing);
    EXPECT_NEAR(m.centroid_s, c.s0 + 0.5 * (c.u0 + c.u1), kSpacing);
    EXPECT_NEAR(m.max_thickness, thickness, kSpacing);

    const Profile profile = slide_profile(P, b, 2 * kSpacing, kSpacing);
    ASSERT_FALSE(profile.bins.empty());
    for (const ProfileBin& bin : profile.bins) {
      EXPECT_NEAR(bin.thickness, thickness, kSpacing) << bin.s;
      const Seed top = f.at(bin.s - c.s0, bin.thickness);
      EXPECT_NEAR(bin.x_surface, top.x, 1e-9);
      EXPECT_NEAR(bin.y_surface, top.y, 1e-9);
    }
  }
}

TEST(MeasureSlide, VelocitiesOfABlockMovingUniformly) {
  const Base base = escarpment();
  const BaseView b = base.view();
  const Frame f = segment_frame(b, 0);
  const double speed = 2.5;
  std::vector<Seed> seeds = rectangle(f, 20.0, 40.0, 2.0);
  for (Seed& s : seeds) {
    s.vx = speed * f.tx;
    s.vy = speed * f.ty;
  }
  const Particles P = make_particles(seeds);
  const SlideMorphology m = measure_slide(P, b, kSpacing);
  EXPECT_NEAR(m.toe_velocity, speed, 1e-12);
  EXPECT_NEAR(m.centroid_velocity_s, speed, 1e-12);
  EXPECT_NEAR(m.centroid_vx, speed * f.tx, 1e-12);
  EXPECT_NEAR(m.centroid_vy, speed * f.ty, 1e-12);
  EXPECT_NEAR(m.max_speed, speed, 1e-12);
  EXPECT_NEAR(m.kinetic_energy, 0.5 * kMass * P.size() * speed * speed, 1e-9);
}

// Velocity growing linearly towards the front: the toe velocity is the
// mean of the two front columns, not the front particle's.
TEST(MeasureSlide, ToeVelocityAveragesTheTwoFrontColumns) {
  std::vector<Seed> seeds = rectangle(planar_frame(0.0), 0.0, 10.0, 2.0);
  for (Seed& s : seeds) s.vx = 1.0 + 0.3 * s.x;
  const SlideMorphology m = measure_slide(make_particles(seeds), planar_base(0.0), kSpacing);
  const double front_centre = 10.0 - 0.5 * kSpacing;
  EXPECT_NEAR(m.toe_velocity, 1.0 + 0.3 * (front_centre - 0.5 * kSpacing), 1e-12);
}

TEST(MeasureSlide, RunoutIsTheToeDisplacement) {
  const Frame f = planar_frame(0.0);
  const SlideMorphology before =
      measure_slide(make_particles(rectangle(f, 0.0, 10.0, 2.0)), planar_base(0.0), kSpacing);
  const SlideMorphology after =
      measure_slide(make_particles(rectangle(f, 0.0, 17.0, 1.0)), planar_base(0.0), kSpacing);
  EXPECT_NEAR(runout_distance(after, before.toe_s), 7.0, 1e-9);
}

TEST(MeasureSlide, NoParticlesAndBadSpacing) {
  const SlideMorphology m = measure_slide(Particles{}, planar_base(0.0), kSpacing);
  EXPECT_EQ(m.particles, 0);
  EXPECT_EQ(m.kinetic_energy, 0.0);
  EXPECT_TRUE(slide_profile(Particles{}, planar_base(0.0), kSpacing, kSpacing).bins.empty());
  EXPECT_THROW(measure_slide(Particles{}, planar_base(0.0), 0.0), std::invalid_argument);
  EXPECT_THROW(slide_profile(Particles{}, planar_base(0.0), -1.0, kSpacing),
               std::invalid_argument);
}

// ---------------------------------------------------------- slide_profile

// The trapezoid of the parametric cases: 48.66 m along the base, 5 m high,
// side faces at 30 degrees to the base.
TEST(SlideProfile, TrapezoidFollowsItsHeight) {
  const double length = 48.66, height = 5.0, slope = std::tan(30.0 * kPi / 180.0);
  const auto analytic = [&](double u) {
    return std::max(0.0, std::min({height, u * slope, (length - u) * slope}));
  };
  const Particles P = make_particles(lattice(planar_frame(0.0), 0.0, length, analytic));
  const Profile profile = slide_profile(P, planar_base(0.0), kSpacing, kSpacing);
  ASSERT_GT(profile.bins.size(), 150u);
  // The end columns are too short to hold a particle centre.
  EXPECT_NEAR(profile.bins.front().s, 0.0, 2 * kSpacing);
  EXPECT_NEAR(profile.bins.back().s, length, 2 * kSpacing);
  int particles = 0;
  for (const ProfileBin& bin : profile.bins) {
    EXPECT_NEAR(bin.thickness, analytic(bin.s), kSpacing) << bin.s;
    EXPECT_DOUBLE_EQ(bin.x_surface, bin.s);
    EXPECT_DOUBLE_EQ(bin.y_surface, bin.thickness);
    particles += bin.particles;
  }
  EXPECT_EQ(particles, P.size());
}

TEST(SlideProfile, EmptyBinsHaveNoThickness) {
  const Frame f = planar_frame(0.0);
  std::vector<Seed> seeds = joined(rectangle(f, 0.0, 2.0, 1.0), rectangle(f, 6.0, 8.0, 1.0));
  for (Seed& s : seeds) s.vx = 1.5;
  const Profile profile = slide_profile(make_particles(seeds), planar_base(0.0), 0.5, kSpacing);
  int empty = 0;
  for (const ProfileBin& bin : profile.bins) {
    if (bin.s > 2.25 && bin.s < 5.75) {
      ++empty;
      EXPECT_EQ(bin.particles, 0);
      EXPECT_EQ(bin.thickness, 0.0);
      EXPECT_EQ(bin.velocity_s, 0.0);
      EXPECT_EQ(bin.y_surface, 0.0);
    } else {
      EXPECT_GT(bin.particles, 0) << bin.s;
      EXPECT_NEAR(bin.velocity_s, 1.5, 1e-12);
    }
  }
  EXPECT_EQ(empty, 7);
}

TEST(SlideProfile, CsvHasTheTimeHeaderAndOneRowPerBin) {
  const fs::path dir = fs::temp_directory_path() / ("runout_profile_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Particles P = make_particles(rectangle(planar_frame(0.0), 0.0, 3.0, 1.0));
  const Profile profile = slide_profile(P, planar_base(0.0), 0.5, kSpacing);
  const fs::path path = dir / "profile_00003.csv";
  write_profile_csv(path.string(), 1.5, profile);

  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "# time = 1.5");
  std::getline(in, line);
  EXPECT_EQ(line, "s,x_surface,y_surface,thickness,particles,velocity_s");
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    ASSERT_LT(rows, profile.bins.size());
    const ProfileBin& bin = profile.bins[rows++];
    std::istringstream row(line);
    std::vector<double> fields;
    for (std::string field; std::getline(row, field, ',');) fields.push_back(std::stod(field));
    ASSERT_EQ(fields.size(), 6u) << line;
    EXPECT_EQ(fields[0], bin.s);
    EXPECT_EQ(fields[3], bin.thickness);
    EXPECT_EQ(fields[4], bin.particles);
  }
  EXPECT_EQ(rows, profile.bins.size());

  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);  // no temporary file left behind
  fs::remove_all(dir);
}

// ----------------------------------------------------------- determinism

TEST(Morphology, SameResultTwice) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Seed> seeds;
  for (int k = 0; k < 20000; ++k)
    seeds.push_back(Seed{160.0 * u(rng), 50.0 - 30.0 * u(rng), u(rng) - 0.5, u(rng) - 0.5});
  const Particles P = make_particles(seeds);
  const Base base = escarpment();
  const auto run = [&] {
    return std::make_pair(measure_slide(P, base.view(), kSpacing),
                          slide_profile(P, base.view(), 2 * kSpacing, kSpacing));
  };
  const auto [m1, p1] = run();
  const auto [m2, p2] = run();
  for (const auto field : {&SlideMorphology::toe_s, &SlideMorphology::rear_s,
                           &SlideMorphology::centroid_s, &SlideMorphology::centroid_velocity_s,
                           &SlideMorphology::toe_velocity, &SlideMorphology::max_thickness,
                           &SlideMorphology::outside_mass, &SlideMorphology::kinetic_energy})
    EXPECT_EQ(m1.*field, m2.*field);
  ASSERT_EQ(p1.bins.size(), p2.bins.size());
  for (std::size_t k = 0; k < p1.bins.size(); ++k) {
    EXPECT_EQ(p1.bins[k].thickness, p2.bins[k].thickness);
    EXPECT_EQ(p1.bins[k].velocity_s, p2.bins[k].velocity_s);
  }
}

}  // namespace

// Particle columns pulled 1.5 bins apart by stretching leave bins that hold
// only low particles or none: the closing puts the surface back on the
// columns' tops, while a trough 6 bins wide (a graben) stays.
TEST(SlideProfile, GapsBetweenStretchedColumnsAreClosedButGrabensStay) {
  const double bin = 0.4;
  std::vector<Seed> seeds;
  for (int c = 0; c < 40; ++c) {
    const double x = 0.6 * c;
    if (x > 10.0 && x < 12.4) continue;  // the graben: no columns over 2.4 m
    for (int r = 0; r < 5; ++r) seeds.push_back(Seed{x, 0.1 + 0.2 * r});
  }
  const Profile profile = slide_profile(make_particles(seeds), planar_base(0.0), bin, 0.2);
  // Bins are centred on multiples of 0.4 m (the rear particle is at 0);
  // the columns next to the graben are at 9.6 and 12.6 m.
  int in_graben = 0;
  for (const ProfileBin& b : profile.bins) {
    if (b.s > 9.9 && b.s < 12.1) {
      EXPECT_EQ(b.thickness, 0.0) << b.s;
      ++in_graben;
    } else if (b.s < 9.7 || b.s > 12.7) {
      EXPECT_NEAR(b.thickness, 1.0, 1e-12) << b.s;
    }
  }
  EXPECT_EQ(in_graben, 6);
}

// ---------------------------------------------------------------- basal_fill.hpp

namespace {

// Each particle with its share of a lattice cell, spacing^2.
Particles with_lattice_volumes(Particles P) {
  for (int p = 0; p < P.size(); ++p) P.vol[p] = kSpacing * kSpacing;
  return P;
}

}  // namespace

// A lattice of particles tiles its basal layer on any cell that is a whole
// number of spacings: 2 x 2 and 4 x 4 particles per cell alike.
TEST(BasalFill, ALatticeTilesItsBasalLayer) {
  const Frame f = planar_frame(0.5);
  for (int ppc : {2, 4}) {
    const double h = ppc * kSpacing;
    const Particles P = with_lattice_volumes(make_particles(rectangle(f, 0.0, 12.0, 5.0)));
    EXPECT_NEAR(basal_fill(P, planar_base(0.5), h), 1.0, 1e-12) << ppc;
  }
}

TEST(BasalFill, ALayerParallelToEachSegmentOfAPolylineFillsItsBasalLayer) {
  const Base base = escarpment();
  const BaseView b = base.view();
  const double h = 2 * kSpacing;
  // Both segments are 100 m long, so each starts on a whole cell of s.
  for (int segment : {0, 1}) {
    const Particles P =
        with_lattice_volumes(make_particles(rectangle(segment_frame(b, segment), 20.0, 60.0, 4.0)));
    EXPECT_NEAR(basal_fill(P, b, h), 1.0, 1e-9) << segment;
  }
}

// What the measure is for: particles that leave the basal layer, or crowd
// into it, show as the fraction of the layer they cover.
TEST(BasalFill, AThinnedOrCrowdedBasalLayerShowsAsItsShare) {
  const Frame f = planar_frame(0.0);
  const double h = 4 * kSpacing;
  std::vector<Seed> thinned, crowded;
  int k = 0;
  for (const Seed& s : rectangle(f, 0.0, 12.0, 5.0)) {
    const bool basal = s.y < h;
    if (!basal || k++ % 2 == 0) thinned.push_back(s);
    crowded.push_back(s);
    if (s.y < kSpacing) crowded.push_back(f.at(s.x, s.y + 0.5 * kSpacing));  // a fifth row
  }
  EXPECT_NEAR(basal_fill(with_lattice_volumes(make_particles(thinned)), planar_base(0.0), h), 0.5,
              1e-12);
  EXPECT_NEAR(basal_fill(with_lattice_volumes(make_particles(crowded)), planar_base(0.0), h), 1.25,
              1e-12);
}

// Under three cells thick nothing counts: a thin layer's basal cell is its
// whole depth, and the front and rear bins are left out of every slide.
TEST(BasalFill, AThinLayerHasNoBasalLayerToMeasure) {
  const double h = 2 * kSpacing;
  const Particles thin =
      with_lattice_volumes(make_particles(rectangle(planar_frame(0.0), 0.0, 12.0, 2.5 * h)));
  EXPECT_TRUE(std::isnan(basal_fill(thin, planar_base(0.0), h)));
  const Particles narrow =
      with_lattice_volumes(make_particles(rectangle(planar_frame(0.0), 0.0, 2.0 * h, 5.0)));
  EXPECT_TRUE(std::isnan(basal_fill(narrow, planar_base(0.0), h)));
  EXPECT_TRUE(std::isnan(basal_fill(Particles{}, planar_base(0.0), h)));
}

// ---------------------------------------------------------------- remoulded_mass.hpp

// The remoulded mass counts a particle of a softening clay once its own
// plastic shear has taken 95 % of the strength remoulding can take (S(xi)
// within e^-3 (1 - 1/St) of 1/St), and nothing of a clay that does not
// soften, of an elastic body, or of the basal band's remoulding.
TEST(RemouldedMass, CountsTheClayThatHasLost95PercentOfWhatItCanLose) {
  std::vector<MaterialParams> materials(3);
  materials[0].model = MaterialModel::Tresca;
  materials[0].strength.su0 = 5000.0;
  materials[0].strength.d_rem = 1.0 / 40.0;
  materials[0].strength.xi95 = 5.0;
  materials[1] = materials[0];
  materials[1].strength.d_rem = 1.0;  // St = 1
  materials[2] = elastic_params(600.0, 5e5, 0.49);

  struct Point {
    int material;
    double xi, band_xi, mass;
  };
  const std::vector<Point> points = {{0, 0.0, 0.0, 1.0},   {0, 4.99, 0.0, 2.0},
                                     {0, 5.0, 0.0, 4.0},   {0, 120.0, 0.0, 8.0},
                                     {0, 0.5, 900.0, 16.0}, {1, 120.0, 0.0, 32.0},
                                     {2, 120.0, 0.0, 64.0}};
  Particles P;
  P.resize(static_cast<int>(points.size()));
  double expected = 0.0;
  for (int p = 0; p < P.size(); ++p) {
    P.material[p] = points[p].material;
    P.xi[p] = points[p].xi;
    P.band_xi[p] = points[p].band_xi;
    P.mass[p] = points[p].mass;
    const StrengthParams& k = materials[points[p].material].strength;
    const double left = softening(k, points[p].xi) - k.d_rem;
    const bool lost_95 = materials[points[p].material].model == MaterialModel::Tresca &&
                         k.d_rem < 1.0 && left <= std::exp(-3.0) * (1.0 - k.d_rem) * (1 + 1e-12);
    if (lost_95) expected += points[p].mass;
  }
  EXPECT_EQ(expected, 12.0);  // the particles at xi95 and far past it
  EXPECT_EQ(remoulded_mass(P, materials), expected);
  EXPECT_EQ(remoulded_mass(Particles{}, materials), 0.0);
}

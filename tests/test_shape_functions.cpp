// Partition of unity and zero gradient sum of the GIMP and linear shape
// functions, with particles on nodes, on cell edges, at cell centres and in
// between, on a grid whose origin is not zero.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "runout/mpm/particles.hpp"
#include "runout/mpm/shape.hpp"
#include "runout/mpm/stages.hpp"

using namespace runout;

namespace {

struct Case {
  ShapeKind kind;
  double lp_fraction;  // lp / h
};

void expect_partition(ShapeKind kind, double xp, double origin, double h, double lp) {
  Stencil1D s;
  stencil_1d(kind, xp, origin, h, lp, s);
  double sum = 0, dsum = 0, moment = 0;
  for (int k = 0; k < 3; ++k) {
    EXPECT_GE(s.w[k], 0.0);
    sum += s.w[k];
    dsum += s.dw[k];
    moment += s.dw[k] * (origin + (s.first + k) * h);
  }
  EXPECT_NEAR(sum, 1.0, 1e-14) << "xp = " << xp;
  EXPECT_NEAR(dsum, 0.0, 1e-12 / h) << "xp = " << xp;
  // Linear completeness: sum dN_i x_i = 1 (the gradient of x is 1).
  EXPECT_NEAR(moment, 1.0, 1e-9) << "xp = " << xp;
}

}  // namespace

TEST(ShapeFunctions, PartitionOfUnityEverywhere) {
  const double h = 0.37, origin = -12.345;
  for (Case c : {Case{ShapeKind::Gimp, 0.25}, Case{ShapeKind::Gimp, 0.5},
                 Case{ShapeKind::Gimp, 0.125}, Case{ShapeKind::Linear, 0.25}}) {
    const double lp = c.lp_fraction * h;
    for (int node = -3; node <= 3; ++node) {
      const double xn = origin + node * h;
      for (double f : {0.0, 1e-13, 0.1, 0.25, 0.5 - 1e-12, 0.5, 0.5 + 1e-12, 0.75, 0.999})
        expect_partition(c.kind, xn + f * h, origin, h, lp);
    }
  }
}

TEST(ShapeFunctions, GimpMatchesClosedFormOnNodeAndEdge) {
  // Particle on a node: centre weight 1 - lp/(2h), neighbours lp/(4h).
  const double h = 1.0, lp = 0.25;
  Stencil1D s;
  stencil_1d(ShapeKind::Gimp, 3.0, 0.0, h, lp, s);
  EXPECT_EQ(s.first, 2);
  EXPECT_NEAR(s.w[1], 1.0 - lp / (2.0 * h), 1e-15);
  EXPECT_NEAR(s.w[0], lp / (4.0 * h), 1e-15);
  EXPECT_NEAR(s.w[2], lp / (4.0 * h), 1e-15);
  EXPECT_NEAR(s.dw[1], 0.0, 1e-15);
  // Particle at a cell centre, in the linear zone of both cell nodes.
  stencil_1d(ShapeKind::Gimp, 3.5, 0.0, h, lp, s);
  EXPECT_NEAR(s.w[0] + s.w[1] + s.w[2], 1.0, 1e-15);
  double w3 = 0, w4 = 0;
  for (int k = 0; k < 3; ++k) {
    if (s.first + k == 3) w3 = s.w[k];
    if (s.first + k == 4) w4 = s.w[k];
  }
  EXPECT_NEAR(w3, 0.5, 1e-15);
  EXPECT_NEAR(w4, 0.5, 1e-15);
}

// A GIMP stencil that starts at the cell's left neighbour (the x rows of
// the step) has every node's weight and derivative of the nearest-start
// one, bit for bit, and zero at the node it adds; so it sums to one.
TEST(ShapeFunctions, CellLeftStartHoldsTheSameWeightsOneNodeOver) {
  const double h = 0.37, origin = -12.345;
  for (double lp : {0.125 * h, 0.25 * h, 0.5 * h}) {
    for (double f : {0.0, 1e-13, 0.1, 0.25, 0.5 - 1e-12, 0.5, 0.5 + 1e-12, 0.75, 0.999}) {
      const double xp = origin + 2 * h + f * h;
      Stencil1D nearest, left;
      stencil_1d(ShapeKind::Gimp, xp, origin, h, lp, nearest, StencilStart::Nearest);
      stencil_1d(ShapeKind::Gimp, xp, origin, h, lp, left, StencilStart::CellLeft);
      EXPECT_EQ(left.first, left.cell - 1);
      double sum = 0;
      for (int k = 0; k < kStencilNodes; ++k) {
        sum += left.w[k];
        const int in_nearest = left.first + k - nearest.first;
        const bool touched = in_nearest >= 0 && in_nearest < 3;
        EXPECT_EQ(left.w[k], touched ? nearest.w[in_nearest] : 0.0) << "f = " << f << ", k = " << k;
        EXPECT_EQ(left.dw[k], touched ? nearest.dw[in_nearest] : 0.0) << "f = " << f << ", k = " << k;
      }
      EXPECT_NEAR(sum, 1.0, 1e-14) << "f = " << f;
    }
  }
}

// The weight and derivative a GIMP stencil gives node i, zero where it
// gives none.
std::pair<double, double> node_weight(double xp, double origin, double h, double lp, int node) {
  Stencil1D s;
  stencil_1d(ShapeKind::Gimp, xp, origin, h, lp, s, StencilStart::CellLeft);
  const int k = node - s.first;
  if (k < 0 || k >= kStencilNodes) return {0.0, 0.0};
  return {s.w[k], s.dw[k]};
}

// Node 0 seen from either side of each boundary of the pieces (|r| = lp,
// h - lp, h + lp), of a cell edge and of a cell's middle.
TEST(ShapeFunctions, GimpIsContinuousAcrossZoneBoundaries) {
  const double h = 1.0, lp = 0.25, eps = 1e-9;
  for (double r : {lp, h - lp, h + lp, 0.5 * h, h, -lp, -(h - lp), -(h + lp), -h}) {
    const auto [a, da] = node_weight(r - eps, 0.0, h, lp, 0);
    const auto [b, db] = node_weight(r + eps, 0.0, h, lp, 0);
    EXPECT_NEAR(a, b, 1e-8) << "r = " << r;
    EXPECT_NEAR(da, db, 1e-7) << "r = " << r;
  }
}

// The uGIMP weight of Bardenhagen & Kober (2004, eq. 39) node by node,
// written out by its pieces: the stencil's weights, each node's from the
// particle's place in its cell, are the same.
TEST(ShapeFunctions, GimpStencilMatchesThePiecewiseFormNodeByNode) {
  const double h = 0.37, origin = -12.345;
  const auto piecewise = [&](double r, double lp) {
    const double a = std::fabs(r), s = r < 0.0 ? -1.0 : 1.0;
    if (a < lp) return std::pair{1.0 - (r * r + lp * lp) / (2.0 * h * lp), -r / (h * lp)};
    if (a < h - lp) return std::pair{1.0 - a / h, -s / h};
    if (a < h + lp) {
      const double b = h + lp - a;
      return std::pair{b * b / (4.0 * h * lp), -s * b / (2.0 * h * lp)};
    }
    return std::pair{0.0, 0.0};
  };
  for (double lp : {0.125 * h, 0.25 * h, 0.4 * h, 0.5 * h})
    for (int i = 0; i <= 400; ++i) {
      const double xp = origin + 5.0 * h + 2.0 * h * i / 400.0;
      for (int node = 3; node <= 9; ++node) {
        const auto [w, dw] = node_weight(xp, origin, h, lp, node);
        const auto [w_ref, dw_ref] = piecewise(xp - (origin + node * h), lp);
        EXPECT_NEAR(w, w_ref, 1e-13) << "lp = " << lp << ", xp = " << xp << ", node " << node;
        EXPECT_NEAR(dw * h, dw_ref * h, 1e-12) << "lp = " << lp << ", xp = " << xp << ", node " << node;
      }
    }
}

// The CPU backend makes the stencils four particles at a time
// (domain_half_widths_4, gimp_stencils_x4): the same as make_stencil one at
// a time, to rounding,
// for bodies stretched, sheared (some past the point where the lattice
// basis needs reducing, which falls back to make_stencil) and rotated.
TEST(ShapeFunctions, FourParticleStencilsMatchOneAtATime) {
  const double h = 0.37, lp = h / 4;
  GridView g;
  g.h = h;
  g.ox = -3.1;
  g.oy = 0.45;
  StepConfig c;
  c.shape = ShapeKind::Gimp;
  c.domain = DomainKind::Deforming;
  c.lp = lp;
  Particles particles;
  const int n = 4 * 250;
  particles.resize(n);
  ParticleView P = particles.view();
  for (int p = 0; p < n; ++p) {
    const double s = std::sin(1.7 * p), t = std::cos(2.3 * p);
    P.x[p] = g.ox + 2.0 * h + 10.0 * h * (0.5 + 0.5 * s);
    P.y[p] = g.oy + 2.0 * h + 6.0 * h * (0.5 + 0.5 * t);
    const double gamma = 1.6 * s * t, stretch = 1.0 + 0.3 * t, angle = 0.8 * s;
    // F = R(angle) [stretch gamma; 0 1 / stretch]
    const double ca = std::cos(angle), sa = std::sin(angle);
    P.fxx[p] = ca * stretch;
    P.fxy[p] = ca * gamma - sa / stretch;
    P.fyx[p] = sa * stretch;
    P.fyy[p] = sa * gamma + ca / stretch;
    P.vol0[p] = 4.0 * lp * lp;
    P.vol[p] = P.vol0[p] * (1.0 + 0.05 * s);
  }
  std::vector<Stencil2D> one(n), four(n);
  for (int p = 0; p < n; ++p) make_stencil(g, c, P, p, one[p]);
  std::vector<double> lx(n), ly(n);
  for (int p = 0; p < n; p += 4) {
    domain_half_widths_4(P, p, c, h, &lx[p], &ly[p]);
    gimp_stencils_x4(g, load_lanes(P.x + p), load_lanes(P.y + p), load_lanes(&lx[p]),
                     load_lanes(&ly[p]), &four[p]);
  }
  const auto expect_close = [](double a, double b, int p) {
    EXPECT_NEAR(a, b, 4e-16 * (1.0 + std::fabs(b))) << "particle " << p;
  };
  for (int p = 0; p < n; ++p) {
    const Stencil2D &a = four[p], &b = one[p];
    EXPECT_EQ(a.w.first_x, b.w.first_x) << "particle " << p;
    EXPECT_EQ(a.w.first_y, b.w.first_y) << "particle " << p;
    expect_close(a.r.r0x, b.r.r0x, p);
    expect_close(a.r.r0y, b.r.r0y, p);
    for (int k = 0; k < kStencilNodes; ++k) {
      expect_close(a.w.wx[k], b.w.wx[k], p);
      expect_close(a.d.dwx[k] * h, b.d.dwx[k] * h, p);
    }
    for (int k = 0; k < 3; ++k) {
      expect_close(a.w.wy[k], b.w.wy[k], p);
      expect_close(a.d.dwy[k] * h, b.d.dwy[k] * h, p);
    }
    expect_close(a.r.lx, b.r.lx, p);
    expect_close(a.r.ly, b.r.ly, p);
  }
  // Without derivatives (the passes that read only the weights): the same
  // weights and places to the bit, so a particle scatters and gathers with
  // one set of weights whichever pass made them.
  std::vector<Stencil2D> weights(n);
  for (int p = 0; p < n; p += 4)
    gimp_stencils_x4<false>(g, load_lanes(P.x + p), load_lanes(P.y + p), load_lanes(&lx[p]),
                            load_lanes(&ly[p]), &weights[p]);
  for (int p = 0; p < n; ++p) {
    const Stencil2D &a = weights[p], &b = four[p];
    EXPECT_EQ(a.w.first_x, b.w.first_x) << "particle " << p;
    EXPECT_EQ(a.w.first_y, b.w.first_y) << "particle " << p;
    EXPECT_EQ(a.r.r0x, b.r.r0x) << "particle " << p;
    EXPECT_EQ(a.r.r0y, b.r.r0y) << "particle " << p;
    for (int k = 0; k < kStencilNodes; ++k) {
      EXPECT_EQ(a.w.wx[k], b.w.wx[k]) << "particle " << p;
      EXPECT_EQ(a.w.wy[k], b.w.wy[k]) << "particle " << p;
    }
  }
}

// Incremental instant radiosity (Laine et al. 2007), the GL-free core: domain mappings, clipped
// Voronoi cells and the two incremental triangulations (the per-frame VPL maintenance is
// IirVplDistributionTest.cpp's).
#include "techniques/iir/DiscCell.h"
#include "techniques/iir/DiscTriangulation.h"
#include "techniques/iir/LightBasis.h"
#include "techniques/iir/SphereCells.h"
#include "techniques/iir/SphereTriangulation.h"
#include "techniques/iir/SpotDiscMap.h"
#include "techniques/iir/TileAssignment.h"
#include "techniques/iir/VplDistribution.h"
#include "IirTestSupport.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <vector>

using namespace bounce;
using namespace bounce::iirtest;

namespace {

glm::dvec2 randomInDisc(std::mt19937_64& rng, double radius = 1.0) {
    const double r = radius * std::sqrt(random01(rng));
    const double phi = 2.0 * kPi * random01(rng);
    return glm::dvec2(r * std::cos(phi), r * std::sin(phi));
}

// Fibonacci lattice: n nearly equal-area points on the unit sphere.
std::vector<glm::dvec3> fibonacciSphere(int n) {
    std::vector<glm::dvec3> out;
    out.reserve(n);
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double z = 1.0 - (2.0 * i + 1.0) / n;
        const double s = std::sqrt(1.0 - z * z);
        out.emplace_back(s * std::cos(golden * i), s * std::sin(golden * i), z);
    }
    return out;
}

double nearestDistance(const glm::dvec3& x, const std::vector<glm::dvec3>& sites) {
    double best = std::numeric_limits<double>::infinity();
    for (const glm::dvec3& p : sites) best = std::min(best, glm::distance(x, p));
    return best;
}

std::vector<glm::dvec3> pointsOf(const DomainTriangulation& t) {
    std::vector<glm::dvec3> out;
    for (SlotId s = 0; s < t.slotCapacity(); ++s)
        if (t.contains(s)) out.push_back(t.point(s));
    return out;
}

double minPairwiseDistance(const std::vector<glm::dvec3>& points) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < points.size(); ++i)
        for (size_t j = i + 1; j < points.size(); ++j) best = std::min(best, glm::distance(points[i], points[j]));
    return best;
}

// Dispersion of points on the disc by brute force over a grid of spacing h plus rimCount rim points.
// The nearest-site distance is 1-Lipschitz and every disc point is within sqrt(2) h of a grid point
// inside the disc or within 2 pi / rimCount of a rim sample, so the result is in [delta - that, delta].
double bruteDiscDispersion(const std::vector<glm::dvec3>& sites, double h, int rimCount) {
    double best = 0.0;
    for (double x = -1.0; x <= 1.0; x += h)
        for (double y = -1.0; y <= 1.0; y += h)
            if (x * x + y * y <= 1.0) best = std::max(best, nearestDistance(glm::dvec3(x, y, 0.0), sites));
    for (int i = 0; i < rimCount; ++i) {
        const double a = 2.0 * kPi * i / rimCount;
        best = std::max(best, nearestDistance(glm::dvec3(std::cos(a), std::sin(a), 0.0), sites));
    }
    return best;
}

void fillDiscRandom(DiscTriangulation& t, int count, std::mt19937_64& rng) {
    for (int i = 0; i < count; ++i) ASSERT_TRUE(t.insert({static_cast<SlotId>(i), glm::dvec3(randomInDisc(rng), 0.0)}));
}

void fillSphereRandom(SphereTriangulation& t, int count, std::mt19937_64& rng) {
    for (int i = 0; i < count; ++i) ASSERT_TRUE(t.insert({static_cast<SlotId>(i), randomOnSphere(rng)}));
}

}  // namespace

// ---------------------------------------------------------------- domain mappings

TEST(IirLightBasis, OrthonormalRightHandedForAnyAxis) {
    std::mt19937_64 rng(7);
    std::vector<glm::dvec3> axes{{0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {1, 0, 0}, {1e-9, 0, -1}};
    for (int i = 0; i < 100; ++i) axes.push_back(randomOnSphere(rng) * 3.0);
    for (const glm::dvec3& axis : axes) {
        const LightBasis b = LightBasis::fromAxis(axis);
        // Orthonormality up to a few double roundings.
        EXPECT_NEAR(glm::length(b.tangent), 1.0, 1e-14);
        EXPECT_NEAR(glm::length(b.bitangent), 1.0, 1e-14);
        EXPECT_NEAR(glm::dot(b.tangent, b.bitangent), 0.0, 1e-14);
        EXPECT_NEAR(glm::distance(glm::cross(b.tangent, b.bitangent), glm::normalize(axis)), 0.0, 1e-14);
        const glm::dvec3 v(0.3, -0.2, 0.9);
        EXPECT_NEAR(glm::distance(b.toWorld(b.toLocal(v)), v), 0.0, 1e-14);
    }
}

TEST(IirSpotDiscMap, NusseltAnalogForTheCosineSpot) {
    // n = 1, c = 90 degrees is the paper's 180-degree cosine spot: the disc point is (x, y) of the
    // direction and the inverse lifts (x, y) to (x, y, sqrt(1 - x^2 - y^2)).
    const SpotDiscMap map(1.0, glm::half_pi<double>());
    std::mt19937_64 rng(1);
    for (int i = 0; i < 1000; ++i) {
        glm::dvec3 d = randomOnSphere(rng);
        d.z = std::abs(d.z);
        const auto disc = map.toDisc(d);
        ASSERT_TRUE(disc.has_value());
        // log1p/expm1 and a square root: a few ulps.
        EXPECT_NEAR(disc->x, d.x, 1e-13);
        EXPECT_NEAR(disc->y, d.y, 1e-13);
        const glm::dvec2 p = randomInDisc(rng);
        const glm::dvec3 lifted = map.toDirection(p);
        EXPECT_NEAR(glm::distance(lifted, glm::dvec3(p, std::sqrt(1.0 - glm::dot(p, p)))), 0.0, 1e-13);
    }
    EXPECT_FALSE(map.toDisc({0.3, 0.1, -0.2}).has_value());  // behind the spot
    // The cone is closed: alpha = c maps to the rim, where the empty-circle search puts points.
    const auto horizon = map.toDisc({1.0, 0.0, 0.0});
    ASSERT_TRUE(horizon.has_value());
    EXPECT_NEAR(glm::distance(*horizon, glm::dvec2(1.0, 0.0)), 0.0, 1e-15);
    const SpotDiscMap narrow(2.0, 0.5);
    EXPECT_FALSE(narrow.toDisc({std::sin(0.5 + 1e-9), 0.0, std::cos(0.5 + 1e-9)}).has_value());
    EXPECT_TRUE(narrow.toDisc({std::sin(0.5 - 1e-9), 0.0, std::cos(0.5 - 1e-9)}).has_value());
}

TEST(IirSpotDiscMap, RoundTripsAndRespectsTheCone) {
    const double cutoffs[] = {0.2, 0.7, 1.2, glm::half_pi<double>()};
    const double exponents[] = {0.0, 1.0, 4.5, 50.0};
    std::mt19937_64 rng(2);
    for (double c : cutoffs) {
        for (double n : exponents) {
            const SpotDiscMap map(n, c);
            for (int i = 0; i < 200; ++i) {
                const glm::dvec2 p = randomInDisc(rng, 0.999);
                const glm::dvec3 d = map.toDirection(p);
                EXPECT_NEAR(glm::length(d), 1.0, 1e-14);
                EXPECT_LT(std::acos(std::clamp(d.z, -1.0, 1.0)), c + 1e-12);
                const auto back = map.toDisc(d);
                ASSERT_TRUE(back.has_value()) << "n " << n << " c " << c;
                // The inverse of r^2 = F(alpha)/F(c) loses a few digits where F is flat (n = 50 near
                // the axis, r -> 1 for narrow cones): 1e-9 is well above that and far below any
                // cell size.
                EXPECT_NEAR(glm::distance(*back, p), 0.0, 1e-9) << "n " << n << " c " << c;
            }
            EXPECT_NEAR(map.fluxFractionWithin(c), 1.0, 1e-15);
            EXPECT_EQ(map.fluxFractionWithin(0.0), 0.0);
        }
    }
}

TEST(IirSpotDiscMap, UniformDiscSamplesFollowTheCosinePowerIntensity) {
    // Uniform points on the disc mapped to directions must be distributed like I(alpha) sin(alpha)
    // on [0, c] (intensity times the solid-angle Jacobian). The expected bin probabilities come from
    // Simpson quadrature of cos^n(alpha) sin(alpha), independent of the map's closed form.
    struct Case {
        double n, c;
    };
    const Case cases[] = {{1.0, glm::half_pi<double>()}, {4.0, 1.0}, {20.0, 0.5}, {0.0, 0.8}, {2.5, 1.4}};
    constexpr int kSamples = 100000;
    constexpr int kBins = 16;
    std::mt19937_64 rng(3);
    for (const Case& k : cases) {
        const SpotDiscMap map(k.n, k.c);
        std::vector<int> counts(kBins, 0);
        for (int i = 0; i < kSamples; ++i) {
            const glm::dvec3 d = map.toDirection(randomInDisc(rng));
            const double alpha = std::acos(std::clamp(d.z, -1.0, 1.0));
            ++counts[std::min(kBins - 1, static_cast<int>(alpha / k.c * kBins))];
        }
        auto density = [&](double a) { return std::pow(std::cos(a), k.n) * std::sin(a); };
        auto simpson = [&](double a, double b) {
            constexpr int kSteps = 200;
            const double h = (b - a) / kSteps;
            double sum = density(a) + density(b);
            for (int s = 1; s < kSteps; ++s) sum += density(a + s * h) * (s % 2 ? 4.0 : 2.0);
            return sum * h / 3.0;
        };
        const double total = simpson(0.0, k.c);
        for (int b = 0; b < kBins; ++b) {
            const double p = simpson(k.c * b / kBins, k.c * (b + 1) / kBins) / total;
            const double sigma = std::sqrt(p * (1.0 - p) / kSamples);
            // 5 binomial standard deviations: 80 bins in all, false alarm odds ~5e-5 (and the seed is
            // fixed, so the test is deterministic).
            EXPECT_NEAR(counts[b] / static_cast<double>(kSamples), p, 5.0 * sigma + 1e-12)
                << "n " << k.n << " c " << k.c << " bin " << b;
        }
    }
}

// ---------------------------------------------------------------- exact cell geometry

TEST(IirDiscCell, KnownCells) {
    // One site: the whole disc; the empty circle is centred on the rim opposite it.
    DiscCell one = computeDiscCell({0.3, 0.4}, {}, 0.0);
    EXPECT_NEAR(one.area, kPi, 1e-14);
    EXPECT_NEAR(one.farthestDistance, 1.5, 1e-14);
    EXPECT_NEAR(glm::distance(one.farthestPoint, glm::dvec2(-0.6, -0.8)), 0.0, 1e-14);

    // Two sites symmetric about the origin: half discs.
    const glm::dvec2 a(0.5, 0.0), b(-0.5, 0.0);
    const DiscCell half = computeDiscCell(a, std::span(&b, 1), 0.0);
    EXPECT_NEAR(half.area, kPi / 2.0, 1e-14);
    EXPECT_NEAR(half.farthestDistance, std::sqrt(0.25 + 1.0), 1e-14);  // at (0, +-1)

    // A centre site with six at radius 0.5: a regular hexagon of apothem 0.25 in the middle, six
    // equal cells outside.
    std::vector<glm::dvec2> ring;
    for (int i = 0; i < 6; ++i) ring.emplace_back(0.5 * std::cos(i * kPi / 3.0), 0.5 * std::sin(i * kPi / 3.0));
    const DiscCell centre = computeDiscCell({0.0, 0.0}, ring, 0.0);
    const double hexagon = 2.0 * std::sqrt(3.0) * 0.25 * 0.25;
    EXPECT_NEAR(centre.area, hexagon, 1e-14);
    EXPECT_NEAR(centre.farthestDistance, 0.25 / std::cos(kPi / 6.0), 1e-14);  // hexagon corner
    std::vector<glm::dvec2> around{{0.0, 0.0}, ring[1], ring[5]};
    const DiscCell outer = computeDiscCell(ring[0], around, 0.0);
    EXPECT_NEAR(outer.area, (kPi - hexagon) / 6.0, 1e-13);
    // Farthest point of the outer cell: where its bisector with a ring neighbour meets the rim.
    EXPECT_NEAR(glm::length(outer.farthestPoint), 1.0, 1e-14);

    // A site at the centre alone: every rim point is equally far; the tie angle picks one.
    const DiscCell centred = computeDiscCell({0.0, 0.0}, {}, 1.0);
    EXPECT_NEAR(glm::distance(centred.farthestPoint, glm::dvec2(std::cos(1.0), std::sin(1.0))), 0.0, 1e-15);
}

TEST(IirSphereCells, TrianglesAndLunes) {
    // The octant triangle covers 1/8 of the sphere.
    EXPECT_NEAR(signedSphericalTriangleArea({1, 0, 0}, {0, 1, 0}, {0, 0, 1}), kPi / 2.0, 1e-14);
    EXPECT_NEAR(signedSphericalTriangleArea({1, 0, 0}, {0, 0, 1}, {0, 1, 0}), -kPi / 2.0, 1e-14);
    // Three sites on the equator at azimuths 0, 90 and 180 degrees: each cell is a lune of area
    // (gap before + gap after).
    const glm::dvec3 sites[] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}};
    double areas[3];
    planarSphereCellAreas({0, 0, 1}, sites, areas);
    EXPECT_NEAR(areas[0], kPi / 2.0 + kPi, 1e-14);  // gaps: 180 (from -x) and 90
    EXPECT_NEAR(areas[1], kPi, 1e-14);
    EXPECT_NEAR(areas[2], kPi / 2.0 + kPi, 1e-14);
}

// ---------------------------------------------------------------- disc triangulation

TEST(IirDiscTriangulation, DelaunayAndAreasUnderInsertAndRemove) {
    std::mt19937_64 rng(11);
    DiscTriangulation t(400, 1);
    fillDiscRandom(t, 300, rng);
    for (SlotId s = 0; s < 300; s += 3) t.remove(s);
    std::vector<std::array<SlotId, 3>> faces;
    t.triangles(faces);
    ASSERT_FALSE(faces.empty());
    const std::vector<glm::dvec3> sites = pointsOf(t);
    // Empty circumcircles: no site strictly inside any Delaunay triangle's circumcircle (relative
    // slack for the circumcentre's rounding; CGAL decides with exact predicates).
    for (const auto& f : faces) {
        const glm::dvec2 a(t.point(f[0])), b(t.point(f[1])), c(t.point(f[2]));
        const double d = 2.0 * (a.x * (b.y - c.y) + b.x * (c.y - a.y) + c.x * (a.y - b.y));
        const glm::dvec2 centre(((glm::dot(a, a)) * (b.y - c.y) + glm::dot(b, b) * (c.y - a.y) + glm::dot(c, c) * (a.y - b.y)) / d,
                                ((glm::dot(a, a)) * (c.x - b.x) + glm::dot(b, b) * (a.x - c.x) + glm::dot(c, c) * (b.x - a.x)) / d);
        const double radius = glm::distance(centre, a);
        for (const glm::dvec3& p : sites) EXPECT_GE(glm::distance(glm::dvec2(p), centre), radius * (1.0 - 1e-9));
    }
    std::vector<double> areas(400);
    t.cellAreas(areas);
    double sum = 0.0;
    for (double a : areas) sum += a;
    EXPECT_NEAR(sum, kPi, kAreaSumTolerance);
}

TEST(IirDiscTriangulation, CellAreasMatchPixelCounting) {
    std::mt19937_64 rng(12);
    DiscTriangulation t(12, 1);
    fillDiscRandom(t, 12, rng);
    std::vector<double> areas(12);
    t.cellAreas(areas);
    const std::vector<glm::dvec3> sites = pointsOf(t);  // slot order = insertion order here
    constexpr int kGrid = 1000;
    constexpr double h = 2.0 / kGrid;
    std::vector<double> counted(12, 0.0);
    for (int i = 0; i < kGrid; ++i) {
        for (int j = 0; j < kGrid; ++j) {
            const glm::dvec3 x(-1.0 + (i + 0.5) * h, -1.0 + (j + 0.5) * h, 0.0);
            if (x.x * x.x + x.y * x.y > 1.0) continue;
            size_t nearest = 0;
            for (size_t k = 1; k < sites.size(); ++k)
                if (glm::distance(x, sites[k]) < glm::distance(x, sites[nearest])) nearest = k;
            counted[nearest] += h * h;
        }
    }
    for (size_t k = 0; k < 12; ++k) {
        // Only pixels cut by the cell's boundary can be miscounted: at most (perimeter / h + 4) * 2
        // of them, each h^2, and a convex region in the disc has perimeter <= 2 pi: 4 pi h + 8 h^2.
        EXPECT_NEAR(counted[k], areas[k], 4.0 * kPi * h + 8.0 * h * h) << "cell " << k;
    }
}

TEST(IirDiscTriangulation, LargestEmptyCircleIsTheDispersion) {
    std::mt19937_64 rng(13);
    for (int count : {1, 2, 3, 7, 40}) {
        DiscTriangulation t(64, 5);
        fillDiscRandom(t, count, rng);
        const DomainTriangulation::EmptyCircle circle = t.largestEmptyCircle();
        const std::vector<glm::dvec3> sites = pointsOf(t);
        // The circle is empty and centred in the disc, its radius is its nearest-site distance.
        EXPECT_LE(glm::length(circle.centre), 1.0 + 1e-12);
        EXPECT_NEAR(nearestDistance(circle.centre, sites), circle.radius, 1e-12);
        constexpr double h = 0.01;
        constexpr int kRim = 4096;
        const double brute = bruteDiscDispersion(sites, h, kRim);
        EXPECT_LE(brute, circle.radius + 1e-12) << count << " sites";
        EXPECT_GE(brute, circle.radius - (std::sqrt(2.0) * h + 2.0 * kPi / kRim)) << count << " sites";
    }
}

TEST(IirDiscTriangulation, CollinearAndCoincidentSites) {
    DiscTriangulation t(8, 1);
    ASSERT_TRUE(t.insert({0, {-0.5, 0.0, 0.0}}));
    ASSERT_TRUE(t.insert({1, {0.0, 0.0, 0.0}}));
    ASSERT_TRUE(t.insert({2, {0.5, 0.0, 0.0}}));
    EXPECT_FALSE(t.insert({3, {0.5, 0.0, 0.0}}));  // on top of slot 2
    EXPECT_FALSE(t.contains(3));
    std::vector<double> areas(8);
    t.cellAreas(areas);
    // Strips between x = -0.25 and 0.25: the middle one is 2 * (0.25 sqrt(1-0.0625) + asin(0.25)).
    const double middle = 2.0 * (0.25 * std::sqrt(1.0 - 0.0625) + std::asin(0.25));
    EXPECT_NEAR(areas[1], middle, 1e-14);
    EXPECT_NEAR(areas[0], (kPi - middle) / 2.0, 1e-14);
    std::vector<SlotId> around;
    t.neighbours(1, around);
    std::sort(around.begin(), around.end());
    EXPECT_EQ(around, (std::vector<SlotId>{0, 2}));
    const DomainTriangulation::EmptyCircle circle = t.largestEmptyCircle();
    // The farthest points are where the bisector x = +-0.25 meets the rim, or (0, +-1).
    EXPECT_NEAR(circle.radius, std::sqrt(0.25 * 0.25 + 1.0 - 0.0625), 1e-14);
}

TEST(IirDiscTriangulation, ShortestEdgeDeletionIncreasesTheMinimumDistance) {
    std::mt19937_64 rng(14);
    DiscTriangulation t(200, 1);
    fillDiscRandom(t, 200, rng);
    double before = minPairwiseDistance(pointsOf(t));
    for (int i = 0; i < 150; ++i) {
        const std::optional<DomainTriangulation::Edge> edge = t.shortestEdge();
        ASSERT_TRUE(edge.has_value());
        EXPECT_NEAR(edge->length, before, 1e-15);  // the closest pair is a Delaunay edge
        const std::optional<SlotId> victim = t.shortestEdgeVictim();
        ASSERT_TRUE(victim.has_value());
        EXPECT_TRUE(*victim == edge->a || *victim == edge->b);
        t.remove(*victim);
        const double after = minPairwiseDistance(pointsOf(t));
        // Random points: the closest pair is unique, so the minimum distance strictly grows.
        EXPECT_GT(after, before);
        before = after;
    }
}

TEST(IirDiscTriangulation, GreedyInsertionReducesDispersion) {
    DiscTriangulation t(256, 9);
    double previous = DomainTriangulation::kEmptyDomainRadius;
    for (SlotId n = 0; n < 256; ++n) {
        const DomainTriangulation::EmptyCircle circle = t.largestEmptyCircle();
        EXPECT_LE(circle.radius, previous + 1e-12);  // adding points never increases Eq. (1)
        previous = circle.radius;
        ASSERT_TRUE(t.insert({n, circle.centre}));
        const double delta = t.largestEmptyCircle().radius;
        const double count = n + 1.0;
        // n circles of radius delta must cover the disc: delta >= 1/sqrt(n). Farthest-point
        // insertion keeps all pairwise distances >= delta, so n disjoint discs of radius delta/2 fit
        // in the disc of radius 1 + delta/2: delta <= 2/(sqrt(n) - 1).
        if (count >= 4) {
            EXPECT_GE(delta, 1.0 / std::sqrt(count) - 1e-12) << count;
            EXPECT_LE(delta, 2.0 / (std::sqrt(count) - 1.0) + 1e-12) << count;
        }
    }
    std::vector<double> areas(256);
    t.cellAreas(areas);
    double sum = 0.0;
    for (double a : areas) sum += a;
    EXPECT_NEAR(sum, kPi, kAreaSumTolerance);
}

// ---------------------------------------------------------------- sphere triangulation

TEST(IirSphereTriangulation, EmptyCapsAndAreaSumUnderInsertAndRemove) {
    std::mt19937_64 rng(21);
    SphereTriangulation t(600, 1);
    fillSphereRandom(t, 500, rng);
    for (SlotId s = 0; s < 500; s += 2) t.remove(s);
    const std::vector<glm::dvec3> sites = pointsOf(t);
    std::vector<std::array<SlotId, 3>> faces;
    t.triangles(faces);
    ASSERT_EQ(faces.size(), 2 * sites.size() - 4);  // Euler: a triangulated sphere
    for (const auto& f : faces) {
        const glm::dvec3 a = t.point(f[0]), b = t.point(f[1]), c = t.point(f[2]);
        const glm::dvec3 centre = glm::normalize(glm::cross(b - a, c - a));
        const double radius = glm::distance(centre, a);
        // The cap centred on the outward normal through the face's vertices holds no site.
        for (const glm::dvec3& p : sites) EXPECT_GE(glm::distance(p, centre), radius - 1e-12);
    }
    std::vector<double> areas(600);
    t.cellAreas(areas);
    double sum = 0.0;
    for (double a : areas) sum += a;
    EXPECT_NEAR(sum, 4.0 * kPi, kAreaSumTolerance);
}

TEST(IirSphereTriangulation, PlatonicSolidsHaveEqualCells) {
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    const std::vector<std::vector<glm::dvec3>> solids{
        {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}},                            // tetrahedron
        {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},         // octahedron
        {{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {1, -1, -1}, {-1, 1, 1}, {-1, 1, -1}, {-1, -1, 1}, {-1, -1, -1}},  // cube
        {{0, 1, g}, {0, 1, -g}, {0, -1, g}, {0, -1, -g}, {1, g, 0}, {1, -g, 0}, {-1, g, 0}, {-1, -g, 0},
         {g, 0, 1}, {g, 0, -1}, {-g, 0, 1}, {-g, 0, -1}}};                             // icosahedron
    for (const auto& solid : solids) {
        SphereTriangulation t(solid.size(), 1);
        for (size_t i = 0; i < solid.size(); ++i) ASSERT_TRUE(t.insert({static_cast<SlotId>(i), glm::normalize(solid[i])}));
        std::vector<double> areas(solid.size());
        t.cellAreas(areas);
        // Symmetry: every cell is 4 pi / n (the cube's square faces split into two triangles whose
        // circumcentres coincide, which must not change anything).
        for (double a : areas) EXPECT_NEAR(a, 4.0 * kPi / solid.size(), 1e-12) << solid.size() << " vertices";
        // The empty cap is centred on a face centre: all sites are equally far and none nearer.
        const DomainTriangulation::EmptyCircle circle = t.largestEmptyCircle();
        std::vector<glm::dvec3> sites;
        for (const glm::dvec3& p : solid) sites.push_back(glm::normalize(p));
        EXPECT_NEAR(nearestDistance(circle.centre, sites), circle.radius, 1e-12);
    }
}

TEST(IirSphereTriangulation, TinyAndCoplanarSets) {
    const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    {
        SphereTriangulation t(8, 3);
        const DomainTriangulation::EmptyCircle empty = t.largestEmptyCircle();
        EXPECT_NEAR(glm::length(empty.centre), 1.0, 1e-15);
        ASSERT_TRUE(t.insert({0, x}));
        std::vector<double> areas(8);
        t.cellAreas(areas);
        EXPECT_NEAR(areas[0], 4.0 * kPi, 1e-15);
        EXPECT_NEAR(glm::distance(t.largestEmptyCircle().centre, -x), 0.0, 1e-15);
        ASSERT_TRUE(t.insert({1, y}));
        t.cellAreas(areas);
        EXPECT_NEAR(areas[0], 2.0 * kPi, 1e-14);
        EXPECT_NEAR(areas[1], 2.0 * kPi, 1e-14);
        // Opposite the midpoint of x and y.
        EXPECT_NEAR(glm::distance(t.largestEmptyCircle().centre, -glm::normalize(x + y)), 0.0, 1e-15);
        ASSERT_TRUE(t.insert({2, -x}));  // three on the equator (a great circle)
        t.cellAreas(areas);
        EXPECT_NEAR(areas[0] + areas[1] + areas[2], 4.0 * kPi, 1e-13);
        // Azimuths 0, 90, 180 degrees: y's lune spans 45..135 degrees, i.e. (90 + 90) degrees of gaps.
        EXPECT_NEAR(areas[1], kPi, 1e-13);
        const DomainTriangulation::EmptyCircle pole = t.largestEmptyCircle();
        EXPECT_NEAR(std::abs(pole.centre.z), 1.0, 1e-15);
        EXPECT_NEAR(pole.radius, std::sqrt(2.0), 1e-15);
        ASSERT_TRUE(t.insert({3, -y}));  // four on the great circle
        t.cellAreas(areas);
        for (int i = 0; i < 4; ++i) EXPECT_NEAR(areas[i], kPi, 1e-13);
        ASSERT_TRUE(t.insert({4, z}));  // leaves the great circle
        t.cellAreas(areas);
        double sum = 0.0;
        for (double a : areas) sum += a;
        EXPECT_NEAR(sum, 4.0 * kPi, 1e-12);
        EXPECT_NEAR(glm::distance(t.largestEmptyCircle().centre, -z), 0.0, 1e-12);
    }
    {
        // Six sites on a small circle (latitude 30 degrees): a flat hull; lunes of 60 degrees each.
        SphereTriangulation t(6, 3);
        for (SlotId i = 0; i < 6; ++i) {
            const double a = i * kPi / 3.0;
            ASSERT_TRUE(t.insert({i, glm::dvec3(std::cos(a) * std::cos(kPi / 6), std::sin(a) * std::cos(kPi / 6), 0.5)}));
        }
        std::vector<double> areas(6);
        t.cellAreas(areas);
        for (double a : areas) EXPECT_NEAR(a, 4.0 * kPi / 6.0, 1e-9);  // kCoplanarTolerance
        // The south pole is farthest from all six.
        EXPECT_NEAR(glm::distance(t.largestEmptyCircle().centre, -z), 0.0, 1e-9);
    }
}

TEST(IirSphereTriangulation, CellAreasMatchFibonacciQuadrature) {
    std::mt19937_64 rng(22);
    SphereTriangulation t(24, 1);
    fillSphereRandom(t, 24, rng);
    std::vector<double> areas(24);
    t.cellAreas(areas);
    const std::vector<glm::dvec3> sites = pointsOf(t);
    constexpr int kQuadrature = 200000;
    std::vector<double> counted(24, 0.0);
    for (const glm::dvec3& x : fibonacciSphere(kQuadrature)) {
        size_t nearest = 0;
        for (size_t k = 1; k < sites.size(); ++k)
            if (glm::distance(x, sites[k]) < glm::distance(x, sites[nearest])) nearest = k;
        counted[nearest] += 4.0 * kPi / kQuadrature;
    }
    // Each lattice point stands for 4 pi / N of area; only points within one spacing
    // s = sqrt(4 pi / N) of a cell's boundary can be misattributed, so the error is below
    // perimeter * s; a spherical cell contained in a hemisphere has perimeter <= 2 pi.
    const double spacing = std::sqrt(4.0 * kPi / kQuadrature);
    for (size_t k = 0; k < 24; ++k) EXPECT_NEAR(counted[k], areas[k], 2.0 * kPi * spacing) << "cell " << k;
}

TEST(IirSphereTriangulation, LargestEmptyCircleIsTheDispersion) {
    std::mt19937_64 rng(23);
    const std::vector<glm::dvec3> probes = fibonacciSphere(60000);
    // Probe spacing: every point of the sphere is within about sqrt(4 pi / N) of a probe; twice that
    // is a safe bound for the lattice's covering radius.
    const double probeSlack = 2.0 * std::sqrt(4.0 * kPi / probes.size());
    for (int count : {5, 9, 60}) {
        SphereTriangulation t(64, 2);
        fillSphereRandom(t, count, rng);
        const DomainTriangulation::EmptyCircle circle = t.largestEmptyCircle();
        const std::vector<glm::dvec3> sites = pointsOf(t);
        EXPECT_NEAR(nearestDistance(circle.centre, sites), circle.radius, 1e-12);
        double brute = 0.0;
        for (const glm::dvec3& x : probes) brute = std::max(brute, nearestDistance(x, sites));
        EXPECT_LE(brute, circle.radius + 1e-12) << count;
        EXPECT_GE(brute, circle.radius - probeSlack) << count;
    }
}

TEST(IirSphereTriangulation, GreedyInsertionReducesDispersion) {
    SphereTriangulation t(256, 4);
    double previous = DomainTriangulation::kEmptyDomainRadius;
    for (SlotId n = 0; n < 256; ++n) {
        const DomainTriangulation::EmptyCircle circle = t.largestEmptyCircle();
        EXPECT_LE(circle.radius, previous + 1e-12);
        previous = circle.radius;
        ASSERT_TRUE(t.insert({n, circle.centre}));
        const double delta = t.largestEmptyCircle().radius;
        const double count = n + 1.0;
        // A cap of chordal radius r has area pi r^2 (Archimedes). n caps of radius delta cover the
        // sphere: delta >= 2/sqrt(n); caps of radius delta/2 around farthest-point samples are
        // disjoint: delta <= 4/sqrt(n).
        if (count >= 4) {
            EXPECT_GE(delta, 2.0 / std::sqrt(count) - 1e-12) << count;
            EXPECT_LE(delta, 4.0 / std::sqrt(count) + 1e-12) << count;
        }
    }
    std::vector<double> areas(256);
    t.cellAreas(areas);
    double sum = 0.0;
    for (double a : areas) sum += a;
    EXPECT_NEAR(sum, 4.0 * kPi, kAreaSumTolerance);
}

TEST(IirSphereTriangulation, ShortestEdgeDeletionIncreasesTheMinimumDistance) {
    std::mt19937_64 rng(24);
    SphereTriangulation t(200, 1);
    fillSphereRandom(t, 200, rng);
    double before = minPairwiseDistance(pointsOf(t));
    for (int i = 0; i < 190; ++i) {
        const std::optional<SlotId> victim = t.shortestEdgeVictim();
        ASSERT_TRUE(victim.has_value());
        t.remove(*victim);
        const double after = minPairwiseDistance(pointsOf(t));
        EXPECT_GT(after, before);
        before = after;
    }
}

// ---------------------------------------------------------------- per-frame VPL maintenance


#include "techniques/iir/DiscCell.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace bounce {

namespace {

// Half-size of the square the clipping starts from. Any value > 1 works: it only has to contain the
// unit disc, since the region is intersected with the disc afterwards.
constexpr double kStartSquareHalfSize = 2.0;

struct BoundaryPiece {
    glm::dvec2 start;
    glm::dvec2 end;
    bool endsOnRim = false;  // the polygon leaves the disc at `end`; an arc follows
};

double cross(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

// Keeps the part of a convex polygon where dot(normal, x) <= offset (Sutherland-Hodgman).
void clipHalfPlane(std::vector<glm::dvec2>& polygon, std::vector<glm::dvec2>& scratch, const glm::dvec2& normal,
                   double offset) {
    scratch.clear();
    const size_t count = polygon.size();
    for (size_t i = 0; i < count; ++i) {
        const glm::dvec2& a = polygon[i];
        const glm::dvec2& b = polygon[(i + 1) % count];
        const double da = glm::dot(normal, a) - offset;
        const double db = glm::dot(normal, b) - offset;
        const bool aInside = da <= 0.0, bInside = db <= 0.0;
        if (aInside) scratch.push_back(a);
        if (aInside != bInside) scratch.push_back(a + (b - a) * (da / (da - db)));
    }
    polygon.swap(scratch);
}

// Parameter interval [lo, hi] of the segment a + t (b - a), t in [0, 1], inside the unit circle.
bool insideInterval(const glm::dvec2& a, const glm::dvec2& b, double& lo, double& hi) {
    const glm::dvec2 d = b - a;
    const double qa = glm::dot(d, d);
    if (qa == 0.0) return false;
    const double halfB = glm::dot(a, d);
    const double qc = glm::dot(a, a) - 1.0;
    const double disc = halfB * halfB - qa * qc;
    if (disc <= 0.0) return false;  // misses or touches the circle: no area either way
    const double root = std::sqrt(disc);
    // Numerically stable pair of roots.
    const double q = halfB >= 0.0 ? -(halfB + root) : -(halfB - root);
    double t0 = q / qa;
    double t1 = q != 0.0 ? qc / q : -t0;
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(t0, 0.0);
    hi = std::min(t1, 1.0);
    return lo < hi;
}

double angleOf(const glm::dvec2& p) { return std::atan2(p.y, p.x); }

// Counter-clockwise angle from direction a to direction b, in [0, 2 pi).
double ccwAngle(const glm::dvec2& a, const glm::dvec2& b) {
    double angle = std::atan2(cross(a, b), glm::dot(a, b));
    if (angle < 0.0) angle += glm::two_pi<double>();
    return angle;
}

bool containsOrigin(const std::vector<glm::dvec2>& polygon) {
    const size_t count = polygon.size();
    if (count < 3) return false;
    for (size_t i = 0; i < count; ++i) {
        const glm::dvec2& a = polygon[i];
        const glm::dvec2& b = polygon[(i + 1) % count];
        if (cross(b - a, -a) < 0.0) return false;  // origin right of a ccw edge
    }
    return true;
}

}  // namespace

DiscCell computeDiscCell(const glm::dvec2& site, std::span<const glm::dvec2> neighbours, double tieAngle) {
    constexpr double h = kStartSquareHalfSize;
    std::vector<glm::dvec2> polygon{{-h, -h}, {h, -h}, {h, h}, {-h, h}};
    std::vector<glm::dvec2> scratch;
    polygon.reserve(16);
    scratch.reserve(16);
    for (const glm::dvec2& q : neighbours) {
        const glm::dvec2 normal = q - site;
        if (normal.x == 0.0 && normal.y == 0.0) continue;
        clipHalfPlane(polygon, scratch, normal, glm::dot(normal, 0.5 * (site + q)));
    }

    // Walk the ccw polygon keeping the parts inside the disc; between leaving and re-entering the
    // disc the region's boundary follows the circle counter-clockwise (the region is convex).
    std::vector<BoundaryPiece> pieces;
    pieces.reserve(polygon.size());
    const size_t count = polygon.size();
    for (size_t i = 0; i < count; ++i) {
        const glm::dvec2& a = polygon[i];
        const glm::dvec2& b = polygon[(i + 1) % count];
        double lo = 0.0, hi = 0.0;
        if (!insideInterval(a, b, lo, hi)) continue;
        BoundaryPiece piece;
        // Points on the rim are re-projected onto it so that arcs start and end exactly there.
        piece.start = lo > 0.0 ? glm::normalize(a + (b - a) * lo) : a;
        piece.end = hi < 1.0 ? glm::normalize(a + (b - a) * hi) : b;
        piece.endsOnRim = hi < 1.0;
        pieces.push_back(piece);
    }

    DiscCell cell;
    const double siteLength = glm::length(site);
    // The rim point farthest from the site is the one opposite it (the paper's case 3).
    const glm::dvec2 opposite =
        siteLength > 0.0 ? -site / siteLength : glm::dvec2(std::cos(tieAngle), std::sin(tieAngle));

    if (pieces.empty()) {
        if (containsOrigin(polygon)) {  // the cell contains the whole disc
            cell.area = glm::pi<double>();
            cell.farthestPoint = opposite;
            cell.farthestDistance = glm::distance(opposite, site);
        } else {  // degenerate (site on the rim with a sliver cell): nothing of positive area
            cell.farthestPoint = site;
        }
        return cell;
    }

    auto consider = [&](const glm::dvec2& p) {
        const double distance = glm::distance(p, site);
        if (distance > cell.farthestDistance) {
            cell.farthestDistance = distance;
            cell.farthestPoint = p;
        }
    };

    double twiceChordArea = 0.0;
    double segmentArea = 0.0;
    const double oppositeAngle = angleOf(opposite);
    const size_t pieceCount = pieces.size();
    for (size_t k = 0; k < pieceCount; ++k) {
        const BoundaryPiece& piece = pieces[k];
        const BoundaryPiece& next = pieces[(k + 1) % pieceCount];
        twiceChordArea += cross(piece.start, piece.end) + cross(piece.end, next.start);
        consider(piece.start);
        consider(piece.end);
        if (piece.endsOnRim) {
            const double arc = ccwAngle(piece.end, next.start);
            segmentArea += 0.5 * (arc - std::sin(arc));  // circular segment cut off by the chord
            double offset = oppositeAngle - angleOf(piece.end);
            if (offset < 0.0) offset += glm::two_pi<double>();
            if (offset <= arc) consider(opposite);
        }
    }
    cell.area = 0.5 * twiceChordArea + segmentArea;
    return cell;
}

}  // namespace bounce

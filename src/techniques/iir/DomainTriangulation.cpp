#include "techniques/iir/DomainTriangulation.h"

#include <glm/geometric.hpp>

#include <limits>

namespace bounce {

double DomainTriangulation::secondClosestNeighbourDistance(SlotId slot) const {
    std::vector<SlotId> around;
    neighbours(slot, around);
    const glm::dvec3 p = point(slot);
    double closest = std::numeric_limits<double>::infinity();
    double second = std::numeric_limits<double>::infinity();
    for (SlotId other : around) {
        const double distance = glm::distance(p, point(other));
        if (distance < closest) {
            second = closest;
            closest = distance;
        } else if (distance < second) {
            second = distance;
        }
    }
    return second;
}

std::optional<SlotId> DomainTriangulation::shortestEdgeVictim() const {
    const std::optional<Edge> edge = shortestEdge();
    if (!edge) return std::nullopt;
    const double a = secondClosestNeighbourDistance(edge->a);
    const double b = secondClosestNeighbourDistance(edge->b);
    if (a < b) return edge->a;
    if (b < a) return edge->b;
    return std::min(edge->a, edge->b);
}

}  // namespace bounce

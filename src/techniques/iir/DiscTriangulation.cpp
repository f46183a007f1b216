#include "techniques/iir/DiscTriangulation.h"

#include "core/Check.h"
#include "techniques/iir/DiscCell.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <random>
#include <utility>

namespace bounce {

namespace {

// Exact predicates keep the triangulation valid however close the points get; constructions (the
// cell geometry) are done in double by DiscCell.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<SlotId, Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, DataStructure>;
using VertexHandle = Delaunay::Vertex_handle;
using CgalPoint = Kernel::Point_2;

glm::dvec2 toGlm(const CgalPoint& p) { return glm::dvec2(p.x(), p.y()); }

DomainTriangulation::Edge orderedEdge(SlotId a, SlotId b, double length) {
    return a < b ? DomainTriangulation::Edge{a, b, length} : DomainTriangulation::Edge{b, a, length};
}

}  // namespace

struct DiscTriangulation::Impl {
    Delaunay dt;
    std::vector<VertexHandle> vertexBySlot;
    std::vector<DiscCell> cellBySlot;
    std::vector<uint8_t> cellDirty;
    std::vector<SlotId> dirtySlots;
    double tieAngle = 0.0;

    void markDirty(SlotId slot) {
        if (cellDirty[slot]) return;
        cellDirty[slot] = 1;
        dirtySlots.push_back(slot);
    }
    void markWithNeighbours(VertexHandle v) {
        markDirty(v->info());
        if (dt.dimension() < 1) return;
        Delaunay::Vertex_circulator around = dt.incident_vertices(v), done = around;
        if (around == nullptr) return;
        do {
            if (!dt.is_infinite(around)) markDirty(around->info());
        } while (++around != done);
    }
    void markAll() {
        for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) markDirty(v->info());
    }
    void refreshCells() {
        std::vector<glm::dvec2> around;
        std::vector<SlotId> aroundSlots;
        for (SlotId slot : dirtySlots) {
            cellDirty[slot] = 0;
            const VertexHandle v = vertexBySlot[slot];
            if (v == VertexHandle()) {
                cellBySlot[slot] = DiscCell{};
                continue;
            }
            around.clear();
            aroundSlots.clear();
            if (dt.dimension() >= 1) {
                Delaunay::Vertex_circulator it = dt.incident_vertices(v), done = it;
                if (it != nullptr) {
                    do {
                        if (!dt.is_infinite(it)) {
                            around.push_back(toGlm(it->point()));
                            aroundSlots.push_back(it->info());
                        }
                    } while (++it != done);
                }
            }
            // The circulator starts at whichever neighbour the vertex's face happens to hold, which
            // follows CGAL's memory layout (runs differed with address-space randomisation). Starting
            // the counter-clockwise list at the lowest slot makes the cell's sums the same every run.
            if (!aroundSlots.empty()) {
                const auto first = std::min_element(aroundSlots.begin(), aroundSlots.end()) - aroundSlots.begin();
                std::rotate(around.begin(), around.begin() + first, around.end());
            }
            cellBySlot[slot] = computeDiscCell(toGlm(v->point()), around, tieAngle);
        }
        dirtySlots.clear();
    }
};

DiscTriangulation::DiscTriangulation(size_t slotCapacity, uint64_t seed) : m_impl(std::make_unique<Impl>()) {
    m_impl->vertexBySlot.assign(slotCapacity, VertexHandle());
    m_impl->cellBySlot.assign(slotCapacity, DiscCell{});
    m_impl->cellDirty.assign(slotCapacity, 0);
    std::mt19937_64 rng(seed);
    // 53 random bits to [0, 1): the same on every platform, unlike std::uniform_real_distribution.
    m_impl->tieAngle = glm::two_pi<double>() * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

DiscTriangulation::~DiscTriangulation() = default;

size_t DiscTriangulation::slotCapacity() const { return m_impl->vertexBySlot.size(); }

double DiscTriangulation::domainArea() const { return glm::pi<double>(); }

size_t DiscTriangulation::size() const { return m_impl->dt.number_of_vertices(); }

bool DiscTriangulation::contains(SlotId slot) const {
    return slot < m_impl->vertexBySlot.size() && m_impl->vertexBySlot[slot] != VertexHandle();
}

glm::dvec3 DiscTriangulation::point(SlotId slot) const {
    BOUNCE_CHECK(contains(slot), "disc slot {} has no point", slot);
    const CgalPoint& p = m_impl->vertexBySlot[slot]->point();
    return glm::dvec3(p.x(), p.y(), 0.0);
}

void DiscTriangulation::clear() {
    Impl& m = *m_impl;
    m.dt.clear();
    std::fill(m.vertexBySlot.begin(), m.vertexBySlot.end(), VertexHandle());
    std::fill(m.cellBySlot.begin(), m.cellBySlot.end(), DiscCell{});
    std::fill(m.cellDirty.begin(), m.cellDirty.end(), 0);
    m.dirtySlots.clear();
}

std::vector<SlotId> DiscTriangulation::rebuild(std::span<const Site> sites) {
    clear();
    Impl& m = *m_impl;
    std::vector<std::pair<CgalPoint, SlotId>> input;
    input.reserve(sites.size());
    for (const Site& site : sites) {
        BOUNCE_CHECK(site.slot < m.vertexBySlot.size(), "disc slot {} out of range", site.slot);
        input.emplace_back(CgalPoint(site.point.x, site.point.y), site.slot);
    }
    // The range insertion sorts spatially (with CGAL's fixed-seed shuffle, so it is deterministic).
    m.dt.insert(input.begin(), input.end());
    for (auto v = m.dt.finite_vertices_begin(); v != m.dt.finite_vertices_end(); ++v)
        m.vertexBySlot[v->info()] = v;
    std::vector<SlotId> rejected;
    for (const Site& site : sites)
        if (m.vertexBySlot[site.slot] == VertexHandle()) rejected.push_back(site.slot);
    m.markAll();
    return rejected;
}

bool DiscTriangulation::insert(const Site& site) {
    Impl& m = *m_impl;
    BOUNCE_CHECK(site.slot < m.vertexBySlot.size(), "disc slot {} out of range", site.slot);
    BOUNCE_CHECK(!contains(site.slot), "disc slot {} is already used", site.slot);
    const size_t before = m.dt.number_of_vertices();
    const VertexHandle v = m.dt.insert(CgalPoint(site.point.x, site.point.y));
    if (m.dt.number_of_vertices() == before) return false;  // coincides with a present site
    v->info() = site.slot;
    m.vertexBySlot[site.slot] = v;
    m.markWithNeighbours(v);
    return true;
}

void DiscTriangulation::remove(SlotId slot) {
    Impl& m = *m_impl;
    BOUNCE_CHECK(contains(slot), "disc slot {} has no point to remove", slot);
    const VertexHandle v = m.vertexBySlot[slot];
    m.markWithNeighbours(v);  // the neighbours absorb the removed cell
    m.dt.remove(v);
    m.vertexBySlot[slot] = VertexHandle();
}

void DiscTriangulation::neighbours(SlotId slot, std::vector<SlotId>& out) const {
    out.clear();
    BOUNCE_CHECK(contains(slot), "disc slot {} has no point", slot);
    const Delaunay& dt = m_impl->dt;
    if (dt.dimension() < 1) return;
    Delaunay::Vertex_circulator it = dt.incident_vertices(m_impl->vertexBySlot[slot]), done = it;
    if (it == nullptr) return;
    do {
        if (!dt.is_infinite(it)) out.push_back(it->info());
    } while (++it != done);
}

std::optional<DomainTriangulation::Edge> DiscTriangulation::shortestEdge() const {
    const Delaunay& dt = m_impl->dt;
    if (dt.dimension() < 1) return std::nullopt;
    std::optional<Edge> best;
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
        const VertexHandle a = e->first->vertex(Delaunay::ccw(e->second));
        const VertexHandle b = e->first->vertex(Delaunay::cw(e->second));
        const double length = glm::distance(toGlm(a->point()), toGlm(b->point()));
        // Equal lengths (symmetric layouts) go to the lower pair of slots, not to the first edge the
        // iteration meets: CGAL's iteration order is not the same from run to run.
        const Edge edge = orderedEdge(a->info(), b->info(), length);
        if (!best || edge.length < best->length ||
            (edge.length == best->length && std::pair(edge.a, edge.b) < std::pair(best->a, best->b)))
            best = edge;
    }
    return best;
}

DomainTriangulation::EmptyCircle DiscTriangulation::largestEmptyCircle() {
    Impl& m = *m_impl;
    if (m.dt.number_of_vertices() == 0) return EmptyCircle{glm::dvec3(0.0), kEmptyDomainRadius};
    m.refreshCells();
    EmptyCircle best{glm::dvec3(0.0), -1.0};
    for (SlotId slot = 0; slot < m.vertexBySlot.size(); ++slot) {
        if (m.vertexBySlot[slot] == VertexHandle()) continue;
        const DiscCell& cell = m.cellBySlot[slot];
        if (cell.farthestDistance > best.radius)
            best = EmptyCircle{glm::dvec3(cell.farthestPoint, 0.0), cell.farthestDistance};
    }
    return best;
}

void DiscTriangulation::cellAreas(std::span<double> areas) {
    Impl& m = *m_impl;
    BOUNCE_CHECK(areas.size() == m.vertexBySlot.size(), "{} areas for {} disc slots", areas.size(),
                 m.vertexBySlot.size());
    m.refreshCells();
    for (SlotId slot = 0; slot < m.vertexBySlot.size(); ++slot)
        areas[slot] = m.vertexBySlot[slot] == VertexHandle() ? 0.0 : m.cellBySlot[slot].area;
}

void DiscTriangulation::triangles(std::vector<std::array<SlotId, 3>>& out) const {
    out.clear();
    const Delaunay& dt = m_impl->dt;
    if (dt.dimension() < 2) return;
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
        out.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
}

void DiscTriangulation::edges(std::vector<Edge>& out) const {
    out.clear();
    const Delaunay& dt = m_impl->dt;
    if (dt.dimension() < 1) return;
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
        const VertexHandle a = e->first->vertex(Delaunay::ccw(e->second));
        const VertexHandle b = e->first->vertex(Delaunay::cw(e->second));
        out.push_back(Edge{a->info(), b->info(), glm::distance(toGlm(a->point()), toGlm(b->point()))});
    }
}

}  // namespace bounce

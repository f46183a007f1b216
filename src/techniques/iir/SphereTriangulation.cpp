#include "techniques/iir/SphereTriangulation.h"

#include "core/Check.h"
#include "techniques/iir/SphereCells.h"

#include <CGAL/Delaunay_triangulation_on_sphere_2.h>
#include <CGAL/Delaunay_triangulation_on_sphere_traits_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_on_sphere_face_base_2.h>
#include <CGAL/Triangulation_on_sphere_vertex_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <cmath>
#include <random>
#include <utility>

namespace bounce {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Traits = CGAL::Delaunay_triangulation_on_sphere_traits_2<Kernel>;
using VertexBase =
    CGAL::Triangulation_vertex_base_with_info_2<SlotId, Traits, CGAL::Triangulation_on_sphere_vertex_base_2<Traits>>;
using FaceBase = CGAL::Triangulation_on_sphere_face_base_2<Traits>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Delaunay = CGAL::Delaunay_triangulation_on_sphere_2<Traits, DataStructure>;
using VertexHandle = Delaunay::Vertex_handle;
using FaceHandle = Delaunay::Face_handle;
using CgalPoint = Kernel::Point_3;

// Points closer than this to one plane are treated as coplanar: the hull is then flat, its two sides'
// Voronoi vertices are antipodal and the triangle fan is undefined, so cells are computed as lunes.
// The lune formula's error grows with the offset from the plane, the fan's rounding error with its
// inverse (1e-16 / offset); 1e-9 keeps both below 1e-7 sr.
constexpr double kCoplanarTolerance = 1e-9;
// Two sites whose sum is shorter than this are antipodal for the two-site empty-circle search.
constexpr double kAntipodalTolerance = 1e-12;

glm::dvec3 toGlm(const CgalPoint& p) { return glm::dvec3(p.x(), p.y(), p.z()); }

double random01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

glm::dvec3 randomUnitVector(std::mt19937_64& rng) {
    const double z = 2.0 * random01(rng) - 1.0;
    const double phi = glm::two_pi<double>() * random01(rng);
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    return glm::dvec3(s * std::cos(phi), s * std::sin(phi), z);
}

glm::dvec3 outwardNormal(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& r) {
    // CGAL orders every face counter-clockwise seen from outside the hull (ghost faces included:
    // they are hull facets that face away from the centre), so this is the outward normal.
    return glm::cross(q - p, r - p);
}

}  // namespace

struct SphereTriangulation::Impl {
    Delaunay dt;
    std::vector<VertexHandle> vertexBySlot;
    std::mt19937_64 rng;
    FaceHandle hint;
    // Cached result of the coplanarity test (reset by every change).
    bool planarKnown = false;
    std::optional<glm::dvec3> planarAxis;

    // CGAL's traits accept only points within 2^-50 of the unit sphere; a normalised double vector is
    // usually within a few 2^-53, and one more renormalisation fixes the rare miss.
    std::optional<CgalPoint> onSphere(const glm::dvec3& p) const {
        glm::dvec3 q = p / glm::length(p);
        for (int attempt = 0; attempt < 3; ++attempt) {
            const CgalPoint candidate(q.x, q.y, q.z);
            if (dt.geom_traits().is_on_sphere(candidate)) return candidate;
            q /= std::sqrt(glm::dot(q, q));
        }
        return std::nullopt;
    }

    bool insertPoint(SlotId slot, const glm::dvec3& p) {
        const std::optional<CgalPoint> point = onSphere(p);
        if (!point) return false;
        const size_t before = dt.number_of_vertices();
        const VertexHandle v = dt.insert(*point, hint);
        if (v == VertexHandle() || dt.number_of_vertices() == before) return false;
        v->info() = slot;
        vertexBySlot[slot] = v;
        hint = v->face();
        planarKnown = false;
        return true;
    }

    std::vector<VertexHandle> vertices() const {
        std::vector<VertexHandle> out;
        out.reserve(dt.number_of_vertices());
        for (auto v = dt.vertices_begin(); v != dt.vertices_end(); ++v) out.push_back(v);
        return out;
    }

    // The normal of the plane holding every site, if there is one (always for three sites or fewer).
    const std::optional<glm::dvec3>& coplanarAxis() {
        if (planarKnown) return planarAxis;
        planarKnown = true;
        planarAxis.reset();
        const std::vector<VertexHandle> all = vertices();
        if (all.size() < 3) return planarAxis;
        // CGAL's dimension 1 means every point lies in one plane (a circle, not necessarily great).
        const glm::dvec3 p0 = toGlm(all[0]->point());
        const glm::dvec3 n = glm::normalize(
            outwardNormal(p0, toGlm(all[1]->point()), toGlm(all[2]->point())));
        if (dt.dimension() < 2) {
            planarAxis = n;
            return planarAxis;
        }
        const double offset = glm::dot(n, p0);
        for (const VertexHandle& v : all)
            if (std::abs(glm::dot(n, toGlm(v->point())) - offset) > kCoplanarTolerance) return planarAxis;
        planarAxis = n;
        return planarAxis;
    }
};

SphereTriangulation::SphereTriangulation(size_t slotCapacity, uint64_t seed) : m_impl(std::make_unique<Impl>()) {
    m_impl->vertexBySlot.assign(slotCapacity, VertexHandle());
    m_impl->rng.seed(seed);
}

SphereTriangulation::~SphereTriangulation() = default;

size_t SphereTriangulation::slotCapacity() const { return m_impl->vertexBySlot.size(); }

double SphereTriangulation::domainArea() const { return 4.0 * glm::pi<double>(); }

size_t SphereTriangulation::size() const { return m_impl->dt.number_of_vertices(); }

bool SphereTriangulation::contains(SlotId slot) const {
    return slot < m_impl->vertexBySlot.size() && m_impl->vertexBySlot[slot] != VertexHandle();
}

glm::dvec3 SphereTriangulation::point(SlotId slot) const {
    BOUNCE_CHECK(contains(slot), "sphere slot {} has no point", slot);
    return toGlm(m_impl->vertexBySlot[slot]->point());
}

void SphereTriangulation::clear() {
    Impl& m = *m_impl;
    m.dt.clear();
    std::fill(m.vertexBySlot.begin(), m.vertexBySlot.end(), VertexHandle());
    m.hint = FaceHandle();
    m.planarKnown = false;
}

std::vector<SlotId> SphereTriangulation::rebuild(std::span<const Site> sites) {
    clear();
    Impl& m = *m_impl;
    using Entry = std::pair<CgalPoint, SlotId>;
    std::vector<Entry> input;
    input.reserve(sites.size());
    std::vector<SlotId> rejected;
    for (const Site& site : sites) {
        BOUNCE_CHECK(site.slot < m.vertexBySlot.size(), "sphere slot {} out of range", site.slot);
        const glm::dvec3 p = site.point;
        input.emplace_back(CgalPoint(p.x, p.y, p.z), site.slot);
    }
    // A 3D Hilbert order of the points keeps successive insertions close to the previous hint.
    CGAL::spatial_sort(input.begin(), input.end(),
                       CGAL::Spatial_sort_traits_adapter_3<Kernel, CGAL::First_of_pair_property_map<Entry>>());
    for (const Entry& entry : input)
        if (!m.insertPoint(entry.second, toGlm(entry.first))) rejected.push_back(entry.second);
    return rejected;
}

bool SphereTriangulation::insert(const Site& site) {
    Impl& m = *m_impl;
    BOUNCE_CHECK(site.slot < m.vertexBySlot.size(), "sphere slot {} out of range", site.slot);
    BOUNCE_CHECK(!contains(site.slot), "sphere slot {} is already used", site.slot);
    return m.insertPoint(site.slot, site.point);
}

void SphereTriangulation::remove(SlotId slot) {
    Impl& m = *m_impl;
    BOUNCE_CHECK(contains(slot), "sphere slot {} has no point to remove", slot);
    m.dt.remove(m.vertexBySlot[slot]);
    m.vertexBySlot[slot] = VertexHandle();
    m.hint = FaceHandle();
    m.planarKnown = false;
}

void SphereTriangulation::neighbours(SlotId slot, std::vector<SlotId>& out) const {
    out.clear();
    BOUNCE_CHECK(contains(slot), "sphere slot {} has no point", slot);
    const Delaunay& dt = m_impl->dt;
    const VertexHandle v = m_impl->vertexBySlot[slot];
    if (dt.dimension() < 1) {  // two sites (or one): each other's only neighbour
        for (auto w = dt.vertices_begin(); w != dt.vertices_end(); ++w)
            if (VertexHandle(w) != v) out.push_back(w->info());
        return;
    }
    Delaunay::Vertex_circulator it = dt.incident_vertices(v), done = it;
    if (it == nullptr) return;
    do {
        out.push_back(it->info());
    } while (++it != done);
}

std::optional<DomainTriangulation::Edge> SphereTriangulation::shortestEdge() const {
    std::vector<Edge> all;
    edges(all);
    std::optional<Edge> best;
    for (const Edge& e : all)
        if (!best || e.length < best->length) best = e;
    return best;
}

DomainTriangulation::EmptyCircle SphereTriangulation::largestEmptyCircle() {
    Impl& m = *m_impl;
    const std::vector<VertexHandle> all = m.vertices();
    if (all.empty()) return EmptyCircle{randomUnitVector(m.rng), kEmptyDomainRadius};
    const glm::dvec3 p = toGlm(all[0]->point());
    if (all.size() == 1) return EmptyCircle{-p, 2.0};
    if (all.size() == 2) {
        // No Voronoi vertex: the empty circle is centred on the bisecting great circle, farthest
        // from both sites, i.e. opposite their midpoint.
        const glm::dvec3 sum = p + toGlm(all[1]->point());
        glm::dvec3 centre;
        if (glm::length(sum) > kAntipodalTolerance) {
            centre = -glm::normalize(sum);
        } else {  // antipodal: every point of the bisecting great circle is equally far
            const glm::dvec3 r = randomUnitVector(m.rng);
            centre = glm::normalize(r - glm::dot(r, p) * p);
        }
        return EmptyCircle{centre, glm::distance(centre, p)};
    }
    if (const std::optional<glm::dvec3>& axis = m.coplanarAxis()) {
        // The only Voronoi vertices are the two poles of the sites' common circle.
        const double up = glm::distance(*axis, p), down = glm::distance(-*axis, p);
        return up >= down ? EmptyCircle{*axis, up} : EmptyCircle{-*axis, down};
    }
    // §4.6: without a boundary the largest empty circle is centred at a Voronoi vertex, the
    // circumcentre of a Delaunay face: the outward normal of a hull facet, where its empty cap is
    // centred.
    EmptyCircle best{glm::dvec3(0.0), -1.0};
    for (auto f = m.dt.all_faces_begin(); f != m.dt.all_faces_end(); ++f) {
        const glm::dvec3 a = toGlm(f->vertex(0)->point());
        const glm::dvec3 n = outwardNormal(a, toGlm(f->vertex(1)->point()), toGlm(f->vertex(2)->point()));
        const double length = glm::length(n);
        if (!(length > 0.0)) continue;
        const glm::dvec3 centre = n / length;
        const double radius = glm::distance(centre, a);
        if (radius > best.radius) best = EmptyCircle{centre, radius};
    }
    return best;
}

void SphereTriangulation::cellAreas(std::span<double> areas) {
    Impl& m = *m_impl;
    BOUNCE_CHECK(areas.size() == m.vertexBySlot.size(), "{} areas for {} sphere slots", areas.size(),
                 m.vertexBySlot.size());
    std::fill(areas.begin(), areas.end(), 0.0);
    const std::vector<VertexHandle> all = m.vertices();
    if (all.empty()) return;
    if (all.size() <= 2 || m.coplanarAxis()) {
        std::vector<glm::dvec3> sites;
        for (const VertexHandle& v : all) sites.push_back(toGlm(v->point()));
        glm::dvec3 axis(0.0);
        if (all.size() == 2) {
            const glm::dvec3 n = glm::cross(sites[0], sites[1]);
            // Antipodal pair: any great circle through both works; the cells are hemispheres.
            axis = glm::length(n) > kAntipodalTolerance
                       ? glm::normalize(n)
                       : glm::normalize(glm::cross(sites[0], std::abs(sites[0].x) < 0.9 ? glm::dvec3(1, 0, 0)
                                                                                        : glm::dvec3(0, 1, 0)));
        } else if (all.size() > 2) {
            axis = *m.coplanarAxis();
        }
        std::vector<double> lune(sites.size());
        planarSphereCellAreas(all.size() == 1 ? glm::dvec3(0, 0, 1) : axis, sites, lune);
        for (size_t i = 0; i < all.size(); ++i) areas[all[i]->info()] = lune[i];
        return;
    }
    // The cell of site p is the spherical polygon of the circumcentres of its incident faces, in the
    // circulator's (counter-clockwise) order; sum the triangles (p, c_k, c_k+1).
    std::vector<glm::dvec3> corners;
    for (const VertexHandle& v : all) {
        const glm::dvec3 p = toGlm(v->point());
        corners.clear();
        Delaunay::Face_circulator f = m.dt.incident_faces(v), done = f;
        do {
            const glm::dvec3 n = outwardNormal(toGlm(f->vertex(0)->point()), toGlm(f->vertex(1)->point()),
                                               toGlm(f->vertex(2)->point()));
            corners.push_back(glm::normalize(n));
        } while (++f != done);
        double area = 0.0;
        for (size_t k = 0; k < corners.size(); ++k)
            area += signedSphericalTriangleArea(p, corners[k], corners[(k + 1) % corners.size()]);
        areas[v->info()] = std::abs(area);
    }
}

void SphereTriangulation::triangles(std::vector<std::array<SlotId, 3>>& out) const {
    out.clear();
    const Delaunay& dt = m_impl->dt;
    if (dt.dimension() < 2) return;
    for (auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f)
        out.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
}

void SphereTriangulation::edges(std::vector<Edge>& out) const {
    out.clear();
    const Delaunay& dt = m_impl->dt;
    if (dt.number_of_vertices() == 2) {
        const VertexHandle a = dt.vertices_begin(), b = std::next(dt.vertices_begin());
        out.push_back(Edge{a->info(), b->info(), glm::distance(toGlm(a->point()), toGlm(b->point()))});
        return;
    }
    if (dt.dimension() < 1) return;
    for (auto e = dt.all_edges_begin(); e != dt.all_edges_end(); ++e) {
        const VertexHandle a = e->first->vertex(Delaunay::ccw(e->second));
        const VertexHandle b = e->first->vertex(Delaunay::cw(e->second));
        out.push_back(Edge{a->info(), b->info(), glm::distance(toGlm(a->point()), toGlm(b->point()))});
    }
}

}  // namespace bounce

#include "techniques/radiosity/PatchModel.h"

#include "core/Check.h"
#include "scene/AreaTexture.h"
#include "techniques/radiosity/radiosity_shared.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

namespace bounce::radiosity {

namespace {

// A chart takes the connected triangles whose normals lie within this angle of its first triangle's
// (bounce's choice, radiosity.md "Charts, not the mesh's faces"). 0 would leave curved surfaces at
// about the old per-face quads (at least 2x2 texels per face: 145,496 elements for Sponza at any
// elementSize); 20 degrees keeps the cosine error of a receiver's normal against its chart's
// (area-weighted mean) normal at most 1 - cos 20 = 6 %, while a 64-segment column takes four faces
// per chart and a 16-segment one (22.5 degrees per face) a face each. Planar surfaces merge whole.
constexpr float kChartConeDegrees = 20.0f;
// Triangles below this area (m^2) are degenerate: no quad, drawn as "no patch".
constexpr float kDegenerateArea = 1e-12f;
// A triangle whose projection onto its chart's plane is below this area, in texel cells, gives its whole
// area to the cell of its centroid (it is edge-on to the plane: impossible within the cone, kept as a guard).
constexpr double kEdgeOnCells = 1e-12;
// Widest atlas row, texels (GL_MAX_TEXTURE_SIZE is at least 16384 in GL 4.5).
constexpr int kMaxAtlasSide = 16384;

using Key = std::tuple<float, float, float>;
Key keyOf(glm::vec3 p) { return {p.x, p.y, p.z}; }

glm::vec3 albedoAt(const Scene& scene, const Material& m, glm::vec2 uv) {
    glm::vec3 a = m.baseColor;
    if (m.baseColorTexture < 0) return a;
    const Image& img = scene.textures[static_cast<size_t>(m.baseColorTexture)].image;
    if (img.empty()) return a;
    // Nearest texel with repeat, v running down the stored image (docs/scene.md, as scene.glsl).
    const float u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
    const int x = std::clamp(static_cast<int>(u * img.width()), 0, img.width() - 1);
    const int y = std::clamp(static_cast<int>(v * img.height()), 0, img.height() - 1);
    return a * img.at(x, y);
}

int texelsAlong(float length, float pitch) { return std::max(2, static_cast<int>(std::ceil(length / pitch - 1e-4f)) + 1); }

// A convex polygon in texel-grid coordinates (a triangle clipped by a cell: at most 7 vertices).
struct Polygon {
    std::array<glm::dvec2, 8> v;
    int n = 0;
};

// Sutherland-Hodgman against the half-plane sign * (p[axis] - bound) >= 0.
Polygon clipAxis(const Polygon& in, int axis, double bound, double sign) {
    Polygon out;
    for (int k = 0; k < in.n; ++k) {
        const glm::dvec2 a = in.v[static_cast<size_t>(k)], b = in.v[static_cast<size_t>((k + 1) % in.n)];
        const double da = sign * (a[axis] - bound), db = sign * (b[axis] - bound);
        if (da >= 0.0) out.v[static_cast<size_t>(out.n++)] = a;
        if ((da >= 0.0) != (db >= 0.0)) out.v[static_cast<size_t>(out.n++)] = a + (b - a) * (da / (da - db));
    }
    return out;
}

// Area and centroid of a convex polygon (shoelace).
double polygonArea(const Polygon& p, glm::dvec2& centroid) {
    double a = 0.0;
    glm::dvec2 c(0.0);
    for (int k = 0; k < p.n; ++k) {
        const glm::dvec2 u = p.v[static_cast<size_t>(k)], w = p.v[static_cast<size_t>((k + 1) % p.n)];
        const double cr = u.x * w.y - w.x * u.y;
        a += cr;
        c += (u + w) * cr;
    }
    if (std::abs(a) < 1e-300) return 0.0;
    centroid = c / (3.0 * a);
    return 0.5 * std::abs(a);
}

// Convex hull (Andrew's monotone chain), counter-clockwise.
std::vector<glm::dvec2> convexHull(std::vector<glm::dvec2> pts) {
    std::sort(pts.begin(), pts.end(), [](glm::dvec2 a, glm::dvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    if (pts.size() < 3) return pts;
    std::vector<glm::dvec2> h(2 * pts.size());
    size_t k = 0;
    const auto turn = [](glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
    for (size_t i = 0; i < pts.size(); ++i) {
        while (k >= 2 && turn(h[k - 2], h[k - 1], pts[i]) <= 0.0) --k;
        h[k++] = pts[i];
    }
    for (size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && turn(h[k - 2], h[k - 1], pts[i]) <= 0.0) --k;
        h[k++] = pts[i];
    }
    h.resize(k - 1);
    return h;
}

}  // namespace

float autoElementSize(const Scene& scene) {
    double area = 0.0;
    // World-space area (the objects' transforms at t = 0: a scene scaled 10x has 100x the area).
    for (const Object& obj : scene.objects) {
        const Mesh& mesh = scene.meshes[obj.mesh];
        const glm::mat4 m = obj.worldFromObject(0.0f);
        const auto world = [&](size_t i) { return glm::vec3(m * glm::vec4(mesh.positions[mesh.indices[i]], 1.0f)); };
        for (size_t t = 0; t < mesh.triangleCount(); ++t) {
            const glm::vec3 a = world(3 * t), b = world(3 * t + 1), c = world(3 * t + 2);
            area += 0.5 * glm::length(glm::cross(b - a, c - a));
        }
    }
    for (const Light& l : scene.lights)
        if (l.type == LightType::Area) area += l.area();
    // No surface at all: any pitch (build() refuses the scene).
    return area > 0.0 ? static_cast<float>(std::sqrt(area / kAutoTargetElements)) : 1.0f;
}

glm::mat4 lightFrame(const Light& light) {
    return glm::mat4(glm::vec4(light.edgeU, 0.0f), glm::vec4(light.edgeV, 0.0f), glm::vec4(light.areaNormal(), 0.0f),
                     glm::vec4(light.position, 1.0f));
}

glm::vec3 punctualDirectRadiance(const Light& light, glm::vec3 p, glm::vec3 n, glm::vec3 albedo) {
    glm::vec3 l{0.0f}, irradiance{0.0f};
    switch (light.type) {
        case LightType::Area: return glm::vec3(0.0f);
        case LightType::Directional:
            l = -glm::normalize(light.direction);
            irradiance = light.irradiance;
            break;
        case LightType::Point:
        case LightType::Spot: {
            const glm::vec3 d = light.position - p;
            const float r2 = std::max(glm::dot(d, d), 1e-12f);  // as lighting.glsl
            l = d / std::sqrt(r2);
            irradiance = light.intensity / r2;
            if (light.type == LightType::Spot) {
                const float cosAlpha = glm::dot(-l, glm::normalize(light.direction));
                if (cosAlpha < std::cos(light.cutoffAngle) || cosAlpha <= 0.0f) return glm::vec3(0.0f);
                irradiance *= std::pow(cosAlpha, light.falloffExponent);
            }
            break;
        }
    }
    return albedo * irradiance * std::max(glm::dot(n, l), 0.0f) * glm::one_over_pi<float>();
}

void PatchModel::addChart(Quad q, const std::vector<ChartTriangle>& tris, const std::function<glm::vec3(glm::vec2)>& albedo,
                          const glm::dmat3& areaMap) {
    const auto quad = static_cast<uint32_t>(m_quads.size());
    q.firstElement = static_cast<uint32_t>(m_elements.size());
    q.surface = quad;
    const size_t cells = static_cast<size_t>(q.nu) * static_cast<size_t>(q.nv);
    // Texel-grid coordinates: (s (nu-1), t (nv-1)); texel (i, j)'s cell is [i-1/2, i+1/2] x [j-1/2, j+1/2]
    // clipped to the rectangle [0, nu-1] x [0, nv-1].
    const glm::vec3 o = q.p[0], eu = q.p[1] - q.p[0], ev = q.p[3] - q.p[0];
    const float uu = glm::dot(eu, eu), uv = glm::dot(eu, ev), vv = glm::dot(ev, ev);
    const float det = uu * vv - uv * uv;
    const auto paramOf = [&](glm::vec3 p) {  // least-squares (s, t) of p's projection onto the rectangle's plane
        const glm::vec3 d = p - o;
        const float du = glm::dot(d, eu), dv = glm::dot(d, ev);
        return glm::clamp(glm::vec2(vv * du - uv * dv, uu * dv - uv * du) / det, glm::vec2(0.0f), glm::vec2(1.0f));
    };
    const glm::dvec2 gridScale(q.nu - 1, q.nv - 1);
    struct Acc {
        double area = 0.0;
        glm::dvec3 position{0.0}, albedo{0.0};
        double largest = 0.0;                    // the largest piece's area, m^2
        glm::dvec3 onLargest{0.0}, normal{0.0};  // a point of its triangle and the triangle's unit normal
    };
    std::vector<Acc> acc(cells);
    double total = 0.0;
    for (const ChartTriangle& tri : tris) {
        glm::vec2 st[3];
        glm::dvec2 g[3];
        for (int k = 0; k < 3; ++k) {
            st[k] = paramOf(tri.p[k]);
            g[k] = glm::dvec2(st[k]) * gridScale;
        }
        if (tri.ref != SIZE_MAX) {
            m_triangles[tri.ref].quad = quad;
            for (int k = 0; k < 3; ++k) m_triangles[tri.ref].st[k] = st[k];
        }
        const glm::dvec3 cross3 = glm::cross(glm::dvec3(tri.p[1] - tri.p[0]), glm::dvec3(tri.p[2] - tri.p[0]));
        const double objectArea = 0.5 * glm::length(cross3);
        const glm::dvec3 normal3 = cross3 / std::max(2.0 * objectArea, 1e-300);  // object space (sample positions)
        // World m^2: a linear map L takes the area vector a to cof(L) a (areaMap).
        const double area3 = 0.5 * glm::length(areaMap * cross3);
        total += area3;
        const glm::dvec2 e1 = g[1] - g[0], e2 = g[2] - g[0];
        const double cross2 = e1.x * e2.y - e1.y * e2.x, area2 = 0.5 * std::abs(cross2);
        // Lifts a grid point inside the triangle to the surface (barycentric): position and uv.
        const auto lift = [&](glm::dvec2 c, glm::dvec3& p, glm::dvec2& uvOut) {
            const glm::dvec2 d = c - g[0];
            const double b1 = (d.x * e2.y - d.y * e2.x) / cross2, b2 = (e1.x * d.y - e1.y * d.x) / cross2, b0 = 1.0 - b1 - b2;
            p = b0 * glm::dvec3(tri.p[0]) + b1 * glm::dvec3(tri.p[1]) + b2 * glm::dvec3(tri.p[2]);
            uvOut = b0 * glm::dvec2(tri.uv[0]) + b1 * glm::dvec2(tri.uv[1]) + b2 * glm::dvec2(tri.uv[2]);
        };
        const auto cellOf = [&](double x, int n) { return std::clamp(static_cast<int>(std::floor(x + 0.5)), 0, n - 1); };
        if (area2 < kEdgeOnCells) {
            const glm::dvec2 c = (g[0] + g[1] + g[2]) / 3.0;
            Acc& a = acc[static_cast<size_t>(cellOf(c.y, q.nv)) * static_cast<size_t>(q.nu) + static_cast<size_t>(cellOf(c.x, q.nu))];
            const glm::dvec3 p = (glm::dvec3(tri.p[0]) + glm::dvec3(tri.p[1]) + glm::dvec3(tri.p[2])) / 3.0;
            a.area += area3;
            a.position += area3 * p;
            a.albedo += area3 * glm::dvec3(albedo((tri.uv[0] + tri.uv[1] + tri.uv[2]) / 3.0f));
            continue;
        }
        const double scale = area3 / area2;  // surface m^2 per grid unit^2 (curved charts: > the rectangle's)
        const glm::dvec2 lo = glm::min(g[0], glm::min(g[1], g[2])), hi = glm::max(g[0], glm::max(g[1], g[2]));
        for (int j = cellOf(lo.y, q.nv); j <= cellOf(hi.y, q.nv); ++j)
            for (int i = cellOf(lo.x, q.nu); i <= cellOf(hi.x, q.nu); ++i) {
                Polygon poly;
                poly.n = 3;
                for (int k = 0; k < 3; ++k) poly.v[static_cast<size_t>(k)] = g[k];
                poly = clipAxis(poly, 0, std::max(0.0, i - 0.5), 1.0);
                poly = clipAxis(poly, 0, std::min(q.nu - 1.0, i + 0.5), -1.0);
                poly = clipAxis(poly, 1, std::max(0.0, j - 0.5), 1.0);
                poly = clipAxis(poly, 1, std::min(q.nv - 1.0, j + 0.5), -1.0);
                if (poly.n < 3) continue;
                glm::dvec2 c(0.0);
                const double a2 = polygonArea(poly, c);
                if (!(a2 > 0.0)) continue;
                glm::dvec3 p;
                glm::dvec2 uvc;
                lift(c, p, uvc);
                const double w = a2 * scale;
                Acc& a = acc[static_cast<size_t>(j) * static_cast<size_t>(q.nu) + static_cast<size_t>(i)];
                a.area += w;
                a.position += w * p;
                a.albedo += w * glm::dvec3(albedo(glm::vec2(uvc)));
                if (w > a.largest) {
                    a.largest = w;
                    a.onLargest = p;
                    a.normal = normal3;
                }
            }
    }
    q.area = static_cast<float>(total);
    // Elements: covered cells at their centroid; ghosts take the nearest covered cell's sample (breadth-
    // first over the grid), so the bilinear display next to the covered part reads light from the surface.
    std::vector<int> source(cells, -1);
    std::vector<size_t> queue;
    queue.reserve(cells);
    double sum = 0.0;
    for (size_t k = 0; k < cells; ++k)
        if (acc[k].area > 0.0) {
            source[k] = static_cast<int>(k);
            queue.push_back(k);
            sum += acc[k].area;
        }
    for (size_t head = 0; head < queue.size(); ++head) {
        const size_t k = queue[head];
        const int i = static_cast<int>(k % static_cast<size_t>(q.nu)), j = static_cast<int>(k / static_cast<size_t>(q.nu));
        const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
        for (int d = 0; d < 4; ++d) {
            const int a = i + di[d], b = j + dj[d];
            if (a < 0 || b < 0 || a >= q.nu || b >= q.nv) continue;
            const size_t n = static_cast<size_t>(b) * static_cast<size_t>(q.nu) + static_cast<size_t>(a);
            if (source[n] >= 0) continue;
            source[n] = source[k];
            queue.push_back(n);
        }
    }
    m_elements.reserve(m_elements.size() + cells);
    for (int j = 0; j < q.nv; ++j)
        for (int i = 0; i < q.nu; ++i) {
            const size_t k = static_cast<size_t>(j) * static_cast<size_t>(q.nu) + static_cast<size_t>(i);
            Element el;
            el.quad = quad;
            el.i = i;
            el.j = j;
            el.emission = q.emission;
            const Acc& from = acc[static_cast<size_t>(std::max(source[k], 0))];
            if (from.area > 0.0) {
                // The centroid of the covered part, onto the plane of its largest piece: on a planar chart
                // the centroid itself; on a curved one the centroid of pieces on several faces lies inside
                // the surface by up to the cone's sag (1.5 cm on a 0.25 m column), more than the hemicube
                // offset, so a gather hemicube there would see the surface's back.
                const glm::dvec3 c = from.position / from.area;
                el.position = glm::vec3(c - glm::dot(c - from.onLargest, from.normal) * from.normal);
                el.albedo = glm::vec3(from.albedo / from.area);
            } else {
                el.position = pointAt(q, texelParam(q, i, j));
                el.albedo = albedo(glm::vec2(0.0f));
            }
            // The clipped sums miss the exact area by rounding only: rescale to the triangles' area.
            el.area = sum > 0.0 ? static_cast<float>(acc[k].area * (total / sum)) : 0.0f;
            if (el.area > 0.0f) ++m_activeElements;
            m_elements.push_back(el);
        }
    m_quads.push_back(q);
}

glm::vec3 PatchModel::pointAt(const Quad& q, glm::vec2 st) { return q.p[0] + st.x * (q.p[1] - q.p[0]) + st.y * (q.p[3] - q.p[0]); }

glm::mat4 PatchModel::bodyTransform(const Scene& scene, uint32_t body, float t) const {
    if (body < m_objectCount) return scene.objects[body].worldFromObject(t);
    const Light& l = scene.lights[body - m_objectCount];
    return lightFrame(l.at(t)) * glm::inverse(lightFrame(l.at(0.0f)));
}

bool PatchModel::bodyAnimated(const Scene& scene, uint32_t body) const {
    if (body < m_objectCount) return scene.objects[body].isDynamic();
    return scene.lights[body - m_objectCount].isDynamic();
}

Expected<PatchModel> PatchModel::build(const Scene& scene, const PatchOptions& opt) {
    for (const Light& l : scene.lights) {
        // Point, spot and directional lights are not patches: their direct light is shot into the
        // elements as the first unshot radiosity (RadiositySystem::computeLights, radiosity.md
        // "Point, spot and directional lights").
        if (l.type != LightType::Area) continue;
        // An emitter quad has one uniform radiance on its front: a texture (possibly animated) or a second
        // emitting side would be lost without a word (area-screen's bars: 3.6x the path tracer's light).
        if (l.texture.kind != AreaTexture::Kind::None || l.twoSided)
            return makeError("area light '{}' is {}: hemicube radiosity's emitters are uniform, one-sided patches "
                             "(van de Hoef 2013 sec. 4.1)",
                             l.name, l.twoSided ? "two-sided" : "textured");
    }
    if (!(opt.elementSize >= 0.0f) || !(opt.dynamicElementSize >= 0.0f))
        return makeError("elementSize and dynamicElementSize must be positive (or 0: derived from the scene's area)");

    PatchModel pm;
    pm.m_objectCount = static_cast<uint32_t>(scene.objects.size());
    pm.m_bodyCount = pm.m_objectCount + static_cast<uint32_t>(scene.lights.size());
    const float autoSize = (opt.elementSize > 0.0f && opt.dynamicElementSize > 0.0f) ? 0.0f : autoElementSize(scene);
    pm.m_elementSize = opt.elementSize > 0.0f ? opt.elementSize : autoSize;
    pm.m_dynamicElementSize = opt.dynamicElementSize > 0.0f ? opt.dynamicElementSize : autoSize;
    const float coneCosine = std::cos(glm::radians(kChartConeDegrees));

    // 1. Charts per object (each object is its own body: objects move rigidly).
    for (uint32_t oi = 0; oi < scene.objects.size(); ++oi) {
        const Object& obj = scene.objects[oi];
        const Mesh& mesh = scene.meshes[obj.mesh];
        const Material& mat = scene.materials[obj.material];
        const size_t triCount = mesh.triangleCount();
        pm.m_objectTriangleBase.push_back(static_cast<uint32_t>(pm.m_triangles.size()));
        const size_t triBase = pm.m_triangles.size();
        pm.m_triangles.resize(triBase + triCount);

        const auto vtx = [&](size_t t, int k) { return mesh.positions[mesh.indices[3 * t + static_cast<size_t>(k)]]; };
        const auto uvOf = [&](size_t t, int k) {
            return mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[mesh.indices[3 * t + static_cast<size_t>(k)]];
        };
        std::vector<glm::vec3> normal(triCount);
        std::vector<float> area(triCount);
        std::vector<char> degenerate(triCount, 0);
        // Vertices welded by position, edges as (smaller, larger) welded index pairs.
        std::map<Key, uint32_t> weld;
        std::vector<std::pair<uint64_t, uint32_t>> edges;
        edges.reserve(3 * triCount);
        for (size_t t = 0; t < triCount; ++t) {
            const glm::vec3 a = vtx(t, 0), b = vtx(t, 1), c = vtx(t, 2);
            glm::vec3 n = glm::cross(b - a, c - a);
            area[t] = 0.5f * glm::length(n);
            if (area[t] < kDegenerateArea) {
                degenerate[t] = 1;
                continue;
            }
            n = glm::normalize(n);
            // The front side agrees with the mesh's shading normals where it has them.
            if (!mesh.normals.empty()) {
                const glm::vec3 sn = mesh.normals[mesh.indices[3 * t]] + mesh.normals[mesh.indices[3 * t + 1]] +
                                     mesh.normals[mesh.indices[3 * t + 2]];
                if (glm::dot(sn, n) < 0.0f) n = -n;
            }
            normal[t] = n;
            uint32_t id[3];
            for (int k = 0; k < 3; ++k) id[k] = weld.try_emplace(keyOf(vtx(t, k)), static_cast<uint32_t>(weld.size())).first->second;
            for (int k = 0; k < 3; ++k) {
                const uint64_t u = std::min(id[k], id[(k + 1) % 3]), w = std::max(id[k], id[(k + 1) % 3]);
                edges.push_back({u << 32 | w, static_cast<uint32_t>(t)});
            }
        }
        std::sort(edges.begin(), edges.end());
        // Neighbours across shared edges (compressed rows).
        std::vector<uint32_t> degree(triCount + 1, 0), neighbours;
        const auto forPairs = [&](const auto& visit) {
            for (size_t r = 0; r < edges.size();) {
                size_t e = r;
                while (e < edges.size() && edges[e].first == edges[r].first) ++e;
                for (size_t x = r; x < e; ++x)
                    for (size_t y = r; y < e; ++y)
                        if (x != y) visit(edges[x].second, edges[y].second);
                r = e;
            }
        };
        forPairs([&](uint32_t t, uint32_t) { ++degree[t + 1]; });
        for (size_t t = 0; t < triCount; ++t) degree[t + 1] += degree[t];
        neighbours.resize(degree[triCount]);
        std::vector<uint32_t> fill(degree.begin(), degree.end() - 1);
        forPairs([&](uint32_t t, uint32_t o) { neighbours[fill[t]++] = o; });

        const glm::vec3 emission =
            mat.emissionTexture >= 0
                ? mat.emission * imageMean(scene.textures[static_cast<size_t>(mat.emissionTexture)].image)
                : mat.emission;
        const float pitch = obj.isDynamic() ? pm.m_dynamicElementSize : pm.m_elementSize;
        // The object's transform (rigid animation times a fixed transform that may scale): element areas
        // and the pitch are world metres, positions stay in object space (the body transform moves them).
        const glm::dmat3 linear(glm::mat3(obj.worldFromObject(0.0f)));
        const glm::dmat3 areaMap = glm::determinant(linear) * glm::transpose(glm::inverse(linear));
        std::vector<char> assigned(triCount, 0);
        std::vector<uint32_t> members;
        for (size_t seed = 0; seed < triCount; ++seed) {
            if (degenerate[seed] || assigned[seed]) continue;
            // Flood fill within the normal cone of the seed.
            members.assign(1, static_cast<uint32_t>(seed));
            assigned[seed] = 1;
            for (size_t head = 0; head < members.size(); ++head) {
                const uint32_t t = members[head];
                for (uint32_t k = degree[t]; k < degree[t + 1]; ++k) {
                    const uint32_t o = neighbours[k];
                    if (assigned[o] || degenerate[o] || glm::dot(normal[o], normal[seed]) < coneCosine) continue;
                    assigned[o] = 1;
                    members.push_back(o);
                }
            }
            // The chart's plane: area-weighted mean normal through the area-weighted centroid.
            glm::dvec3 nsum(0.0), csum(0.0);
            double asum = 0.0;
            for (uint32_t t : members) {
                nsum += double(area[t]) * glm::dvec3(normal[t]);
                csum += double(area[t]) * glm::dvec3(vtx(t, 0) + vtx(t, 1) + vtx(t, 2)) / 3.0;
                asum += area[t];
            }
            const glm::vec3 n = glm::length(nsum) > 0.0 ? glm::vec3(glm::normalize(nsum)) : normal[seed];
            const glm::vec3 centre(csum / asum);
            const glm::vec3 helper = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
            const glm::vec3 T = glm::normalize(glm::cross(helper, n)), B = glm::cross(n, T);
            // The tightest oriented bounding rectangle of the projection: one side lies on a hull edge.
            std::vector<glm::dvec2> pts;
            pts.reserve(3 * members.size());
            for (uint32_t t : members)
                for (int k = 0; k < 3; ++k) {
                    const glm::vec3 d = vtx(t, k) - centre;
                    pts.push_back({glm::dot(d, T), glm::dot(d, B)});
                }
            const std::vector<glm::dvec2> hull = convexHull(pts);
            glm::dvec2 bestU(1.0, 0.0), bestLo(0.0), bestHi(0.0);
            double bestArea = std::numeric_limits<double>::infinity();
            for (size_t k = 0; k < std::max<size_t>(hull.size(), 1); ++k) {
                glm::dvec2 u(1.0, 0.0);
                if (hull.size() >= 2) {
                    const glm::dvec2 d = hull[(k + 1) % hull.size()] - hull[k];
                    if (glm::length(d) <= 0.0) continue;
                    u = glm::normalize(d);
                }
                const glm::dvec2 v(-u.y, u.x);
                glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
                for (const glm::dvec2& p : hull.size() >= 3 ? hull : pts) {
                    const glm::dvec2 x(glm::dot(p, u), glm::dot(p, v));
                    lo = glm::min(lo, x);
                    hi = glm::max(hi, x);
                }
                const double a = (hi.x - lo.x) * (hi.y - lo.y);
                if (a < bestArea) {
                    bestArea = a;
                    bestU = u;
                    bestLo = lo;
                    bestHi = hi;
                }
            }
            const glm::dvec2 bestV(-bestU.y, bestU.x);
            const glm::vec3 U = glm::vec3(bestU.x) * T + glm::vec3(bestU.y) * B, V = glm::vec3(bestV.x) * T + glm::vec3(bestV.y) * B;
            const float width = std::max(static_cast<float>(bestHi.x - bestLo.x), 1e-6f);
            const float height = std::max(static_cast<float>(bestHi.y - bestLo.y), 1e-6f);
            Quad q;
            q.body = oi;
            q.normal = n;  // cross(U, V) = cross(T, B) = n: p0 p1 p3 counter-clockwise about it
            // An emission texture enters as its mean (patches are coarser than texels; a named deviation
            // in radiosity.md).
            q.emission = emission;
            q.flags = glm::any(glm::greaterThan(mat.emission, glm::vec3(0.0f))) ? RAD_QUAD_EMITTER : 0u;
            q.p[0] = centre + static_cast<float>(bestLo.x) * U + static_cast<float>(bestLo.y) * V;
            q.p[1] = q.p[0] + width * U;
            q.p[3] = q.p[0] + height * V;
            q.p[2] = q.p[1] + height * V;
            q.nu = texelsAlong(width * static_cast<float>(glm::length(linear * glm::dvec3(U))), pitch);
            q.nv = texelsAlong(height * static_cast<float>(glm::length(linear * glm::dvec3(V))), pitch);
            if (pm.m_elements.size() + static_cast<size_t>(q.nu) * static_cast<size_t>(q.nv) > opt.maxElements)
                return makeError("more than {} radiosity elements (object '{}'): raise elementSize (now {} m) or "
                                 "dynamicElementSize (now {} m)",
                                 opt.maxElements, obj.name, pm.m_elementSize, pm.m_dynamicElementSize);
            std::vector<ChartTriangle> tris(members.size());
            for (size_t k = 0; k < members.size(); ++k) {
                for (int c = 0; c < 3; ++c) {
                    tris[k].p[c] = vtx(members[k], c);
                    tris[k].uv[c] = uvOf(members[k], c);
                }
                tris[k].ref = triBase + members[k];
            }
            // Element albedo: the material over the covered part of the cell (uv by the triangles).
            pm.addChart(q, tris, [&](glm::vec2 uv) { return albedoAt(scene, mat, uv); }, areaMap);
        }
    }

    // 2. Area lights: one emitter quad each, in the light's rest frame (world space at t = 0).
    for (size_t li = 0; li < scene.lights.size(); ++li) {
        if (scene.lights[li].type != LightType::Area) continue;
        const Light l = scene.lights[li].at(0.0f);
        if (!(l.area() > 0.0f)) return makeError("area light '{}' has zero area", l.name);
        Quad q;
        q.body = pm.m_objectCount + static_cast<uint32_t>(li);
        const glm::vec3 c = l.position, hu = 0.5f * l.edgeU, hv = 0.5f * l.edgeV;
        q.p[0] = c - hu - hv;
        q.p[1] = c + hu - hv;
        q.p[2] = c + hu + hv;
        q.p[3] = c - hu + hv;
        q.normal = l.areaNormal();  // cross(edgeU, edgeV): p0 p1 p3 counter-clockwise about it
        q.emission = l.radiance;
        q.flags = RAD_QUAD_EMITTER | RAD_QUAD_LIGHT;
        q.nu = texelsAlong(glm::length(l.edgeU), pm.m_elementSize);
        q.nv = texelsAlong(glm::length(l.edgeV), pm.m_elementSize);
        // The rectangle's two triangles as light.vert draws them (p0 p1 p3, p1 p2 p3).
        std::vector<ChartTriangle> tris(2);
        tris[0].p[0] = q.p[0], tris[0].p[1] = q.p[1], tris[0].p[2] = q.p[3];
        tris[1].p[0] = q.p[1], tris[1].p[1] = q.p[2], tris[1].p[2] = q.p[3];
        pm.addChart(q, tris, [](glm::vec2) { return glm::vec3(0.0f); });  // emitters reflect nothing
        ++pm.m_lightQuads;
    }
    if (pm.m_quads.empty()) return makeError("the scene has no surface of non-zero area");
    bool emitter = false;
    for (const Quad& q : pm.m_quads) emitter = emitter || (q.flags & RAD_QUAD_EMITTER);
    for (const Light& l : scene.lights) emitter = emitter || l.type != LightType::Area;
    if (!emitter) return makeError("the scene has no light and no emissive material: radiosity has nothing to shoot");
    if (pm.m_elements.size() > opt.maxElements)
        return makeError("more than {} radiosity elements: raise elementSize (now {} m)", opt.maxElements, pm.m_elementSize);

    // 5. Atlas: shelf packing, tallest regions first.
    std::vector<size_t> order(pm.m_quads.size());
    size_t texels = 0;
    int widest = 0;
    for (size_t k = 0; k < order.size(); ++k) {
        order[k] = k;
        texels += static_cast<size_t>(pm.m_quads[k].nu * pm.m_quads[k].nv);
        widest = std::max(widest, pm.m_quads[k].nu);
    }
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return pm.m_quads[a].nv > pm.m_quads[b].nv; });
    const int width = std::max(widest, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(texels) * 1.25))));
    if (width > kMaxAtlasSide) return makeError("a radiosity quad needs {} texels per row (limit {}): raise elementSize", width, kMaxAtlasSide);
    int x = 0, y = 0, rowHeight = 0;
    for (size_t k : order) {
        Quad& q = pm.m_quads[k];
        if (x + q.nu > width) {
            x = 0;
            y += rowHeight;
            rowHeight = 0;
        }
        q.atlasX = x;
        q.atlasY = y;
        x += q.nu;
        rowHeight = std::max(rowHeight, q.nv);
    }
    pm.m_atlasSize = {width, y + rowHeight};
    if (pm.m_atlasSize.y > kMaxAtlasSide) return makeError("the radiosity atlas needs {} rows (limit {}): raise elementSize", pm.m_atlasSize.y, kMaxAtlasSide);
    return pm;
}

}  // namespace bounce::radiosity

#include "techniques/radiosity/PatchModel.h"

#include "core/Check.h"
#include "scene/AreaTexture.h"
#include "techniques/radiosity/radiosity_shared.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

namespace bounce::radiosity {

namespace {

// Two triangles are coplanar when their unit normals agree within this (cosine 1 - 1e-4 is about
// 0.8 degrees: the published Cornell walls, one of them 3.2 mm out of plane, pair; tessellated
// curved surfaces of 32 or fewer segments per turn do not).
constexpr float kCoplanarCosine = 1.0f - 1e-4f;
// Triangles below this area (m^2) are degenerate: no quad, drawn as "no patch".
constexpr float kDegenerateArea = 1e-12f;
// Sub-samples per side when integrating an element's cell area over the surface map.
constexpr int kAreaSamples = 8;
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

// Jacobian |dP/ds x dP/dt| of the piecewise-linear map at (s,t); 0 outside a triangle's domain.
float jacobian(const Quad& q, glm::vec2 st) {
    if (q.map == QuadMap::Triangle) {
        if (st.x + st.y > 1.0f) return 0.0f;
        return glm::length(glm::cross(q.p[1] - q.p[0], q.p[3] - q.p[0]));
    }
    if (st.x + st.y <= 1.0f) return glm::length(glm::cross(q.p[1] - q.p[0], q.p[3] - q.p[0]));
    return glm::length(glm::cross(q.p[3] - q.p[2], q.p[1] - q.p[2]));
}

int texelsAlong(float length, float pitch) { return std::max(2, static_cast<int>(std::ceil(length / pitch - 1e-4f)) + 1); }

}  // namespace

glm::mat4 lightFrame(const Light& light) {
    return glm::mat4(glm::vec4(light.edgeU, 0.0f), glm::vec4(light.edgeV, 0.0f), glm::vec4(light.areaNormal(), 0.0f),
                     glm::vec4(light.position, 1.0f));
}

void PatchModel::addElements(Quad& q, const std::function<glm::vec3(glm::vec2)>& albedo) {
    q.firstElement = static_cast<uint32_t>(m_elements.size());
    const auto quad = static_cast<uint32_t>(&q - m_quads.data());
    for (int j = 0; j < q.nv; ++j)
        for (int i = 0; i < q.nu; ++i) {
            Element el;
            el.quad = quad;
            el.i = i;
            el.j = j;
            el.albedo = albedo(texelParam(q, i, j));
            el.emission = q.emission;
            m_elements.push_back(el);
        }
}

glm::vec3 PatchModel::pointAt(const Quad& q, glm::vec2 st) {
    const float s = st.x, t = st.y;
    if (q.map == QuadMap::Triangle || s + t <= 1.0f) return q.p[0] + s * (q.p[1] - q.p[0]) + t * (q.p[3] - q.p[0]);
    return q.p[2] + (1.0f - s) * (q.p[3] - q.p[2]) + (1.0f - t) * (q.p[1] - q.p[2]);
}

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
    static const char* kTypeNames[] = {"point", "spot", "directional", "area"};
    for (const Light& l : scene.lights) {
        if (l.type != LightType::Area)
            return makeError("light '{}' is a {} light: hemicube radiosity shades only area lights and emissive surfaces "
                             "(van de Hoef 2013 sec. 4.1: light sources are emitting patches)",
                             l.name, kTypeNames[static_cast<int>(l.type)]);
        // An emitter quad has one uniform radiance on its front: a texture (possibly animated) or a second
        // emitting side would be lost without a word (area-screen's bars: 3.6x the path tracer's light).
        if (l.texture.kind != AreaTexture::Kind::None || l.twoSided)
            return makeError("area light '{}' is {}: hemicube radiosity's emitters are uniform, one-sided patches "
                             "(van de Hoef 2013 sec. 4.1)",
                             l.name, l.twoSided ? "two-sided" : "textured");
    }
    if (!(opt.elementSize > 0.0f) || !(opt.dynamicElementSize > 0.0f))
        return makeError("elementSize and dynamicElementSize must be positive");

    PatchModel pm;
    pm.m_objectCount = static_cast<uint32_t>(scene.objects.size());
    pm.m_bodyCount = pm.m_objectCount + static_cast<uint32_t>(scene.lights.size());

    // 1. Quads from triangle pairs, per object (each object is its own body: objects move rigidly).
    for (uint32_t oi = 0; oi < scene.objects.size(); ++oi) {
        const Object& obj = scene.objects[oi];
        const Mesh& mesh = scene.meshes[obj.mesh];
        const Material& mat = scene.materials[obj.material];
        const size_t triCount = mesh.triangleCount();
        pm.m_objectTriangleBase.push_back(static_cast<uint32_t>(pm.m_triangles.size()));
        const size_t triBase = pm.m_triangles.size();
        pm.m_triangles.resize(triBase + triCount);

        std::vector<glm::vec3> normal(triCount);
        std::vector<float> area(triCount);
        std::vector<char> used(triCount, 0);
        std::map<std::pair<Key, Key>, std::vector<uint32_t>> edges;  // welded by position
        const auto vtx = [&](size_t t, int k) { return mesh.positions[mesh.indices[3 * t + k]]; };
        for (size_t t = 0; t < triCount; ++t) {
            const glm::vec3 a = vtx(t, 0), b = vtx(t, 1), c = vtx(t, 2);
            glm::vec3 n = glm::cross(b - a, c - a);
            area[t] = 0.5f * glm::length(n);
            if (area[t] < kDegenerateArea) {
                used[t] = 1;
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
            for (int k = 0; k < 3; ++k) {
                Key u = keyOf(vtx(t, k)), w = keyOf(vtx(t, (k + 1) % 3));
                if (w < u) std::swap(u, w);
                edges[{u, w}].push_back(static_cast<uint32_t>(t));
            }
        }
        const glm::vec3 emission =
            mat.emissionTexture >= 0
                ? mat.emission * imageMean(scene.textures[static_cast<size_t>(mat.emissionTexture)].image)
                : mat.emission;
        const auto uvOf = [&](size_t t, int k) {
            return mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[mesh.indices[3 * t + k]];
        };
        for (size_t t = 0; t < triCount; ++t) {
            if (used[t]) continue;
            used[t] = 1;
            Quad q;
            q.body = oi;
            q.normal = normal[t];
            // An emission texture enters as its mean (patches are coarser than texels; a named deviation
            // in radiosity.md).
            q.emission = emission;
            q.flags = glm::any(glm::greaterThan(mat.emission, glm::vec3(0.0f))) ? RAD_QUAD_EMITTER : 0u;
            glm::vec2 uv[4];
            uint32_t corners[2][3] = {};
            // Partner across the longest edge first (a rectangle's diagonal).
            int order[3] = {0, 1, 2};
            std::sort(order, order + 3, [&](int x, int y) {
                return glm::length(vtx(t, (x + 1) % 3) - vtx(t, x)) > glm::length(vtx(t, (y + 1) % 3) - vtx(t, y));
            });
            long partner = -1;
            int partnerEdge = -1;
            for (int e : order) {
                Key u = keyOf(vtx(t, e)), w = keyOf(vtx(t, (e + 1) % 3));
                if (w < u) std::swap(u, w);
                for (uint32_t o : edges[{u, w}]) {
                    if (used[o] || glm::dot(normal[o], normal[t]) < kCoplanarCosine) continue;
                    // Convex union: the partner's far vertex and t's far vertex lie on opposite sides of
                    // the shared edge (always true for consistent normals) and the other diagonal
                    // separates the shared edge's ends.
                    const glm::vec3 eu = vtx(t, e), ew = vtx(t, (e + 1) % 3), v1 = vtx(t, (e + 2) % 3);
                    glm::vec3 v2{0.0f};
                    for (int k = 0; k < 3; ++k) {
                        const glm::vec3 p = vtx(o, k);
                        if (p != eu && p != ew) v2 = p;
                    }
                    const glm::vec3 n = normal[t];
                    const float su = glm::dot(glm::cross(v2 - v1, eu - v1), n), sw = glm::dot(glm::cross(v2 - v1, ew - v1), n);
                    if (su * sw >= 0.0f) continue;
                    partner = o;
                    partnerEdge = e;
                    break;
                }
                if (partner >= 0) break;
            }
            if (partner >= 0) {
                const size_t o = static_cast<size_t>(partner);
                used[o] = 1;
                const int e = partnerEdge;
                glm::vec3 pu = vtx(t, e), pw = vtx(t, (e + 1) % 3);
                glm::vec2 uu = uvOf(t, e), uw = uvOf(t, (e + 1) % 3);
                const glm::vec3 v1 = vtx(t, (e + 2) % 3);
                int farK = 0;
                for (int k = 0; k < 3; ++k)
                    if (vtx(o, k) != pu && vtx(o, k) != pw) farK = k;
                const glm::vec3 v2 = vtx(o, farK);
                // Boundary order v1, u, v2, w counter-clockwise about the normal (shared edge p1-p3).
                if (glm::dot(glm::cross(pu - v1, pw - v1), q.normal) < 0.0f) {
                    std::swap(pu, pw);
                    std::swap(uu, uw);
                }
                q.p[0] = v1;
                q.p[1] = pu;
                q.p[2] = v2;
                q.p[3] = pw;
                uv[0] = uvOf(t, (e + 2) % 3);
                uv[1] = uu;
                uv[2] = uvOf(o, farK);
                uv[3] = uw;
                q.map = QuadMap::Quad;
                q.area = area[t] + area[o];
                const auto code = [&](glm::vec3 p) -> uint32_t {
                    if (p == q.p[0]) return 0u;
                    if (p == q.p[1]) return 1u;
                    if (p == q.p[2]) return 3u;
                    return 2u;
                };
                for (int k = 0; k < 3; ++k) corners[0][k] = code(vtx(t, k));
                for (int k = 0; k < 3; ++k) corners[1][k] = code(vtx(o, k));
                const uint32_t qi = static_cast<uint32_t>(pm.m_quads.size());
                pm.m_triangles[triBase + t] = {qi, corners[0][0] | corners[0][1] << 2 | corners[0][2] << 4};
                pm.m_triangles[triBase + o] = {qi, corners[1][0] | corners[1][1] << 2 | corners[1][2] << 4};
            } else {
                // Lone triangle a b c at (0,0) (1,0) (0,1), counter-clockwise about the normal.
                int ia = 0, ib = 1, ic = 2;
                if (glm::dot(glm::cross(vtx(t, 1) - vtx(t, 0), vtx(t, 2) - vtx(t, 0)), q.normal) < 0.0f) std::swap(ib, ic);
                q.map = QuadMap::Triangle;
                q.p[0] = vtx(t, ia);
                q.p[1] = vtx(t, ib);
                q.p[3] = vtx(t, ic);
                q.p[2] = q.p[1] + q.p[3] - q.p[0];
                uv[0] = uvOf(t, ia);
                uv[1] = uvOf(t, ib);
                uv[3] = uvOf(t, ic);
                uv[2] = uv[1] + uv[3] - uv[0];
                q.area = area[t];
                uint32_t c[3];
                c[ia] = 0u;
                c[ib] = 1u;
                c[ic] = 2u;
                pm.m_triangles[triBase + t] = {static_cast<uint32_t>(pm.m_quads.size()), c[0] | c[1] << 2 | c[2] << 4};
            }
            const float pitch = obj.isDynamic() ? opt.dynamicElementSize : opt.elementSize;
            q.nu = texelsAlong(std::max(glm::length(q.p[1] - q.p[0]), glm::length(q.p[2] - q.p[3])), pitch);
            q.nv = texelsAlong(std::max(glm::length(q.p[3] - q.p[0]), glm::length(q.p[2] - q.p[1])), pitch);
            pm.m_quads.push_back(q);
            // Element albedo and emission: the material at the element (uv by the same surface map).
            Quad& added = pm.m_quads.back();
            pm.m_elements.reserve(pm.m_elements.size() + static_cast<size_t>(q.nu * q.nv));
            const auto uvAt = [&](glm::vec2 st) {
                if (q.map == QuadMap::Triangle || st.x + st.y <= 1.0f) return uv[0] + st.x * (uv[1] - uv[0]) + st.y * (uv[3] - uv[0]);
                return uv[2] + (1.0f - st.x) * (uv[3] - uv[2]) + (1.0f - st.y) * (uv[1] - uv[2]);
            };
            pm.addElements(added, [&](glm::vec2 st) { return albedoAt(scene, mat, uvAt(st)); });
            if (pm.m_elements.size() > opt.maxElements)
                return makeError("more than {} radiosity elements (object '{}'): raise elementSize (now {} m) or "
                                 "dynamicElementSize (now {} m)",
                                 opt.maxElements, obj.name, opt.elementSize, opt.dynamicElementSize);
        }
    }

    // 2. Area lights: one emitter quad each, in the light's rest frame (world space at t = 0).
    for (size_t li = 0; li < scene.lights.size(); ++li) {
        const Light l = scene.lights[li].at(0.0f);
        if (!(l.area() > 0.0f)) return makeError("area light '{}' has zero area", l.name);
        Quad q;
        q.body = pm.m_objectCount + static_cast<uint32_t>(li);
        q.map = QuadMap::Quad;
        const glm::vec3 c = l.position, hu = 0.5f * l.edgeU, hv = 0.5f * l.edgeV;
        q.p[0] = c - hu - hv;
        q.p[1] = c + hu - hv;
        q.p[2] = c + hu + hv;
        q.p[3] = c - hu + hv;
        q.normal = l.areaNormal();  // cross(edgeU, edgeV): p0 p1 p3 counter-clockwise about it
        q.area = l.area();
        q.emission = l.radiance;
        q.flags = RAD_QUAD_EMITTER | RAD_QUAD_LIGHT;
        q.nu = texelsAlong(glm::length(l.edgeU), opt.elementSize);
        q.nv = texelsAlong(glm::length(l.edgeV), opt.elementSize);
        pm.m_quads.push_back(q);
        pm.addElements(pm.m_quads.back(), [](glm::vec2) { return glm::vec3(0.0f); });  // emitters reflect nothing
        ++pm.m_lightQuads;
    }
    if (pm.m_quads.empty()) return makeError("the scene has no surface of non-zero area");
    bool emitter = false;
    for (const Quad& q : pm.m_quads) emitter = emitter || (q.flags & RAD_QUAD_EMITTER);
    if (!emitter) return makeError("the scene has no area light and no emissive material: radiosity has nothing to shoot");
    if (pm.m_elements.size() > opt.maxElements)
        return makeError("more than {} radiosity elements: raise elementSize (now {} m)", opt.maxElements, opt.elementSize);

    // 3. Which quad edges continue into a coplanar neighbour (the same two corners, any body): there
    //    the border samples coincide with the neighbour's and stay on the edge; elsewhere (a junction
    //    with a wall, a free edge, a T-junction) they are inset. Edges: 0 p0-p1 (j = 0), 1 p1-p2
    //    (i = nu-1), 2 p2-p3 (j = nv-1), 3 p3-p0 (i = 0).
    std::map<std::pair<Key, Key>, std::vector<std::pair<uint32_t, int>>> quadEdges;
    const auto edgeKey = [](glm::vec3 a, glm::vec3 b) {
        Key u = keyOf(a), w = keyOf(b);
        if (w < u) std::swap(u, w);
        return std::make_pair(u, w);
    };
    std::vector<glm::mat4> restFrame(pm.m_bodyCount);
    for (uint32_t b = 0; b < pm.m_bodyCount; ++b) restFrame[b] = pm.bodyTransform(scene, b, 0.0f);
    const auto world = [&](const Quad& q, int k) { return glm::vec3(restFrame[q.body] * glm::vec4(q.p[k], 1.0f)); };
    for (uint32_t qi = 0; qi < pm.m_quads.size(); ++qi) {
        const Quad& q = pm.m_quads[qi];
        if (q.map == QuadMap::Triangle) continue;
        for (int e = 0; e < 4; ++e) quadEdges[edgeKey(world(q, e), world(q, (e + 1) % 4))].push_back({qi, e});
    }
    std::vector<std::array<bool, 4>> shared(pm.m_quads.size(), {false, false, false, false});
    for (const auto& [key, list] : quadEdges)
        for (const auto& [qa, ea] : list)
            for (const auto& [qb, eb] : list) {
                if (qa == qb) continue;
                const glm::vec3 na = glm::mat3(restFrame[pm.m_quads[qa].body]) * pm.m_quads[qa].normal;
                const glm::vec3 nb = glm::mat3(restFrame[pm.m_quads[qb].body]) * pm.m_quads[qb].normal;
                if (glm::dot(glm::normalize(na), glm::normalize(nb)) >= kCoplanarCosine) shared[qa][ea] = true;
            }
    // Surfaces: quads of one body joined by shared coplanar edges (union-find). The thesis's "quad"
    // is such a surface ("a coplanar surface made of patches"); visibility compares surfaces, so a
    // sample on the edge between two cells of one wall is not hidden by its own wall.
    std::vector<uint32_t> parent(pm.m_quads.size());
    for (uint32_t k = 0; k < parent.size(); ++k) parent[k] = k;
    const auto find = [&](uint32_t k) {
        while (parent[k] != k) k = parent[k] = parent[parent[k]];
        return k;
    };
    for (const auto& [key, list] : quadEdges)
        for (const auto& [qa, ea] : list)
            for (const auto& [qb, eb] : list)
                if (qa != qb && shared[qa][ea] && pm.m_quads[qa].body == pm.m_quads[qb].body) parent[find(qa)] = find(qb);
    for (uint32_t k = 0; k < parent.size(); ++k) pm.m_quads[k].surface = find(k);

    // 4. Element positions and areas (texel cells clipped to the quad, integrated over the map).
    for (uint32_t qi = 0; qi < pm.m_quads.size(); ++qi) {
        Quad& q = pm.m_quads[qi];
        const float ds = 1.0f / static_cast<float>(q.nu - 1), dt = 1.0f / static_cast<float>(q.nv - 1);
        double sum = 0.0;
        for (int j = 0; j < q.nv; ++j)
            for (int i = 0; i < q.nu; ++i) {
                Element& el = pm.m_elements[q.firstElement + static_cast<size_t>(j * q.nu + i)];
                glm::vec2 st = texelParam(q, i, j);
                const float s0 = std::max(0.0f, st.x - 0.5f * ds), s1 = std::min(1.0f, st.x + 0.5f * ds);
                const float t0 = std::max(0.0f, st.y - 0.5f * dt), t1 = std::min(1.0f, st.y + 0.5f * dt);
                double a = 0.0;
                for (int b = 0; b < kAreaSamples; ++b)
                    for (int c = 0; c < kAreaSamples; ++c) {
                        const glm::vec2 p(s0 + (s1 - s0) * (c + 0.5f) / kAreaSamples, t0 + (t1 - t0) * (b + 0.5f) / kAreaSamples);
                        a += jacobian(q, p);
                    }
                a *= double(s1 - s0) * double(t1 - t0) / (kAreaSamples * kAreaSamples);
                el.area = static_cast<float>(a);
                sum += a;
                // Border samples on an edge without a coplanar neighbour move inward, perpendicular to it.
                const auto& sh = shared[qi];
                if (i == 0 && !sh[3]) st.x += opt.borderInset * ds;
                if (i == q.nu - 1 && !sh[1]) st.x -= opt.borderInset * ds;
                if (j == 0 && !sh[0]) st.y += opt.borderInset * dt;
                if (j == q.nv - 1 && !sh[2]) st.y -= opt.borderInset * dt;
                if (q.map == QuadMap::Triangle && st.x + st.y > 1.0f) st -= glm::vec2(0.5f * (st.x + st.y - 1.0f));
                el.position = pointAt(q, st);
            }
        // The sampled integral misses the exact diagonal cut by a little: rescale to the exact area.
        if (sum > 0.0)
            for (int k = 0; k < q.nu * q.nv; ++k) pm.m_elements[q.firstElement + static_cast<size_t>(k)].area *= static_cast<float>(q.area / sum);
    }

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

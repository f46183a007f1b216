#include "techniques/photon_splat/BundleVolume.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace bounce::photonsplat {

namespace {

// Clusters per BVH leaf: a leaf's clusters are tested one by one.
constexpr uint32_t kLeafClusters = 4;
// Margin of the far plane past the scene's box, as a fraction of the box's diagonal: surfaces lie on
// the box's faces, and rounding must not clip them.
constexpr float kFarMarginFraction = 1e-3f;
// Smallest |w.n| used to solve for a plane's depth along w (a ray parallel to the plane).
constexpr float kMinDirectionCosine = 1e-4f;
// Squared length below which a cross-product separating axis is degenerate (w along a world axis).
constexpr float kMinAxisLength2 = 1e-8f;
// Relative margin of the emitter-plane cull: a box must lie behind the plane by this fraction of the
// plane's and the box's coordinate magnitudes (float rounding of the shader's clip distance, ~1e-7).
constexpr float kEmitterCullMargin = 1e-5f;

// 30-bit Morton code of a point in [0, 1]^3 (10 bits per axis).
uint32_t morton(glm::vec3 p) {
    auto spread = [](uint32_t v) {
        v = (v * 0x00010001u) & 0xFF0000FFu;
        v = (v * 0x00000101u) & 0x0F00F00Fu;
        v = (v * 0x00000011u) & 0xC30C30C3u;
        v = (v * 0x00000005u) & 0x49249249u;
        return v;
    };
    const glm::uvec3 q(glm::clamp(p, glm::vec3(0.0f), glm::vec3(1.0f)) * 1023.0f);
    return spread(q.x) | (spread(q.y) << 1) | (spread(q.z) << 2);
}

}  // namespace

bool BundleVolume::contains(glm::vec3 x) const {
    const glm::vec3 d = x - origin;
    const float m = glm::dot(x, nearNormal);
    return std::abs(glm::dot(d, right)) <= half && std::abs(glm::dot(d, up)) <= half && m <= nearOffset && m >= farOffset() &&
           glm::dot(x, emitterNormal) >= emitterOffset;
}

BundleVolume bundleVolume(const Photon& photon, const Bundle& bundle, const VolumeSettings& settings) {
    const float half = settings.half, stepBack = settings.stepBack, emitterOffset = settings.emitterOffset;
    float length = std::max(settings.length, 0.0f);
    BundleVolume v;
    v.origin = photon.position;
    v.right = bundle.right;
    v.up = bundle.up;
    v.direction = bundle.direction;
    v.half = half;
    const glm::vec3 w = bundle.direction;
    // The near plane. b >= d (the default) or an escaped photon: through P, perpendicular to w: each
    // ray starts beside the photon. b < d (the document's small step back): through C = P + (d - b) w,
    // parallel to the hit surface (its tilt from the perpendicular capped at kMaxNearTilt), so that
    // a tilted receiver around the hit is not cut by it. The far plane is D past the near plane.
    const bool fromPhoton = bundle.escaped || !(stepBack < bundle.hitDistance);
    v.length = length;
    const glm::vec3 c = bundle.origin;  // C, placeBundles' step back (P when b >= d)
    glm::vec3 m = fromPhoton ? -w : bundle.hitNormal;
    const float cosHit = -glm::dot(w, m);
    const float cosMin = std::cos(kMaxNearTilt);
    if (!(cosHit >= cosMin)) {
        const glm::vec3 tangent = m + glm::dot(w, m) * -w;  // n_Q's part across w
        const float tl = glm::length(tangent);
        m = tl > 0.0f ? -cosMin * w + std::sin(kMaxNearTilt) * (tangent / tl) : -w;
    }
    v.nearNormal = m;
    v.nearOffset = glm::dot(c, m);
    // The emitter plane: nothing behind the photon's own surface lights or occludes.
    const float cosEmit = glm::dot(w, photon.normal);
    if (cosEmit > kMinDirectionCosine) {
        v.emitterNormal = photon.normal;
        v.emitterOffset = glm::dot(photon.position, photon.normal) + emitterOffset;
    } else {
        v.emitterNormal = glm::vec3(0.0f);  // no usable plane: every point passes
        v.emitterOffset = -std::numeric_limits<float>::infinity();
    }
    const float wm = glm::dot(w, m);  // < 0
    if (glm::all(glm::lessThanEqual(settings.lo, settings.hi))) {
        // Far enough that the far plane lies past the box everywhere over the square: D at least the
        // box's farthest depth along w less the near plane's nearest depth (plus a margin of
        // kFarMarginFraction of the box's diagonal for rounding).
        float boxFar = -std::numeric_limits<float>::infinity(), nearMin = std::numeric_limits<float>::infinity();
        for (int k = 0; k < 8; ++k) {
            const glm::vec3 corner((k & 1) ? settings.hi.x : settings.lo.x, (k & 2) ? settings.hi.y : settings.lo.y, (k & 4) ? settings.hi.z : settings.lo.z);
            boxFar = std::max(boxFar, glm::dot(corner - photon.position, w));
        }
        for (int i = 0; i < 4; ++i) {
            const glm::vec3 s = ((i & 1) ? half : -half) * v.right + ((i & 2) ? half : -half) * v.up;
            nearMin = std::min(nearMin, (v.nearOffset - glm::dot(photon.position + s, m)) / wm);
        }
        length = std::max(length, boxFar - nearMin + kFarMarginFraction * glm::length(settings.hi - settings.lo));
        v.length = length;
    }
    // Corners: the near plane's depth at each corner of the square, and D beyond.
    float nearMin = std::numeric_limits<float>::infinity(), farMax = -nearMin, emitMin = nearMin;
    for (int i = 0; i < 4; ++i) {
        const glm::vec3 s = ((i & 1) ? half : -half) * v.right + ((i & 2) ? half : -half) * v.up;
        const float z = (v.nearOffset - glm::dot(photon.position + s, m)) / wm;
        v.corners[static_cast<size_t>(i)] = photon.position + s + z * w;
        v.corners[static_cast<size_t>(i) + 4] = photon.position + s + (z + length) * w;
        nearMin = std::min(nearMin, z);
        farMax = std::max(farMax, z + length);
        if (cosEmit > kMinDirectionCosine)
            emitMin = std::min(emitMin, (v.emitterOffset - glm::dot(photon.position + s, photon.normal)) / cosEmit);
    }
    v.zNear = cosEmit > kMinDirectionCosine ? std::max(nearMin, emitMin) : nearMin;
    v.zFar = std::max(farMax, v.zNear + 1e-6f);
    v.cornersLo = v.cornersHi = v.corners[0];
    for (const glm::vec3& corner : v.corners) {
        v.cornersLo = glm::min(v.cornersLo, corner);
        v.cornersHi = glm::max(v.cornersHi, corner);
    }
    auto addAxis = [&](glm::vec3 axis) {
        float a = std::numeric_limits<float>::infinity(), b = -a;
        for (const glm::vec3& corner : v.corners) {
            const float t = glm::dot(corner, axis);
            a = std::min(a, t);
            b = std::max(b, t);
        }
        v.axes[static_cast<size_t>(v.axisCount)] = axis;
        v.spans[static_cast<size_t>(v.axisCount++)] = glm::vec2(a, b);
    };
    addAxis(v.right);
    addAxis(v.up);
    addAxis(v.nearNormal);
    // The edges along w against a box's edges: the axes w x e_k. A long bundle crossing the scene
    // diagonally passes its face normals' and the world axes' tests beside many boxes it misses.
    for (int k = 0; k < 3; ++k) {
        glm::vec3 e(0.0f);
        e[k] = 1.0f;
        const glm::vec3 axis = glm::cross(v.direction, e);
        if (glm::dot(axis, axis) > kMinAxisLength2) addAxis(axis);
    }
    return v;
}

bool mayOverlap(const BundleVolume& v, glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 centre = 0.5f * (lo + hi), extent = 0.5f * (hi - lo);
    // The volume is the parallelepiped of its corners (cut by the emitter plane: a subset). The world
    // axes: every corner beyond the box on one side.
    if (glm::any(glm::greaterThan(v.cornersLo, hi)) || glm::any(glm::lessThan(v.cornersHi, lo))) return false;
    // The volume's own axes and w x e_k (bundleVolume's spans) against the box's projection.
    for (int i = 0; i < v.axisCount; ++i) {
        const glm::vec3 axis = v.axes[static_cast<size_t>(i)];
        const float mid = glm::dot(centre, axis);
        const float r = glm::dot(extent, glm::abs(axis));
        if (v.spans[static_cast<size_t>(i)].y < mid - r || v.spans[static_cast<size_t>(i)].x > mid + r) return false;
    }
    // The emitter plane: a box wholly behind the photon's surface (depth.vert clips all of it), with a
    // margin of kEmitterCullMargin of the plane's offset for rounding between here and the shader.
    if (std::isfinite(v.emitterOffset)) {
        const float most = glm::dot(centre, v.emitterNormal) + glm::dot(extent, glm::abs(v.emitterNormal));
        if (most < v.emitterOffset - kEmitterCullMargin * (std::abs(v.emitterOffset) + glm::dot(glm::abs(centre) + extent, glm::abs(v.emitterNormal))))
            return false;
    }
    return true;
}

ClusterSet ClusterSet::build(const Scene& scene, uint32_t maxTriangles) {
    ClusterSet set;
    maxTriangles = std::max(maxTriangles, 1u);
    std::vector<uint32_t> baseVertex;
    uint32_t vertices = 0;
    for (const Mesh& mesh : scene.meshes) {
        baseVertex.push_back(vertices);
        vertices += static_cast<uint32_t>(mesh.positions.size());
    }
    for (uint32_t oi = 0; oi < scene.objects.size(); ++oi) {
        const Object& o = scene.objects[oi];
        const Mesh& mesh = scene.meshes[o.mesh];
        const size_t n = mesh.triangleCount();
        if (n == 0) continue;
        glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
        for (const glm::vec3& p : mesh.positions) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-9f));
        std::vector<std::pair<uint32_t, uint32_t>> keyed(n);
        for (size_t t = 0; t < n; ++t) {
            const glm::vec3 centroid = (mesh.positions[mesh.indices[3 * t]] + mesh.positions[mesh.indices[3 * t + 1]] +
                                        mesh.positions[mesh.indices[3 * t + 2]]) / 3.0f;
            keyed[t] = {morton((centroid - lo) / extent), static_cast<uint32_t>(t)};
        }
        std::sort(keyed.begin(), keyed.end());
        for (size_t first = 0; first < n; first += maxTriangles) {
            Cluster c;
            c.object = oi;
            c.firstIndex = static_cast<uint32_t>(set.m_indices.size());
            c.lo = glm::vec3(std::numeric_limits<float>::infinity());
            c.hi = -c.lo;
            for (size_t k = first; k < std::min<size_t>(n, first + maxTriangles); ++k)
                for (int j = 0; j < 3; ++j) {
                    const uint32_t i = mesh.indices[3 * static_cast<size_t>(keyed[k].second) + static_cast<size_t>(j)];
                    set.m_indices.push_back(baseVertex[o.mesh] + i);
                    c.lo = glm::min(c.lo, mesh.positions[i]);
                    c.hi = glm::max(c.hi, mesh.positions[i]);
                }
            c.indexCount = static_cast<uint32_t>(set.m_indices.size()) - c.firstIndex;
            set.m_clusters.push_back(c);
        }
        set.m_dynamic = set.m_dynamic || o.isDynamic();
    }
    return set;
}

void ClusterSet::update(const Scene& scene, float time) {
    if (m_time >= 0.0f && (!m_dynamic || time == m_time)) return;
    m_time = time;
    const size_t n = m_clusters.size();
    m_worldLo.resize(n);
    m_worldHi.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const Cluster& c = m_clusters[i];
        const glm::mat4 world = scene.objects[c.object].worldFromObject(time);
        glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
        for (int k = 0; k < 8; ++k) {
            const glm::vec3 p(world * glm::vec4((k & 1) ? c.hi.x : c.lo.x, (k & 2) ? c.hi.y : c.lo.y, (k & 4) ? c.hi.z : c.lo.z, 1.0f));
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        m_worldLo[i] = lo;
        m_worldHi[i] = hi;
    }
    // Median-split BVH over the cluster centres.
    m_order.resize(n);
    std::iota(m_order.begin(), m_order.end(), 0u);
    m_nodes.clear();
    if (n == 0) return;
    m_nodes.reserve(2 * n);
    struct Task {
        uint32_t node, first, count;
    };
    std::vector<Task> stack{{0, 0, static_cast<uint32_t>(n)}};
    m_nodes.emplace_back();
    while (!stack.empty()) {
        const Task t = stack.back();
        stack.pop_back();
        Node& node = m_nodes[t.node];
        node.lo = glm::vec3(std::numeric_limits<float>::infinity());
        node.hi = -node.lo;
        for (uint32_t k = t.first; k < t.first + t.count; ++k) {
            node.lo = glm::min(node.lo, m_worldLo[m_order[k]]);
            node.hi = glm::max(node.hi, m_worldHi[m_order[k]]);
        }
        if (t.count <= kLeafClusters) {
            node.first = t.first;
            node.count = t.count;
            continue;
        }
        const glm::vec3 size = node.hi - node.lo;
        const int axis = size.x > size.y ? (size.x > size.z ? 0 : 2) : (size.y > size.z ? 1 : 2);
        const uint32_t half = t.count / 2;
        std::nth_element(m_order.begin() + t.first, m_order.begin() + t.first + half, m_order.begin() + t.first + t.count,
                         [&](uint32_t a, uint32_t b) { return m_worldLo[a][axis] + m_worldHi[a][axis] < m_worldLo[b][axis] + m_worldHi[b][axis]; });
        const auto left = static_cast<uint32_t>(m_nodes.size());
        node.first = left;
        node.count = 0;
        m_nodes.emplace_back();
        m_nodes.emplace_back();
        stack.push_back({left, t.first, half});
        stack.push_back({left + 1, t.first + half, t.count - half});
    }
}

void ClusterSet::cull(const BundleVolume& volume, std::vector<uint32_t>& out) const {
    if (m_nodes.empty()) return;
    uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = m_nodes[stack[--top]];
        if (!mayOverlap(volume, node.lo, node.hi)) continue;
        if (node.count > 0) {
            for (uint32_t k = node.first; k < node.first + node.count; ++k)
                if (mayOverlap(volume, m_worldLo[m_order[k]], m_worldHi[m_order[k]])) out.push_back(m_order[k]);
            continue;
        }
        stack[top++] = node.first;
        stack[top++] = node.first + 1;
    }
}

size_t ClusterSet::bytes() const {
    return m_indices.capacity() * sizeof(uint32_t) + m_clusters.capacity() * sizeof(Cluster) +
           (m_worldLo.capacity() + m_worldHi.capacity()) * sizeof(glm::vec3) + m_order.capacity() * sizeof(uint32_t) +
           m_nodes.capacity() * sizeof(Node);
}

}  // namespace bounce::photonsplat

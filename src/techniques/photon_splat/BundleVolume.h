#pragma once
// The space one orthographic bundle lights (seed 004, §3.3/§4.3, Fig. 4) and the culling of the
// scene's geometry to it. GL-free: PhotonSplatTechnique uploads the volumes and draws the clusters
// each one keeps; the unit tests check both against direct geometry.
//
// A bundle's parallel rays run along w through the square |s.right|, |s.up| <= h around the photon's
// ray. Each ray starts on the bundle's near plane and ends D further along w; it deposits its share
// of the photon's power on the first surface between (the depth map's first hit). The document's
// near plane is perpendicular to w at C = P + (d - b) w. bounce's default b = d puts it at the photon
// (every receiver along the bundle counts, every occluder before it too); with a smaller b it is
// tilted about C to lie parallel to the hit surface (normal n_Q), so that a tilted receiver around the
// hit is not cut by it. No ray starts behind the photon's own surface (its tangent plane, offset by
// `emitterOffset`), and by default D reaches past the scene's box.
#include "techniques/photon_splat/PhotonInjection.h"

#include <array>
#include <cstdint>
#include <vector>

namespace bounce::photonsplat {

// Largest tilt of the near plane from the perpendicular to w, radians: a grazing hit would stretch the
// box along w without bound (tan 75 degrees = 3.7 half-widths per half-width). Receivers tilted further
// lose the part of the square whose depth exceeds the cap; their cosine is below cos 75 = 0.26.
inline constexpr float kMaxNearTilt = 1.3089969f;  // 75 degrees

struct BundleVolume {
    glm::vec3 origin{0.0f};     // P, the photon: local depth z is measured from it along w
    glm::vec3 right{0.0f}, up{0.0f}, direction{0.0f};
    float half = 0.0f;          // h, metres
    glm::vec3 nearNormal{0.0f};  // m: unit, m.w < 0; x is past the near plane when dot(x, m) <= nearOffset
    float nearOffset = 0.0f;
    float length = 0.0f;         // D: the far plane is the near plane moved D along w
    glm::vec3 emitterNormal{0.0f};  // n_P; x is in front of the photon's surface when dot(x, n_P) >= emitterOffset
    float emitterOffset = 0.0f;
    float zNear = 0.0f, zFar = 0.0f;  // depth range along w from P that holds the volume (the map's projection)
    std::array<glm::vec3, 8> corners{};  // corner i: right sign bit 0, up sign bit 1, far bit 2
    // What mayOverlap tests, fixed per volume (bundleVolume fills it once instead of every box's test
    // projecting the eight corners again): the corners' bounds, and their span [x, y] along each
    // separating axis (right, up, the near normal, then w x e_k for the world axes e_k not along w).
    glm::vec3 cornersLo{0.0f}, cornersHi{0.0f};
    std::array<glm::vec3, 6> axes{};
    std::array<glm::vec2, 6> spans{};
    int axisCount = 0;

    // The far plane: x is before it when dot(x, m) >= farOffset().
    float farOffset() const { return nearOffset + length * glm::dot(direction, nearNormal); }
    // Whether x lies in the volume (the square, between the planes, in front of the photon's surface).
    bool contains(glm::vec3 x) const;
};

// The volume of `bundle` (photon `photon`): half width h, step back b (from the hit, along w), length D,
// the emitter plane offset eps. The hit normal is bundle.hitNormal.
struct VolumeSettings {
    float half = 0.0f;           // h, metres
    float stepBack = 0.0f;       // b, metres
    float length = 0.0f;         // D, metres
    float emitterOffset = 0.0f;  // metres
    // When lo <= hi: D grows so that the far plane lies past where every ray of the square leaves this box.
    glm::vec3 lo{0.0f}, hi{-1.0f};
};
BundleVolume bundleVolume(const Photon& photon, const Bundle& bundle, const VolumeSettings& settings);

// The scene's triangles split into clusters of at most `maxTriangles`, each of one object and compact
// in space (triangles ordered by the Morton code of their centroid), with a BVH over the clusters'
// world bounds: a bundle draws only the clusters whose box meets its volume.
class ClusterSet {
public:
    struct Cluster {
        uint32_t object = 0;
        uint32_t firstIndex = 0, indexCount = 0;  // into indices()
        glm::vec3 lo{0.0f}, hi{0.0f};             // object space
    };
    static ClusterSet build(const Scene& scene, uint32_t maxTriangles);

    // Vertex indices of every cluster's triangles, in the vertex order of render::SceneGpu (all meshes'
    // vertices concatenated in Scene::meshes order).
    const std::vector<uint32_t>& indices() const { return m_indices; }
    const std::vector<Cluster>& clusters() const { return m_clusters; }
    // World bounds of the clusters at time t and the BVH over them (static scenes: once).
    void update(const Scene& scene, float time);
    // Appends the clusters whose world box may meet the volume (mayOverlap: conservative).
    void cull(const BundleVolume& volume, std::vector<uint32_t>& out) const;
    size_t bytes() const;  // CPU memory the clusters, their bounds and the BVH take

private:
    struct Node {
        glm::vec3 lo{0.0f}, hi{0.0f};
        uint32_t first = 0, count = 0;  // leaf: m_order[first, first + count); inner: count = 0, children first, first + 1
    };
    std::vector<uint32_t> m_indices;
    std::vector<Cluster> m_clusters;
    std::vector<glm::vec3> m_worldLo, m_worldHi;
    std::vector<uint32_t> m_order;
    std::vector<Node> m_nodes;
    bool m_dynamic = false;
    float m_time = -1.0f;
};

// Separating-axis test of a volume against an axis-aligned box (the world axes, the volume's face
// normals right, up, m, its edges along w against the box's: w x e_k), and the box against the
// emitter plane: false only when they are disjoint.
bool mayOverlap(const BundleVolume& volume, glm::vec3 lo, glm::vec3 hi);

}  // namespace bounce::photonsplat

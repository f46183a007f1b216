#include "reference/Bsdf.h"

#include "core/Image.h"

#include <algorithm>

namespace bounce {

namespace {

// GGX alpha below this makes D overflow float precision near the peak; the reference has no delta
// BRDFs, so near-mirrors are rendered as very sharp glossy lobes (1e-3 = roughness 0.03).
constexpr float kMinAlpha = 1e-3f;

// Lobe selection never drops below this probability, so a lobe whose weight estimate is tiny
// (dark diffuse under strong Fresnel, or the reverse) still gets samples and MIS keeps low variance.
constexpr float kMinLobeProbability = 0.1f;

float ggxD(float alpha2, float cosH) {
    const float d = cosH * cosH * (alpha2 - 1.0f) + 1.0f;
    return alpha2 / (kPi * d * d);
}

float smithG1(float alpha2, float cosV) {
    return 2.0f * cosV / (cosV + std::sqrt(alpha2 + (1.0f - alpha2) * cosV * cosV));
}

glm::vec3 schlick(glm::vec3 f0, float cosD) {
    const float m = 1.0f - std::clamp(cosD, 0.0f, 1.0f);
    const float m2 = m * m;
    return f0 + (1.0f - f0) * (m2 * m2 * m);
}

// Visible-normal sampling of GGX (Heitz, "Sampling the GGX Distribution of Visible Normals",
// JCGT 2018): returns a microfacet normal h distributed as G1(wo) max(0, wo.h) D(h) / wo.z.
glm::vec3 sampleGgxVisibleNormal(glm::vec3 wo, float alpha, float u1, float u2) {
    const glm::vec3 vh = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
    const float lenSq = vh.x * vh.x + vh.y * vh.y;
    const glm::vec3 t1 = lenSq > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lenSq) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 t2 = glm::cross(vh, t1);
    const float r = std::sqrt(u1);
    const float phi = 2.0f * kPi * u2;
    const float p1 = r * std::cos(phi);
    float p2 = r * std::sin(phi);
    const float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
    const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(0.0f, nh.z)));
}

}  // namespace

Bsdf::Bsdf(const Material& material, glm::vec3 textured, bool diffuseOnly) noexcept
    : m_diffuseAlbedo(textured * (1.0f - material.metallic)) {
    if (diffuseOnly) return;
    m_f0 = glm::mix(glm::vec3(material.specularF0), textured, material.metallic);
    m_hasSpecular = maxComponent(m_f0) > 0.0f;
    m_alpha = std::max(material.roughness * material.roughness, kMinAlpha);
}

float Bsdf::specularProbability(glm::vec3 wo) const noexcept {
    const float spec = luminance(schlick(m_f0, wo.z));
    const float diff = luminance(m_diffuseAlbedo);
    if (diff <= 0.0f) return 1.0f;
    return std::clamp(spec / (spec + diff), kMinLobeProbability, 1.0f - kMinLobeProbability);
}

glm::vec3 Bsdf::evalSpecular(glm::vec3 wo, glm::vec3 wi) const noexcept {
    const glm::vec3 h = glm::normalize(wo + wi);
    const float alpha2 = m_alpha * m_alpha;
    const float d = ggxD(alpha2, h.z);
    const float g = smithG1(alpha2, wo.z) * smithG1(alpha2, wi.z);
    return schlick(m_f0, glm::dot(wo, h)) * (d * g / (4.0f * wo.z * wi.z));
}

float Bsdf::pdfSpecular(glm::vec3 wo, glm::vec3 wi) const noexcept {
    const glm::vec3 h = glm::normalize(wo + wi);
    const float alpha2 = m_alpha * m_alpha;
    const float woh = glm::dot(wo, h);
    if (woh <= 0.0f) return 0.0f;
    // pdf(h) = G1(wo) (wo.h) D(h) / wo.z, and the reflection Jacobian is 1 / (4 wo.h).
    return smithG1(alpha2, wo.z) * ggxD(alpha2, h.z) / (4.0f * wo.z);
}

glm::vec3 Bsdf::eval(glm::vec3 wo, glm::vec3 wi) const noexcept {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 f = m_diffuseAlbedo * kInvPi;
    if (m_hasSpecular) f += evalSpecular(wo, wi);
    return f;
}

float Bsdf::pdf(glm::vec3 wo, glm::vec3 wi) const noexcept {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
    if (!m_hasSpecular) return wi.z * kInvPi;
    const float ps = specularProbability(wo);
    return (1.0f - ps) * wi.z * kInvPi + ps * pdfSpecular(wo, wi);
}

bool Bsdf::sample(glm::vec3 wo, float uLobe, float u1, float u2, Sample& out) const noexcept {
    if (wo.z <= 0.0f) return false;
    if (!m_hasSpecular) {
        out.wi = cosineHemisphere(u1, u2);
        if (out.wi.z <= 0.0f) return false;
        out.pdf = out.wi.z * kInvPi;
        out.weight = m_diffuseAlbedo;  // (albedo / pi) cos / (cos / pi)
        return true;
    }
    const float ps = specularProbability(wo);
    if (uLobe < ps) {
        const glm::vec3 h = sampleGgxVisibleNormal(wo, m_alpha, u1, u2);
        out.wi = glm::reflect(-wo, h);
    } else {
        out.wi = cosineHemisphere(u1, u2);
    }
    if (out.wi.z <= 0.0f) return false;
    out.pdf = (1.0f - ps) * out.wi.z * kInvPi + ps * pdfSpecular(wo, out.wi);
    if (!(out.pdf > 0.0f)) return false;
    out.weight = eval(wo, out.wi) * (out.wi.z / out.pdf);
    return true;
}

}  // namespace bounce

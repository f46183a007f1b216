#pragma once
// The scene model's BRDF (Scene.h, docs/scene.md "Materials") at one surface point, in the local
// shading frame (normal = +z, wo and wi pointing away from the surface):
//   f = diffuseAlbedo / pi + D G F / (4 cos_i cos_o)
//   diffuseAlbedo = baseColor * texture * (1 - metallic)
//   F0 = mix(specularF0, baseColor * texture, metallic), F = F0 + (1 - F0)(1 - wo.h)^5   (Schlick)
//   D = GGX with alpha = roughness^2, G = G1(wo) G1(wi), separable Smith for GGX.
// The GGX lobe exists only when F0 is not zero: specularF0 = 0 and metallic = 0 is pure Lambert, as
// Scene.h promises, even at grazing angles where Schlick would otherwise add (1 - cos)^5.
#include "reference/Sampling.h"
#include "scene/Scene.h"

namespace bounce {

class Bsdf {
public:
    struct Sample {
        glm::vec3 wi;      // local frame
        glm::vec3 weight;  // f * cos(wi) / pdf
        float pdf;         // solid angle
    };

    // `textured` is baseColor already multiplied by the base-colour texture. `diffuseOnly` keeps
    // the Lambert lobe alone (the --diffuse-only scope for vertices after the first).
    Bsdf(const Material& material, glm::vec3 textured, bool diffuseOnly) noexcept;
    Bsdf() noexcept : m_diffuseAlbedo(0.0f) {}  // black

    bool isLambertian() const noexcept { return !m_hasSpecular; }
    glm::vec3 eval(glm::vec3 wo, glm::vec3 wi) const noexcept;
    float pdf(glm::vec3 wo, glm::vec3 wi) const noexcept;
    // Returns false when no direction was produced (sample below the surface, zero pdf).
    bool sample(glm::vec3 wo, float uLobe, float u1, float u2, Sample& out) const noexcept;

private:
    float specularProbability(glm::vec3 wo) const noexcept;
    glm::vec3 evalSpecular(glm::vec3 wo, glm::vec3 wi) const noexcept;
    float pdfSpecular(glm::vec3 wo, glm::vec3 wi) const noexcept;

    glm::vec3 m_diffuseAlbedo;
    glm::vec3 m_f0{0.0f};
    float m_alpha = 1.0f;
    bool m_hasSpecular = false;
};

}  // namespace bounce

// The viewer's A/B state: side A and side B each a technique with its own settings and pipeline, or
// side B an image (a stored EXR or the background path-traced reference of the current view, which
// restarts whenever the view it was started for changes); relMSE and FLIP of A against B, recomputed
// every viewer.metricsInterval frames on the CPU, with the FLIP heat map.
#include "app/viewer/Viewer.h"

#include "app/Options.h"
#include "core/ImageIo.h"
#include "core/ToneMap.h"
#include "metrics/ErrorMetrics.h"
#include "metrics/Heatmap.h"
#include "techniques/Registry.h"

#include <spdlog/spdlog.h>

namespace bounce {

Expected<std::unique_ptr<Technique>> makeTechnique(const Scene& scene, const std::string& name,
                                                   const std::map<std::string, std::string>& values) {
    BOUNCE_TRY(auto technique, createTechnique(name));
    render::RenderSettings ignored;  // the scene's renderer defaults were applied once at start
    // With a context, the device profile's defaults first (core/DeviceProfile.h).
    const std::optional<DeviceProfile> profile =
        gl::Context::current() ? std::optional(gl::Context::current()->info().profile) : std::nullopt;
    BOUNCE_TRY_VOID(applyAllSettings(scene, *technique, ignored, {}, profile));
    BOUNCE_TRY_VOID(applySettings(*technique, values, fmt::format("technique '{}'", name)));
    return technique;
}

std::map<std::string, std::string> currentValues(Technique& t) {
    std::map<std::string, std::string> values;
    for (const auto& d : describeSettings(t)) values[d.name] = d.defaultValue;
    return values;
}

// RGBA32F texture holding `image` (re-created when the size changes). Image row 0 is the top.
void uploadImage(gl::Texture& texture, const std::string& label, const Image& image) {
    if (!texture || texture.width() != image.width() || texture.height() != image.height())
        texture = gl::Texture::create2D(label, image.width(), image.height(), GL_RGBA32F);
    std::vector<glm::vec4> rgba(image.pixelCount());
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            rgba[static_cast<size_t>(image.height() - 1 - y) * image.width() + x] = glm::vec4(image.at(x, y), 1.0f);
    glTextureSubImage2D(texture.id(), 0, 0, 0, image.width(), image.height(), GL_RGBA, GL_FLOAT, rgba.data());
}

bool Viewer::readB(Image& out) {
    if (bSource == BSource::Image) {
        if (bImage.empty()) return false;
        out = bImage;
        return true;
    }
    if (!b.pipeline) return false;
    out = b.pipeline->readback(static_cast<Component>(component));
    return true;
}

void Viewer::computeMetrics() {
    metrics = {};
    metrics.frame = currentFrame();
    Image imgA, imgB;
    if (!a.pipeline || !readB(imgB)) {
        metrics.message = "no image on one side";
        return;
    }
    imgA = a.pipeline->readback(static_cast<Component>(component));
    if (imgA.width() != imgB.width() || imgA.height() != imgB.height()) {
        metrics.message = fmt::format("sizes differ: A {}x{}, B {}x{}", imgA.width(), imgA.height(), imgB.width(), imgB.height());
        return;
    }
    metrics.relMse = relativeSquaredErrorMap(imgA, imgB).mean();
    // LDR-FLIP of what is displayed: both tone-mapped with the viewer's exposure and curve,
    // decoded to linear display values as metrics/ErrorMetrics.cpp does.
    ToneMap tm{renderSettings.exposure, parseToneCurve(renderSettings.toneCurve).ok() ? *parseToneCurve(renderSettings.toneCurve) : ToneCurve::Aces};
    auto decoded = [&](const Image& radiance) {
        Image d = toDisplay(radiance, tm);
        for (glm::vec3& p : d.pixels()) p = {srgbDecode(p.r), srgbDecode(p.g), srgbDecode(p.b)};
        return d;
    };
    const ErrorMap flip = ldrFlip(decoded(imgA), decoded(imgB));
    metrics.flip = flip.mean();
    metrics.valid = true;
    Image heat(flip.width(), flip.height());
    for (int y = 0; y < flip.height(); ++y)
        for (int x = 0; x < flip.width(); ++x) heat.at(x, y) = heatmapColor(flip.at(x, y));
    uploadImage(heatTexture, "viewer.heatmap", heat);
}

Expected<void> Viewer::writeSideImage(Side& side, const std::string& file) {
    ToneMap tm{renderSettings.exposure, parseToneCurve(renderSettings.toneCurve).ok() ? *parseToneCurve(renderSettings.toneCurve) : ToneCurve::Aces};
    if (&side == &b && bSource == BSource::Image) {
        if (bImage.empty()) return makeError("side B has no image yet");
        return writeImage(file, bImage, tm);
    }
    if (!side.pipeline) return makeError("side {} has no image ({})", side.label, side.error);
    return writeImage(file, side.pipeline->readback(static_cast<Component>(component)), tm);
}

// (Re)builds the shown sides' pipelines at renderSize after a change of technique, settings or size.
void Viewer::rebuildSides() {
    for (Side* side : {&a, &b}) {
        if (side == &b && (!showsB() || bSource != BSource::Technique)) continue;
        // A failed build is retried only when something changes (settings, technique, size).
        if (!side->rebuild && side->builtSize == renderSize) continue;
        side->builtSize = renderSize;
        auto t = makeTechnique(*scene, side->technique, side->values);
        if (t.ok()) {
            auto p = Pipeline::create(*scene, std::move(*t), renderSize, renderSettings);
            if (p.ok()) {
                // The frame loop shows times, it does not record them: read them a frame late and
                // let the CPU queue the next frame while the GPU works (docs/gpu.md "Measured runs").
                (*p)->setLateTimings(true);
                side->pipeline = std::move(*p);
                side->error.clear();
            } else {
                side->pipeline.reset();
                side->error = p.error().message;
            }
        } else {
            side->pipeline.reset();
            side->error = t.error().message;
        }
        if (!side->error.empty()) spdlog::error("side {}: {}", side->label, side->error);
        side->rebuild = false;
        forceMetrics = true;
    }
}

std::vector<float> Viewer::currentView() const {
    const CameraPose pose = CameraPose::of(camera);
    std::vector<float> k{pose.position.x, pose.position.y, pose.position.z, pose.target.x, pose.target.y, pose.target.z,
                         pose.up.x, pose.up.y, pose.up.z, pose.verticalFov, static_cast<float>(currentFrame()),
                         static_cast<float>(referenceSize().x), static_cast<float>(referenceSize().y)};
    for (const Light& l : scene->lights) k.insert(k.end(), {l.position.x, l.position.y, l.position.z, l.direction.x, l.direction.y, l.direction.z});
    for (int i : movableObjects) {
        const glm::mat4& m = scene->objects[static_cast<size_t>(i)].transform;
        for (int c = 0; c < 4; ++c) k.insert(k.end(), {m[c].x, m[c].y, m[c].z, m[c].w});
    }
    return k;
}

void Viewer::startReference(int spp) {
    controller.apply(camera);
    if (followPath && !path.keys.empty()) camera = path.evaluate(scene->timeOfFrame(currentFrame())).applyTo(camera);
    referenceActive = true;
    referenceSpp = spp;
    referenceView = currentView();
    PathTracerSettings s;
    const glm::ivec2 rs = referenceSize();
    s.width = rs.x;
    s.height = rs.y;
    s.samplesPerPixel = static_cast<uint32_t>(std::max(1, spp));
    s.bounces = viewer.referenceBounces < 0 ? PathTracerSettings::kUnbounded : viewer.referenceBounces;
    s.indirectOnly = viewer.referenceIndirectOnly;
    s.threads = viewer.referenceThreads;
    s.frame = currentFrame();
    background.start(*scene, camera, s);
    bSource = BSource::Image;
    bImage = Image();
    bImageTexture = {};  // nothing shown until the first sample of this view
    bImageName = fmt::format("path-traced reference, frame {}", s.frame);
    if (abMode == AbMode::Off) abMode = AbMode::Split;
}

void Viewer::followReference() {
    // A background reference is of the view it was started for: when the camera (or the frame, a
    // light, an object, the size) changes, it restarts for the new view, and side B and the
    // metrics follow it from its first sample (the old one no longer matches side A).
    if (referenceActive && bSource == BSource::Image && currentView() != referenceView) {
        startReference(referenceSpp);
        ++referenceRestarts;
    }
}

void Viewer::takeReferenceUpdate() {
    if (Image update; background.takeUpdate(update)) {
        bImage = std::move(update);
        uploadImage(bImageTexture, "viewer.bImage", bImage);
        forceMetrics = true;
    }
}

void Viewer::techniqueCombo(Side& side, const char* label) {
    if (ImGui::BeginCombo(label, side.technique.c_str())) {
        for (const TechniqueInfo& t : registeredTechniques())
            if (ImGui::Selectable(t.name.c_str(), t.name == side.technique)) {
                auto tech = makeTechnique(*scene, t.name, {});
                if (tech.ok()) {
                    side.technique = t.name;
                    side.values = currentValues(**tech);
                    side.view.clear();
                    side.settingView.clear();
                    side.rebuild = true;
                    if (&side == &b) {
                        bSource = BSource::Technique;
                        background.stop();
                        referenceActive = false;
                    }
                }
            }
        ImGui::EndCombo();
    }
}

void Viewer::abPanel() {
    if (ImGui::CollapsingHeader("A/B comparison", ImGuiTreeNodeFlags_DefaultOpen)) {
        int mode = static_cast<int>(abMode);
        for (int i = 0; i < 3; ++i) {
            if (i) ImGui::SameLine();
            ImGui::RadioButton(kAbModeNames[i], &mode, i);
        }
        if (mode != static_cast<int>(abMode)) {
            abMode = static_cast<AbMode>(mode);
            forceMetrics = true;
        }
        ImGui::SameLine();
        ImGui::TextDisabled("(b)");
        if (showsB()) {
            int source = static_cast<int>(bSource);
            ImGui::RadioButton("B technique", &source, 0);
            ImGui::SameLine();
            ImGui::RadioButton("B image", &source, 1);
            bSource = static_cast<BSource>(source);
            if (bSource == BSource::Technique) techniqueCombo(b, "B technique##combo");
            else ImGui::TextWrapped("%s", bImageName.empty() ? "(no image: render a reference)" : bImageName.c_str());
            if (abMode == AbMode::Wipe) ImGui::SliderFloat("wipe", &wipe, 0.0f, 1.0f);
            if (ImGui::Checkbox("FLIP heat map", &heatmap)) forceMetrics = true;
            if (metrics.valid)
                ImGui::Text("A vs B, frame %u: relMSE %.4g  FLIP %.4f", metrics.frame, metrics.relMse, metrics.flip);
            else
                ImGui::TextDisabled("no metrics: %s", metrics.message.c_str());
        }
        const auto progress = background.progress();
        if (ImGui::Button(progress.running ? "restart reference" : "render reference")) startReference(viewer.referenceSpp);
        if (progress.running) {
            ImGui::SameLine();
            if (ImGui::Button("stop")) {
                background.stop();
                referenceActive = false;  // stopped on purpose: moving the camera does not restart it
            }
        }
        if (progress.samplesTarget > 0) {
            const float fraction = static_cast<float>(progress.samplesDone) / static_cast<float>(progress.samplesTarget);
            ImGui::ProgressBar(fraction, ImVec2(-1, 0),
                               fmt::format("{}/{} spp  {:.1f} s", progress.samplesDone, progress.samplesTarget, progress.seconds).c_str());
        }
        if (!progress.error.empty()) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "%s", progress.error.c_str());
    }
}

}  // namespace bounce

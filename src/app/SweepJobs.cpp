// The four kinds of study job. Each writes its images first (atomically, one by one) and its record
// last, so a job killed halfway leaves images without a record: not finished, redone on the next run.
#include "app/SweepJobs.h"

#include "app/CpuJobOptions.h"
#include "app/Options.h"
#include "app/ProcessContext.h"
#include "app/RunRecord.h"
#include "core/FileIo.h"
#include "core/ImageIo.h"
#include "gpu/Context.h"
#include "metrics/Convergence.h"
#include "metrics/ErrorMetrics.h"
#include "metrics/FlickerMeter.h"
#include "metrics/Heatmap.h"
#include "metrics/LightLeak.h"
#include "metrics/NoiseFloor.h"
#include "reference/ReferenceJob.h"
#include "techniques/Pipeline.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <thread>

namespace bounce::study {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path jobFolder(const Study& study, const Job& job) { return study.output / job.id; }
fs::path recordPath(const Study& study, const Job& job) { return jobFolder(study, job) / "record.json"; }

namespace {

Expected<json> readRecord(const fs::path& path) {
    BOUNCE_TRY(const std::string text, readTextFile(path));
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        return makeError("{}: {}", path.string(), e.what());
    }
}

std::string utcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    char buffer[32];
    std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buffer;
}

json baseRecord(const Study& study, const Job& job, const std::string& status) {
    return {{"job", job.id},   {"kind", jobKindName(job.kind)}, {"status", status}, {"study", study.name},
            {"spec", job.spec}, {"host", hostJson()},            {"finished", utcNow()}};
}

Expected<void> writeRecord(const Study& study, const Job& job, const json& record) {
    return writeTextFileAtomic(recordPath(study, job), record.dump(2) + "\n");
}

// The process's headless context (app/ProcessContext.h), made on first use (reference and compare jobs
// need none). Render and temporal jobs record timings: no debug context (docs/gpu.md "Measured runs").
Expected<gl::Context*> context() { return processContext(gl::measuredContextConfig()); }

struct Loaded {
    Scene scene;
    std::unique_ptr<Pipeline> pipeline;
    render::RenderSettings renderSettings;
    std::string refusal;  // non-empty: the technique cannot render this scene
};

// Scene, technique and pipeline of a render or temporal job. The study was checked, so settings
// apply; Pipeline::create failing is the technique refusing the scene (a one-line reason).
Expected<std::unique_ptr<Loaded>> load(const Study& study, const Job& job) {
    auto out = std::make_unique<Loaded>();
    const SceneSpec& spec = study.scenes[job.scene];
    const Variant& variant = study.variants[*job.variant];
    BOUNCE_TRY(out->scene, loadScene(spec.source, spec.params));
    BOUNCE_TRY(auto technique, createTechnique(variant.technique));
    std::vector<std::string> settings;
    for (const auto& [k, v] : variant.settings) settings.push_back(k + "=" + v);
    BOUNCE_TRY(gl::Context* const ctx, context());
    BOUNCE_TRY_VOID(applyAllSettings(out->scene, *technique, out->renderSettings, settings, ctx->info().profile));
    auto pipeline = Pipeline::create(out->scene, std::move(technique), study.size, out->renderSettings);
    if (!pipeline) out->refusal = pipeline.error().message;
    else out->pipeline = std::move(*pipeline);
    return out;
}

ToneMap pngToneMap(const render::RenderSettings& r) {
    ToneMap t;
    t.exposureEv = r.exposure;
    t.curve = *parseToneCurve(r.toneCurve);
    return t;
}

json leakJson(const Expected<double>& score) {
    if (score) return *score;
    return {{"error", score.error().message}};
}

// The pixels where the G-buffer holds a surface (position w = 1, render/gbuffer.frag), top row first
// like readTexture: elsewhere the position is 0, which a scene file's leak box may contain.
PixelMask coveredPixels(const gl::Texture& position) {
    const int w = position.width(), h = position.height();
    std::vector<glm::vec4> rgba(static_cast<size_t>(w) * h);
    glGetTextureImage(position.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(rgba.size() * sizeof(glm::vec4)), rgba.data());
    PixelMask covered(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) covered.set(x, y, rgba[static_cast<size_t>(h - 1 - y) * w + x].w > 0.5f);  // GL rows start at the bottom
    return covered;
}

Expected<void> runRender(const Study& study, const Job& job) {
    const fs::path folder = jobFolder(study, job);
    BOUNCE_TRY(auto loaded, load(study, job));
    if (!loaded->refusal.empty()) {
        json record = baseRecord(study, job, "refused");
        record["reason"] = loaded->refusal;
        record["technique"] = study.variants[*job.variant].technique;
        return writeRecord(study, job, record);
    }
    Pipeline& pipeline = *loaded->pipeline;
    std::vector<FrameStats> frames;
    for (int f = study.startFrame; f < study.startFrame + study.frames; ++f)
        frames.push_back(pipeline.renderFrame(static_cast<uint32_t>(f)));
    const ToneMap toneMap = pngToneMap(loaded->renderSettings);
    // Every image and the record are written together: a job that fails leaves none of them.
    OutputFiles files;
    json images = json::object();
    std::map<Component, Image> outputs;
    for (Component c : {Component::Full, Component::Direct, Component::Indirect}) {
        const std::string name(componentName(c));
        Image image = pipeline.readback(c);
        BOUNCE_TRY_VOID(checkFinite(image, fmt::format("{} {} output", job.id, name)));
        for (const char* ext : {".exr", ".png"}) {
            BOUNCE_TRY(std::string bytes, encodeImage(folder / (name + ext), image, toneMap));
            files.add(folder / (name + ext), std::move(bytes));
        }
        images[name] = name + ".png";
        outputs[c] = std::move(image);
    }
    json extra = {{"command", "sweep"}, {"frame_count", study.frames}, {"start_frame", study.startFrame}};
    json record = renderRunRecord(loaded->scene, pipeline, frames, (*context())->info(), extra);
    const json base = baseRecord(study, job, "ok");
    for (const auto& [k, v] : base.items()) record[k] = v;
    record["variant"] = study.variants[*job.variant].id;
    record["scope"] = scopeJson(job.scope);
    record["images"] = images;
    if (const auto& regions = loaded->scene.leakRegions) {
        // The masks come from this render's G-buffer positions: the pixels that see each room.
        const Image positions = readTexture(pipeline.gbuffer().position());
        const PixelMask covered = coveredPixels(pipeline.gbuffer().position());
        const PixelMask dark = boxMask(positions, regions->darkMin, regions->darkMax, &covered);
        const PixelMask lit = boxMask(positions, regions->litMin, regions->litMax, &covered);
        Image masks(positions.width(), positions.height());
        for (int y = 0; y < masks.height(); ++y)
            for (int x = 0; x < masks.width(); ++x) masks.at(x, y) = {dark.inside(x, y) ? 1.0f : 0.0f, lit.inside(x, y) ? 1.0f : 0.0f, 0.0f};
        BOUNCE_TRY(std::string maskBytes, encodeImage(folder / "leak-mask.png", masks, ToneMap{0.0f, ToneCurve::Clamp}));
        files.add(folder / "leak-mask.png", std::move(maskBytes));
        record["leak"] = {{"full", leakJson(lightLeakScore(outputs[Component::Full], dark, lit))},
                          {std::string(componentName(job.scope.component)),
                           leakJson(lightLeakScore(outputs[job.scope.component], dark, lit))},
                          {"darkPixels", dark.count()}, {"litPixels", lit.count()}, {"mask", "leak-mask.png"}};
    }
    files.add(recordPath(study, job), record.dump(2) + "\n");
    return files.commit();
}

Expected<void> runReference(const Study& study, const Job& job) {
    const fs::path folder = jobFolder(study, job);
    const SceneSpec& spec = study.scenes[job.scene];
    BOUNCE_TRY(const Scene scene, loadScene(spec.source, spec.params));
    ReferenceJob rj;
    rj.scene = spec.source;
    rj.sceneParams = spec.params;
    rj.settings.width = study.size.x;
    rj.settings.height = study.size.y;
    rj.settings.samplesPerPixel = study.reference.spp;
    rj.settings.bounces = job.scope.bounces < 0 ? PathTracerSettings::kUnbounded : job.scope.bounces;
    rj.settings.indirectOnly = job.scope.indirectOnly;
    rj.settings.diffuseOnly = job.scope.diffuseOnly;
    rj.settings.seed = study.reference.seed;
    rj.settings.timeLimitSeconds = study.reference.timeLimit;
    rj.settings.threads = study.reference.threads;
    rj.settings.frame = job.frame;
    rj.output = folder / "image.exr";
    rj.variance = folder / "variance.exr";  // the noise floors of the compares that read this reference
    BOUNCE_TRY(const PathTracerResult result, runReferenceJob(scene, rj));
    BOUNCE_TRY_VOID(writeImage(folder / "image.png", result.radiance, ToneMap{}));
    nlohmann::ordered_json ordered = referenceRunRecord(scene, rj, result);
    addNoiseFloor(ordered, result);
    json record = json(ordered);
    record["output"]["path"] = "image.exr";  // relative: output folders are copied between machines
    record["noise"]["variance"] = "variance.exr";
    const json base = baseRecord(study, job, "ok");
    for (const auto& [k, v] : base.items()) record[k] = v;
    record["images"] = {{"image", "image.png"}};
    return writeRecord(study, job, record);
}

Expected<Image> readExr(const fs::path& path) {
    BOUNCE_TRY(Image image, readImage(path));
    BOUNCE_TRY_VOID(checkFinite(image, path.string()));
    return image;
}

Expected<json> finishedInput(const Study& study, const std::string& id) {
    const Job* input = study.findJob(id);
    if (!input) return makeError("input job '{}' is not in the study", id);
    if (!jobFinished(study, *input))
        return makeError("input job '{}' has not finished (run stage 1 first: its record {} is missing or stale)", id,
                         recordPath(study, *input).string());
    return readRecord(recordPath(study, *input));
}

Expected<void> runCompare(const Study& study, const Job& job) {
    const fs::path folder = jobFolder(study, job);
    BOUNCE_TRY(const json render, finishedInput(study, job.inputs[0]));
    BOUNCE_TRY(const json reference, finishedInput(study, job.inputs[1]));
    json record = baseRecord(study, job, "ok");
    record["technique"] = study.variants[*job.variant].technique;
    record["variant"] = study.variants[*job.variant].id;
    record["scene"] = study.scenes[job.scene].id;
    record["render"] = job.inputs[0];
    record["reference"] = job.inputs[1];
    record["scope"] = scopeJson(job.scope);
    if (render.value("status", "") != "ok") {
        record["status"] = "skipped";
        record["reason"] = "render " + render.value("status", "?") + ": " + render.value("reason", "");
        return writeRecord(study, job, record);
    }
    const std::string component(componentName(job.scope.component));
    const fs::path renderFolder = study.output / job.inputs[0], referenceFolder = study.output / job.inputs[1];
    BOUNCE_TRY(const Image test, readExr(renderFolder / (component + ".exr")));
    BOUNCE_TRY(const Image ref, readExr(referenceFolder / "image.exr"));
    BOUNCE_TRY(const Image variance, readExr(referenceFolder / "variance.exr"));
    CompareMaps maps;
    BOUNCE_TRY(const ErrorMetrics metrics, compareImages(test, ref, CompareOptions{}, &maps));
    BOUNCE_TRY_VOID(writeHeatmap(folder / "heatmap.png", maps.flipHdr, 0.0f, 1.0f));  // FLIP lies in [0, 1]
    json m = toJson(metrics);
    m["relRms"] = relativeRmsError(test, ref);
    // The reference's noise floor beside every metric (metrics/NoiseFloor.h, docs/metrics.md).
    BOUNCE_TRY(const ErrorMetrics floor, referenceNoiseFloor(ref, variance, CompareOptions{}));
    m["relMseCorrected"] = biasCorrectedRelMse(test, ref, variance);
    record["metrics"] = m;
    record["floor"] = noiseFloorJson(floor);
    record["insideFloor"] = insideNoiseFloorJson(metrics, floor);
    record["floorFactor"] = kNoiseFloorFactor;
    record["referenceNoise"] = reference.value("noise", json::object());
    record["component"] = component;
    record["heatmap"] = {{"path", "heatmap.png"}, {"metric", "flip-hdr"}, {"low", 0.0}, {"high", 1.0}};
    record["median_ms"] = render.value("median_ms", json::object());
    if (render.contains("leak")) {
        // The reference's own score on the same masks: its noise (and light it truly has) in the dark room.
        BOUNCE_TRY(const Image masks, readImage(renderFolder / "leak-mask.png"));
        PixelMask dark(masks.width(), masks.height()), lit(masks.width(), masks.height());
        for (int y = 0; y < masks.height(); ++y)
            for (int x = 0; x < masks.width(); ++x) {
                dark.set(x, y, masks.at(x, y).r > 0.5f);
                lit.set(x, y, masks.at(x, y).g > 0.5f);
            }
        json leak = render["leak"].value(component, json());
        record["leak"] = {{"test", leak}, {"reference", leakJson(lightLeakScore(ref, dark, lit))}};
    }
    return writeRecord(study, job, record);
}

double meanLuminance(const Image& image) {
    double sum = 0.0;
    for (size_t i = 0; i < image.pixelCount(); ++i) {
        const glm::vec3 c = image.data()[i];
        sum += 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;  // Rec. 709, as metrics/FlickerMeter
    }
    return image.pixelCount() ? sum / static_cast<double>(image.pixelCount()) : 0.0;
}

// Flicker of one pair of frames: FlickerMeter's definition over just these two (null when black).
json pairFlicker(const Image& previous, const Image& current) {
    FlickerMeter meter;
    if (!meter.addFrame(previous) || !meter.addFrame(current)) return nullptr;
    auto f = meter.flicker();
    return f ? json(*f) : json(nullptr);
}

Expected<void> runTemporal(const Study& study, const Job& job) {
    const TemporalSpec& t = study.temporal;
    // One reference per frame; frames that show the same moment (a held animation) share one image.
    std::map<std::string, Image> referenceImages;
    std::map<std::string, ErrorMetrics> referenceFloors;  // the closed-form floors of each reference
    std::vector<const Image*> references;
    std::vector<const ErrorMetrics*> floors;
    for (const std::string& id : job.inputs) {
        if (!referenceImages.count(id)) {
            BOUNCE_TRY_VOID(finishedInput(study, id));
            BOUNCE_TRY(referenceImages[id], readExr(study.output / id / "image.exr"));
            BOUNCE_TRY(const Image variance, readExr(study.output / id / "variance.exr"));
            BOUNCE_TRY(referenceFloors[id], linearNoiseFloor(referenceImages[id], variance));
        }
        references.push_back(&referenceImages[id]);
        floors.push_back(&referenceFloors[id]);
    }
    BOUNCE_TRY(auto loaded, load(study, job));
    json record = baseRecord(study, job, "ok");
    record["technique"] = study.variants[*job.variant].technique;
    record["variant"] = study.variants[*job.variant].id;
    record["scene"] = study.scenes[job.scene].id;
    record["scope"] = scopeJson(job.scope);
    if (!loaded->refusal.empty()) {
        record["status"] = "refused";
        record["reason"] = loaded->refusal;
        return writeRecord(study, job, record);
    }
    Pipeline& pipeline = *loaded->pipeline;
    std::vector<Image> images;
    json frames = json::array();
    FlickerMeter techniqueFlicker, referenceFlicker;
    for (int i = 0; i < t.frames; ++i) {
        const int f = t.startFrame + i;
        const uint32_t frame = static_cast<uint32_t>(f);
        const uint32_t sceneFrame = t.sceneFrame(f);
        // The technique counts run frames (its history, interleaving, reseeding); the scene shows sceneFrame.
        const FrameStats stats = pipeline.renderFrame(frame, loaded->scene.timeOfFrame(sceneFrame));
        Image image = pipeline.readback(job.scope.component);
        BOUNCE_TRY_VOID(checkFinite(image, fmt::format("{} frame {}", job.id, frame)));
        BOUNCE_TRY_VOID(techniqueFlicker.addFrame(image));
        const Image& ref = *references[static_cast<size_t>(i)];
        BOUNCE_TRY_VOID(referenceFlicker.addFrame(ref));
        // Per frame only the cheap linear metrics: FLIP on every frame would cost more than the render.
        json fr = {{"frame", frame}, {"sceneFrame", sceneFrame}, {"time_s", stats.time},
                   {"gpu_ms", stats.passes.empty() ? 0.0 : stats.passes.front().milliseconds},
                   {"cpu_ms", stats.cpuMilliseconds}, {"relRms", relativeRmsError(image, ref)},
                   {"relMse", relativeSquaredErrorMap(image, ref).mean()}, {"meanLuminance", meanLuminance(image)},
                   {"referenceMeanLuminance", meanLuminance(ref)}};
        // The frame's reference-noise floors (docs/metrics.md), and whether the error is within 2x of them.
        const ErrorMetrics& floor = *floors[static_cast<size_t>(i)];
        fr["relRmsFloor"] = std::isfinite(floor.relRms) ? json(floor.relRms) : json(nullptr);
        fr["relMseFloor"] = floor.relMse;
        fr["relRmsInsideFloor"] = insideNoiseFloor("relRms", fr["relRms"].get<double>(), floor.relRms);
        fr["relMseInsideFloor"] = insideNoiseFloor("relMse", fr["relMse"].get<double>(), floor.relMse);
        fr["flicker"] = images.empty() ? json(nullptr) : pairFlicker(images.back(), image);
        fr["referenceFlicker"] = i == 0 ? json(nullptr) : pairFlicker(*references[static_cast<size_t>(i) - 1], ref);
        frames.push_back(fr);
        images.push_back(std::move(image));
    }
    // Convergence latency from the event (metrics/Convergence.h): the settled image is the last frame,
    // the latency the first k after the event from which every frame is within the threshold of it.
    const size_t event = static_cast<size_t>(t.eventFrame - t.startFrame);
    const ConvergenceLatency c = convergenceLatency(images, event, t.threshold);
    for (size_t i = event; i < images.size(); ++i) {
        const double e = c.errorToSettled[i];
        frames[i]["errorToSettled"] = std::isfinite(e) ? json(e) : json(nullptr);
    }
    auto tf = techniqueFlicker.flicker();
    auto rf = referenceFlicker.flicker();
    record["frames"] = frames;
    record["flicker"] = tf ? json(*tf) : json(nullptr);
    record["referenceFlicker"] = rf ? json(*rf) : json(nullptr);
    record["convergence"] = {{"eventFrame", t.eventFrame},
                             {"animation", animationName(t.animation)},
                             {"threshold", t.threshold},
                             {"metric", "relRms to the last frame"},
                             {"settled", c.settled},
                             {"latencyFrames", c.frames ? json(*c.frames) : json(nullptr)},
                             {"latencySeconds", c.frames ? json(*c.frames / loaded->scene.frameRate) : json(nullptr)}};
    record["gpu"] = gpuInfoJson((*context())->info());
    return writeRecord(study, job, record);
}

}  // namespace

json hostJson() {
    char name[256] = {};
    gethostname(name, sizeof name - 1);
    std::string cpu;
    std::ifstream info("/proc/cpuinfo");
    for (std::string line; std::getline(info, line);)
        if (line.rfind("model name", 0) == 0) {
            cpu = line.substr(line.find(':') + 2);
            break;
        }
    return {{"hostname", name}, {"cpu", cpu}, {"cores", std::thread::hardware_concurrency()}};
}

bool jobFinished(const Study& study, const Job& job) {
    const fs::path path = recordPath(study, job);
    std::error_code ec;
    if (!fs::exists(path, ec)) return false;
    auto record = readRecord(path);
    return record && record->value("spec", json()) == job.spec && record->contains("status");
}

Expected<void> runJob(const Study& study, const Job& job) {
    const fs::path folder = jobFolder(study, job);
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) return makeError("{}: cannot create the folder: {}", folder.string(), ec.message());
    // A stale record (the study changed) must not survive a run that then fails.
    fs::remove(recordPath(study, job), ec);
    switch (job.kind) {
        case JobKind::Render: return runRender(study, job);
        case JobKind::Reference: return runReference(study, job);
        case JobKind::Compare: return runCompare(study, job);
        case JobKind::Temporal: return runTemporal(study, job);
    }
    return makeError("unknown job kind");
}

}  // namespace bounce::study

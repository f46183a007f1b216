#include "app/viewer/BackgroundReference.h"

#include <algorithm>
#include <chrono>

namespace bounce {

void BackgroundReference::start(const Scene& scene, const Camera& camera, const PathTracerSettings& settings,
                                uint32_t chunkSpp) {
    stop();
    m_scene = scene;
    m_scene.camera = camera;
    m_scene.camera.animation = {};
    {
        std::lock_guard lock(m_mutex);
        m_progress = {};
        m_progress.samplesTarget = settings.samplesPerPixel;
        m_progress.running = true;
        m_updated = false;
    }
    m_cancel = false;
    m_thread = std::thread([this, settings, chunkSpp] { run(settings, std::max(1u, chunkSpp)); });
}

void BackgroundReference::stop() {
    m_cancel = true;
    if (m_thread.joinable()) m_thread.join();
    std::lock_guard lock(m_mutex);
    m_progress.running = false;
}

BackgroundReference::Progress BackgroundReference::progress() const {
    std::lock_guard lock(m_mutex);
    return m_progress;
}

bool BackgroundReference::takeUpdate(Image& out) {
    std::lock_guard lock(m_mutex);
    if (!m_updated) return false;
    out = m_mean;
    m_updated = false;
    return true;
}

void BackgroundReference::run(PathTracerSettings settings, uint32_t chunkSpp) {
    const auto begin = std::chrono::steady_clock::now();
    const uint32_t target = settings.samplesPerPixel;
    Image sum(settings.width, settings.height);
    uint32_t done = 0;
    // Each chunk is an independent render with its own seed; the mean of equal-weight chunks is the
    // estimate a single render with done samples would give (with other random numbers).
    for (uint64_t chunk = 0; done < target && !m_cancel; ++chunk) {
        PathTracerSettings s = settings;
        s.samplesPerPixel = std::min(chunkSpp, target - done);
        s.seed = settings.seed + chunk;
        s.timeLimitSeconds = 0.0;
        auto tracer = PathTracer::create(m_scene, s);
        if (!tracer.ok()) {
            std::lock_guard lock(m_mutex);
            m_progress.error = tracer.error().message;
            m_progress.running = false;
            return;
        }
        const PathTracerResult r = tracer->render();
        if (m_cancel) break;
        for (size_t i = 0; i < sum.pixelCount(); ++i)
            sum.data()[i] += r.radiance.data()[i] * static_cast<float>(r.samplesPerPixel);
        done += r.samplesPerPixel;
        Image mean(sum.width(), sum.height());
        for (size_t i = 0; i < sum.pixelCount(); ++i) mean.data()[i] = sum.data()[i] / static_cast<float>(done);
        std::lock_guard lock(m_mutex);
        m_mean = std::move(mean);
        m_updated = true;
        m_progress.samplesDone = done;
        m_progress.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    }
    std::lock_guard lock(m_mutex);
    m_progress.running = false;
}

}  // namespace bounce

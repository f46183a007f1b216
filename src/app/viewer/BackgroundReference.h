#pragma once
// The viewer's background ground truth: the CPU path tracer (reference/PathTracer.h) rendering the
// viewer's current camera, scene time and light positions on a worker thread, progressively. It
// traces `chunkSpp` samples per pixel at a time with a new seed each time and publishes the running
// mean after every chunk, so the A/B view can compare against it while it converges, and a stop
// request is honoured within one chunk.
#include "core/Image.h"
#include "reference/PathTracer.h"
#include "scene/Scene.h"

#include <atomic>
#include <mutex>
#include <string>
#include <thread>

namespace bounce {

class BackgroundReference {
public:
    struct Progress {
        uint32_t samplesDone = 0, samplesTarget = 0;
        double seconds = 0.0;
        bool running = false;
        std::string error;  // PathTracer::create's message (e.g. a scene without lights)
    };

    BackgroundReference() = default;
    BackgroundReference(const BackgroundReference&) = delete;
    BackgroundReference& operator=(const BackgroundReference&) = delete;
    ~BackgroundReference() { stop(); }

    // Stops a running render and starts one of `scene` (copied, with `camera` in place of its camera)
    // at `settings` (width, height, scope, threads, frame; samplesPerPixel is the target).
    void start(const Scene& scene, const Camera& camera, const PathTracerSettings& settings, uint32_t chunkSpp = 1);
    void stop();
    Progress progress() const;
    // The running mean when it changed since the last call.
    bool takeUpdate(Image& out);

private:
    void run(PathTracerSettings settings, uint32_t chunkSpp);

    Scene m_scene;
    std::thread m_thread;
    std::atomic<bool> m_cancel{false};
    mutable std::mutex m_mutex;
    Image m_mean;
    bool m_updated = false;
    Progress m_progress;
};

}  // namespace bounce

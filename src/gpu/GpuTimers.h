#pragma once
// Per-pass GPU times from GL_TIMESTAMP queries. A frame is bracketed by beginFrame()/endFrame();
// passes open named scopes (nesting allowed, shown as "outer/inner"; a name opened again in the
// same frame adds to its total). With Latency::Immediate endFrame() waits for the frame's results,
// which is what a measuring tool wants (`render --stats`, sweeps, benchmarks: each record holds its
// own frame's times). With Latency::OneFrame (the viewer) endFrame() returns the previous frame's
// results, which are ready by then, so the CPU never waits for the frame it just queued (issue 29 #8).
//
// Mode::Finish is for benchmarks that need to know which pass costs what on a deferred renderer:
// llvmpipe queues draws and rasterises them at the next flush, so a timestamp query charges a pass's
// work to whichever later scope flushes it. In Finish mode every scope boundary calls glFinish and the
// times are CPU wall clock between them: each pass's own work, at the price of the lost overlap (the
// frame gets slower; use it for breakdowns and ratios, Mode::Queries for frame times).
#include "gpu/Objects.h"

#include <chrono>
#include <string>
#include <string_view>
#include <vector>

namespace bounce::gl {

struct PassTime {
    std::string name;
    double milliseconds = 0.0;
};

class GpuTimers {
public:
    enum class Mode { Queries, Finish };
    // When endFrame() reads the timestamps (Mode::Queries only; Finish measures wall clock as it goes).
    enum class Latency { Immediate, OneFrame };

    class Scope {
    public:
        Scope(GpuTimers* timers, size_t index) : m_timers(timers), m_index(index) {}
        Scope(Scope&& o) noexcept : m_timers(std::exchange(o.m_timers, nullptr)), m_index(o.m_index) {}
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;
        Scope& operator=(Scope&&) = delete;
        ~Scope() {
            if (m_timers) m_timers->end(m_index);
        }

    private:
        GpuTimers* m_timers;
        size_t m_index;
    };

    void beginFrame();
    [[nodiscard]] Scope scope(std::string_view name);
    // Frame total (first key "frame") followed by every scope in the order opened: of this frame, or
    // with Latency::OneFrame of the frame before (empty after the first), see resultsFrame().
    std::vector<PassTime> endFrame();
    // The frame (count of beginFrame calls, from 0) whose times the last endFrame() returned; -1: none.
    long long resultsFrame() const { return m_resultsFrame; }
    bool enabled() const { return m_enabled; }
    void setEnabled(bool enabled) { m_enabled = enabled; }
    Mode mode() const { return m_mode; }
    void setMode(Mode mode) { m_mode = mode; }
    Latency latency() const { return m_latency; }
    void setLatency(Latency latency) { m_latency = latency; }

private:
    void end(size_t index);
    GLuint query();

    using Clock = std::chrono::steady_clock;
    struct Entry {
        std::string name;
        GLuint begin = 0, end = 0;          // Mode::Queries
        Clock::time_point beginTime, endTime;  // Mode::Finish
        bool ended = false;
    };
    // The queries of one frame, its scopes and its begin/end timestamps.
    struct FrameQueries {
        std::vector<Query> pool;
        std::vector<Entry> entries;
        GLuint begin = 0, end = 0;
        long long frame = -1;
        bool pending = false;  // ended, results not read yet
    };
    std::vector<PassTime> read(FrameQueries& f);

    FrameQueries m_frames[2];  // this frame's and, with Latency::OneFrame, the previous one's
    int m_current = 0;
    size_t m_used = 0;
    std::vector<std::string> m_stack;
    Clock::time_point m_frameBeginTime;
    Mode m_mode = Mode::Queries;
    Latency m_latency = Latency::Immediate;
    long long m_frameCount = 0, m_resultsFrame = -1;
    bool m_inFrame = false;
    bool m_enabled = true;
};

}  // namespace bounce::gl

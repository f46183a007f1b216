#pragma once
// Per-pass GPU times from GL_TIMESTAMP queries. A frame is bracketed by beginFrame()/endFrame();
// passes open named scopes (nesting allowed, shown as "outer/inner"; a name opened again in the
// same frame adds to its total). endFrame() waits for the
// results, which is what a measuring tool wants; the viewer reads them one frame late instead.
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
    // Frame total (first key "frame") followed by every scope in the order opened.
    std::vector<PassTime> endFrame();
    bool enabled() const { return m_enabled; }
    void setEnabled(bool enabled) { m_enabled = enabled; }
    Mode mode() const { return m_mode; }
    void setMode(Mode mode) { m_mode = mode; }

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
    std::vector<Query> m_pool;
    size_t m_used = 0;
    std::vector<Entry> m_entries;
    std::vector<std::string> m_stack;
    GLuint m_frameBegin = 0;
    Clock::time_point m_frameBeginTime;
    Mode m_mode = Mode::Queries;
    bool m_inFrame = false;
    bool m_enabled = true;
};

}  // namespace bounce::gl

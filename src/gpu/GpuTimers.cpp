#include "gpu/GpuTimers.h"

#include "core/Check.h"

#include <algorithm>

namespace bounce::gl {

GLuint GpuTimers::query() {
    auto& pool = m_frames[m_current].pool;
    if (m_used == pool.size())
        pool.push_back(Query::create(fmt::format("timer{}.{}", m_current, pool.size()), GL_TIMESTAMP));
    return pool[m_used++].id();
}

void GpuTimers::beginFrame() {
    // One frame late: this frame uses the other query set; the previous frame's stays pending.
    if (m_latency == Latency::OneFrame && m_mode == Mode::Queries) m_current = 1 - m_current;
    FrameQueries& f = m_frames[m_current];
    m_used = 0;
    f.entries.clear();
    f.pending = false;
    f.frame = m_frameCount++;
    m_stack.clear();
    m_inFrame = true;
    if (!m_enabled) return;
    if (m_mode == Mode::Finish) {
        glFinish();
        m_frameBeginTime = Clock::now();
        return;
    }
    f.begin = query();
    glQueryCounter(f.begin, GL_TIMESTAMP);
}

GpuTimers::Scope GpuTimers::scope(std::string_view name) {
    std::string full;
    for (const auto& s : m_stack) full += s + "/";
    full += name;
    m_stack.emplace_back(name);
    Entry e;
    e.name = std::move(full);
    if (m_enabled && m_inFrame) {
        if (m_mode == Mode::Finish) {
            glFinish();  // the work queued before the scope is not the scope's
            e.beginTime = Clock::now();
        } else {
            e.begin = query();
            glQueryCounter(e.begin, GL_TIMESTAMP);
        }
    }
    auto& entries = m_frames[m_current].entries;
    entries.push_back(std::move(e));
    return Scope(this, entries.size() - 1);
}

void GpuTimers::end(size_t index) {
    if (!m_stack.empty()) m_stack.pop_back();
    auto& entries = m_frames[m_current].entries;
    if (!m_enabled || !m_inFrame || index >= entries.size()) return;
    Entry& e = entries[index];
    e.ended = true;
    if (m_mode == Mode::Finish) {
        glFinish();  // the scope's work, rasterised now rather than at a later scope's flush
        e.endTime = Clock::now();
        return;
    }
    e.end = query();
    glQueryCounter(e.end, GL_TIMESTAMP);
}

namespace {
// A scope opened several times in one frame (a pass run per batch) reports its total, at the place it
// was first opened.
void add(std::vector<PassTime>& out, const std::string& name, double ms) {
    auto same = std::find_if(out.begin() + 1, out.end(), [&](const PassTime& p) { return p.name == name; });
    if (same != out.end()) same->milliseconds += ms;
    else out.push_back({name, ms});
}
}  // namespace

std::vector<PassTime> GpuTimers::read(FrameQueries& f) {
    std::vector<PassTime> out;
    f.pending = false;
    m_resultsFrame = f.frame;
    auto read = [](GLuint q) {
        GLuint64 t = 0;
        glGetQueryObjectui64v(q, GL_QUERY_RESULT, &t);
        return t;
    };
    const GLuint64 t0 = read(f.begin);
    out.push_back({"frame", static_cast<double>(read(f.end) - t0) * 1e-6});
    for (const Entry& e : f.entries) {
        if (!e.begin || !e.end) continue;
        const GLuint64 b = read(e.begin), en = read(e.end);
        add(out, e.name, static_cast<double>(en >= b ? en - b : 0) * 1e-6);
    }
    return out;
}

std::vector<PassTime> GpuTimers::endFrame() {
    std::vector<PassTime> out;
    if (!m_inFrame) return out;
    m_inFrame = false;
    if (!m_enabled) return out;
    FrameQueries& f = m_frames[m_current];
    if (m_mode == Mode::Finish) {
        glFinish();
        const auto ms = [](Clock::time_point a, Clock::time_point b) {
            return std::chrono::duration<double, std::milli>(b - a).count();
        };
        out.push_back({"frame", ms(m_frameBeginTime, Clock::now())});
        for (const Entry& e : f.entries)
            if (e.ended) add(out, e.name, ms(e.beginTime, e.endTime));
        m_resultsFrame = f.frame;
        return out;
    }
    f.end = query();
    glQueryCounter(f.end, GL_TIMESTAMP);
    f.pending = true;
    if (m_latency == Latency::Immediate) return read(f);
    // One frame late: the previous frame's queries, whose work the GPU has had a whole frame to finish.
    FrameQueries& previous = m_frames[1 - m_current];
    if (!previous.pending) {
        m_resultsFrame = -1;
        return out;
    }
    return read(previous);
}

}  // namespace bounce::gl

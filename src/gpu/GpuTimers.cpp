#include "gpu/GpuTimers.h"

#include "core/Check.h"

#include <algorithm>

namespace bounce::gl {

GLuint GpuTimers::query() {
    if (m_used == m_pool.size()) m_pool.push_back(Query::create(fmt::format("timer{}", m_pool.size()), GL_TIMESTAMP));
    return m_pool[m_used++].id();
}

void GpuTimers::beginFrame() {
    m_used = 0;
    m_entries.clear();
    m_stack.clear();
    m_inFrame = true;
    if (!m_enabled) return;
    if (m_mode == Mode::Finish) {
        glFinish();
        m_frameBeginTime = Clock::now();
        return;
    }
    m_frameBegin = query();
    glQueryCounter(m_frameBegin, GL_TIMESTAMP);
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
    m_entries.push_back(std::move(e));
    return Scope(this, m_entries.size() - 1);
}

void GpuTimers::end(size_t index) {
    if (!m_stack.empty()) m_stack.pop_back();
    if (!m_enabled || !m_inFrame || index >= m_entries.size()) return;
    Entry& e = m_entries[index];
    e.ended = true;
    if (m_mode == Mode::Finish) {
        glFinish();  // the scope's work, rasterised now rather than at a later scope's flush
        e.endTime = Clock::now();
        return;
    }
    e.end = query();
    glQueryCounter(e.end, GL_TIMESTAMP);
}

std::vector<PassTime> GpuTimers::endFrame() {
    std::vector<PassTime> out;
    if (!m_inFrame) return out;
    m_inFrame = false;
    if (!m_enabled) return out;
    const auto add = [&out](const std::string& name, double ms) {
        // A scope opened several times in one frame (a pass run per batch) reports its total, at the
        // place it was first opened.
        auto same = std::find_if(out.begin() + 1, out.end(), [&](const PassTime& p) { return p.name == name; });
        if (same != out.end()) same->milliseconds += ms;
        else out.push_back({name, ms});
    };
    if (m_mode == Mode::Finish) {
        glFinish();
        const auto ms = [](Clock::time_point a, Clock::time_point b) {
            return std::chrono::duration<double, std::milli>(b - a).count();
        };
        out.push_back({"frame", ms(m_frameBeginTime, Clock::now())});
        for (const Entry& e : m_entries)
            if (e.ended) add(e.name, ms(e.beginTime, e.endTime));
        return out;
    }
    const GLuint frameEnd = query();
    glQueryCounter(frameEnd, GL_TIMESTAMP);
    auto read = [](GLuint q) {
        GLuint64 t = 0;
        glGetQueryObjectui64v(q, GL_QUERY_RESULT, &t);
        return t;
    };
    const GLuint64 t0 = read(m_frameBegin);
    out.push_back({"frame", static_cast<double>(read(frameEnd) - t0) * 1e-6});
    for (const Entry& e : m_entries) {
        if (!e.begin || !e.end) continue;
        const GLuint64 b = read(e.begin), en = read(e.end);
        add(e.name, static_cast<double>(en >= b ? en - b : 0) * 1e-6);
    }
    return out;
}

}  // namespace bounce::gl

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
        e.begin = query();
        glQueryCounter(e.begin, GL_TIMESTAMP);
    }
    m_entries.push_back(std::move(e));
    return Scope(this, m_entries.size() - 1);
}

void GpuTimers::end(size_t index) {
    if (!m_stack.empty()) m_stack.pop_back();
    if (!m_enabled || !m_inFrame || index >= m_entries.size()) return;
    m_entries[index].end = query();
    glQueryCounter(m_entries[index].end, GL_TIMESTAMP);
}

std::vector<PassTime> GpuTimers::endFrame() {
    std::vector<PassTime> out;
    if (!m_inFrame) return out;
    m_inFrame = false;
    if (!m_enabled) return out;
    const GLuint frameEnd = query();
    glQueryCounter(frameEnd, GL_TIMESTAMP);
    auto read = [](GLuint q) {
        GLuint64 t = 0;
        glGetQueryObjectui64v(q, GL_QUERY_RESULT, &t);
        return t;
    };
    const GLuint64 t0 = read(m_frameBegin);
    out.push_back({"frame", static_cast<double>(read(frameEnd) - t0) * 1e-6});
    // A scope opened several times in one frame (a pass run per batch) reports its total, at the
    // place it was first opened.
    for (const Entry& e : m_entries) {
        if (!e.begin || !e.end) continue;
        const GLuint64 b = read(e.begin), en = read(e.end);
        const double ms = static_cast<double>(en >= b ? en - b : 0) * 1e-6;
        auto same = std::find_if(out.begin() + 1, out.end(), [&](const PassTime& p) { return p.name == e.name; });
        if (same != out.end()) same->milliseconds += ms;
        else out.push_back({e.name, ms});
    }
    return out;
}

}  // namespace bounce::gl

#pragma once
// The one thread that owns the module's GL context. bounce's GL layer is single-threaded (a context is
// current on the thread that made it, gl::Context::current() is thread-local), while Python may call
// from any thread and releases the GIL while rendering; so every GL call of the module (context
// creation, pipelines, frames, read-backs, deletions) runs here, one task at a time, and the caller
// waits for its result. Exceptions thrown by a task are rethrown in the caller.
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <thread>
#include <type_traits>

namespace bounce::python {

class GlThread {
public:
    // Made on first use and never destroyed: it must outlive every Python object that owns GL objects
    // (shutdown() stops it at interpreter exit, after those were released).
    static GlThread& instance() {
        static GlThread* thread = new GlThread();
        return *thread;
    }

    // Runs f() on the GL thread and returns its result (re-entrant: on the GL thread it just calls f).
    template <class F>
    auto run(F&& f) -> std::invoke_result_t<F&> {
        using R = std::invoke_result_t<F&>;
        if (std::this_thread::get_id() == m_thread.get_id()) return f();
        std::packaged_task<R()> task(std::forward<F>(f));
        std::future<R> result = task.get_future();
        {
            const std::lock_guard lock(m_mutex);
            if (m_stopped) throw std::runtime_error("bounce: the module's GL thread has stopped (the interpreter is exiting)");
            m_tasks.emplace_back([&task] { task(); });
        }
        m_wake.notify_one();
        return result.get();
    }

    // Runs `last` on the GL thread, then ends it (interpreter exit). Later run() calls throw.
    void shutdown(const std::function<void()>& last) {
        if (!m_thread.joinable()) return;
        run(last);
        {
            const std::lock_guard lock(m_mutex);
            m_stopped = true;
        }
        m_wake.notify_one();
        m_thread.join();
    }

private:
    GlThread() : m_thread([this] { loop(); }) {}

    void loop() {
        for (;;) {
            std::function<void()> task;
            {
                std::unique_lock lock(m_mutex);
                m_wake.wait(lock, [this] { return m_stopped || !m_tasks.empty(); });
                if (m_tasks.empty()) return;  // stopped and drained
                task = std::move(m_tasks.front());
                m_tasks.pop_front();
            }
            task();  // a packaged_task: its exception goes to the caller's future
        }
    }

    std::mutex m_mutex;
    std::condition_variable m_wake;
    std::deque<std::function<void()>> m_tasks;
    bool m_stopped = false;
    std::thread m_thread;  // last: started once the members it uses exist
};

}  // namespace bounce::python

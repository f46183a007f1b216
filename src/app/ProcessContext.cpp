#include "app/ProcessContext.h"

#include <memory>
#include <mutex>

namespace bounce {

namespace {
std::mutex g_mutex;
std::unique_ptr<gl::Context> g_context;
}  // namespace

Expected<gl::Context*> processContext() {
    std::unique_ptr<gl::Context>& context = g_context;
    const std::lock_guard lock(g_mutex);
    if (!context) {
        BOUNCE_TRY(context, gl::Context::createHeadless());
    }
    return context.get();
}

void releaseProcessContext() {
    const std::lock_guard lock(g_mutex);
    g_context.reset();
}

}  // namespace bounce

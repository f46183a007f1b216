#include "app/ProcessContext.h"

#include <memory>
#include <mutex>

namespace bounce {

Expected<gl::Context*> processContext() {
    static std::mutex mutex;
    static std::unique_ptr<gl::Context> context;
    const std::lock_guard lock(mutex);
    if (!context) {
        BOUNCE_TRY(context, gl::Context::createHeadless());
    }
    return context.get();
}

}  // namespace bounce

#pragma once
// Shared by the benchmarks of bounce_bench: one headless GL context for the whole binary (without
// debug output, which costs time on llvmpipe).
#include "gpu/Context.h"

#include <memory>

namespace bounce::bench {

inline gl::Context* context() {
    static std::unique_ptr<gl::Context> c = [] {
        gl::ContextConfig config;
        config.debugOutput = false;
        auto made = gl::Context::createHeadless(config);
        return made.ok() ? std::move(*made) : std::unique_ptr<gl::Context>();
    }();
    if (c) c->makeCurrent();
    return c.get();
}

}  // namespace bounce::bench

#pragma once
// Shared fixture of the GPU tests: one headless context per test binary. Under CI=true a missing
// context is a failure, elsewhere the GPU tests skip. Every test fails if KHR_debug reported a GL
// error while it ran.
#include "gpu/Context.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

namespace bounce::gputest {

inline gl::Context* sharedContext(std::string* error = nullptr) {
    static std::unique_ptr<gl::Context> context;
    static std::string failure;
    static bool tried = false;
    if (!tried) {
        tried = true;
        auto c = gl::Context::createHeadless();
        if (c.ok()) context = std::move(*c);
        else failure = c.error().message;
    }
    if (error) *error = failure;
    return context.get();
}

inline bool inCi() {
    const char* ci = std::getenv("CI");
    return ci && std::string(ci) == "true";
}

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string error;
        if (!sharedContext(&error)) {
            if (inCi()) FAIL() << "CI=true and no GL context: " << error;
            GTEST_SKIP() << "no GL context: " << error;
        }
        sharedContext()->makeCurrent();
        gl::Context::resetDebugErrorCount();
    }
    void TearDown() override {
        if (sharedContext()) {
            EXPECT_EQ(gl::Context::debugErrorCount(), 0) << "GL errors were reported (see log)";
        }
    }
};

}  // namespace bounce::gputest

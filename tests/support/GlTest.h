// Fixture for tests that need a GL context: one headless EGL context per test suite; any GL
// error (KHR_debug or glGetError) during a test fails it. Skips only where no context can exist.
#pragma once

#include "engine/gl/Context.h"
#include "engine/gl/Debug.h"
#include "engine/gl/Program.h"

#include <gtest/gtest.h>

#include <memory>

namespace test {

class GlTest : public ::testing::Test {
public:
    static void SetUpTestSuite();
    static void TearDownTestSuite();

protected:
    void SetUp() override;
    void TearDown() override;

    /** Engine shaders, ready to compile. */
    static const gl::ShaderLibrary& shaders();
    static gl::Context& context() { return *sContext; }
    /** For tests that provoke GL errors on purpose: errors so far do not fail the test. */
    void acceptErrors() { mErrorsAtStart = gl::errorCount(); }

private:
    static std::unique_ptr<gl::Context> sContext;
    static std::string sSkipReason;
    std::uint64_t mErrorsAtStart = 0;
};

} // namespace test

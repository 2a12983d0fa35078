// GL test fixture.
#include "support/GlTest.h"

#include "engine/core/Check.h"
#include "engine/gl/Shaders.h"
#include "engine/render/Shared.h"

namespace test {

std::unique_ptr<gl::Context> GlTest::sContext;
std::string GlTest::sSkipReason;

void GlTest::SetUpTestSuite() {
    if (sContext)
        return;
    auto context = gl::createHeadlessContext({.debug = true});
    if (context)
        sContext = std::move(*context);
    else
        sSkipReason = context.error().message;
    gl::setBindingChecks(true); // every draw and dispatch of a test checks its bindings
}

void GlTest::TearDownTestSuite() {
    sContext.reset();
}

const gl::ShaderLibrary& GlTest::shaders() {
    static gl::ShaderLibrary library = [] {
        gl::ShaderLibrary l;
        l.add(engineShaderFiles());
        ENGINE_CHECK(l.share("render", render::sharedTable()), "the render table registers");
        return l;
    }();
    return library;
}

void GlTest::SetUp() {
    if (!sContext)
        GTEST_SKIP() << "no headless OpenGL 4.5 context can be created here: " << sSkipReason;
    gl::checkErrors("before the test");
    mErrorsAtStart = gl::errorCount();
}

void GlTest::TearDown() {
    if (!sContext)
        return;
    gl::checkErrors("end of test");
    EXPECT_EQ(gl::errorCount(), mErrorsAtStart)
        << "GL errors were reported during the test (see log)";
}

} // namespace test

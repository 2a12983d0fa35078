// Frame graph without a GL context: a fake allocator stands in for GPU textures.
#include "engine/fg/FrameGraph.h"
#include "engine/fg/Blackboard.h"
#include "engine/gl/Context.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace {

/** Hands out distinct fake objects, textures and buffers, and counts them. */
class FakeAllocator final : public fg::TextureAllocator, public fg::BufferAllocator {
public:
    void* allocate(const gl::TextureDesc&) override { return fake(); }
    void* allocate(const gl::BufferDesc&) override { return fake(); }
    void release(void*) override { --live; }
    void* fake() {
        ++allocations;
        ++live;
        // A fake handle, never dereferenced: the allocator under test only stores it.
        const std::uintptr_t handle = std::uintptr_t(++next) * 16;
        return reinterpret_cast<void*>(handle); // NOLINT(performance-no-int-to-ptr)
    }
    int allocations = 0, live = 0;
    std::uintptr_t next = 0;
};

/** A context that is never current: fg passes it through untouched. */
class NoContext final : public gl::Context {
public:
    const std::string& description() const override { return mName; }
    bool isHeadless() const override { return true; }
    glm::ivec2 framebufferSize() const override { return {0, 0}; }

private:
    std::string mName = "none";
};

const gl::TextureDesc kColor{{64, 64}, gl::Format::RGBA16F, 1};

/** Each test's pools, over one fake allocator; its graphs draw from them. */
class FrameGraph : public ::testing::Test {
protected:
    FakeAllocator allocator;
    fg::TexturePool pool{allocator};
    fg::BufferPool buffers{allocator};
};
using FrameGraphDeathTest = FrameGraph;

struct One {
    fg::TextureHandle out;
};
struct InOut {
    fg::TextureHandle in, out;
};

TEST_F(FrameGraph, CulledPassNeverExecutes) {
    fg::FrameGraph graph(pool, buffers);
    NoContext context;
    std::vector<std::string> ran;
    const auto back = graph.importTexture("backbuffer", kColor, reinterpret_cast<void*>(8));
    const auto& a = graph.addPass<One>(
        "a", [&](fg::Builder& b, One& d) { d.out = b.write(b.create("a.out", kColor)); },
        [&](const fg::Resources&, const One&, gl::Context&) { ran.emplace_back("a"); });
    graph.addPass<One>(
        "unused", [&](fg::Builder& b, One& d) { d.out = b.write(b.create("unused.out", kColor)); },
        [&](const fg::Resources&, const One&, gl::Context&) { ran.emplace_back("unused"); });
    graph.addPass<InOut>(
        "present",
        [&](fg::Builder& b, InOut& d) {
            d.in = b.read(a.out);
            d.out = b.write(back);
        },
        [&](const fg::Resources& r, const InOut& d, gl::Context&) {
            EXPECT_NE(r.object(d.in), nullptr);
            ran.emplace_back("present");
        });
    ASSERT_TRUE(graph.compile().ok());
    ASSERT_TRUE(graph.execute(context).ok());
    EXPECT_EQ(ran, (std::vector<std::string>{"a", "present"}));
    EXPECT_NE(graph.dump().find("[culled] unused"), std::string::npos) << graph.dump();
    EXPECT_EQ(allocator.allocations, 1); // the culled pass's texture is never allocated
}

TEST_F(FrameGraph, PoolPeakEqualsPeakOfOverlappingLifetimes) {
    fg::FrameGraph graph(pool, buffers);
    NoContext context;
    // A chain t0 -> t1 -> t2 -> t3 of same-descriptor textures: pass i reads t(i-1) and writes
    // t(i), so at most two are alive at once and the pool needs exactly two.
    // names appended, not `"t" + std::to_string(i)`: GCC 12 at -O3 reports a false -Wrestrict
    // there (GCC bug 105329)
    auto named = [](std::string prefix, int i) { return prefix.append(std::to_string(i)); };
    fg::TextureHandle previous;
    for (int i = 0; i < 4; ++i) {
        const auto& d = graph.addPass<InOut>(
            named("step", i),
            [&](fg::Builder& b, InOut& data) {
                if (previous.valid())
                    data.in = b.read(previous);
                data.out = b.write(b.create(named("t", i), kColor));
                if (i == 3)
                    b.sideEffect();
            },
            [](const fg::Resources&, const InOut&, gl::Context&) {});
        previous = d.out;
    }
    ASSERT_TRUE(graph.compile().ok());
    ASSERT_TRUE(graph.execute(context).ok());
    EXPECT_EQ(pool.peakCount(), 2u);
    EXPECT_EQ(allocator.allocations, 2);
    EXPECT_EQ(pool.inUseCount(), 0u);

    // A second frame reuses the pooled textures: no new allocation.
    fg::FrameGraph again(pool, buffers);
    again.addPass<One>(
        "x",
        [&](fg::Builder& b, One& d) {
            d.out = b.write(b.create("x", kColor));
            b.sideEffect();
        },
        [](const fg::Resources&, const One&, gl::Context&) {});
    ASSERT_TRUE(again.compile().ok());
    ASSERT_TRUE(again.execute(context).ok());
    EXPECT_EQ(allocator.allocations, 2);
    for (int frame = 0; frame < 10; ++frame)
        pool.endFrame(8);
    EXPECT_EQ(allocator.live, 0); // idle textures are eventually freed
}

TEST_F(FrameGraph, BuffersOrderPassesAndKeepTheirWritersAlive) {
    fg::FrameGraph graph(pool, buffers);
    NoContext context;
    std::vector<std::string> ran;
    int vertexObject = 0;
    const auto back = graph.importTexture("backbuffer", kColor, reinterpret_cast<void*>(8));
    const auto vertices = graph.importBuffer("vertices", &vertexObject);
    struct Buffered {
        fg::BufferHandle vertices;
    };
    // A reader of the rest pose (kept for its side effect) runs before the writer.
    graph.addPass<Buffered>(
        "rest",
        [&](fg::Builder& b, Buffered&) {
            b.read(vertices);
            b.sideEffect();
        },
        [&](const fg::Resources&, const Buffered&, gl::Context&) { ran.emplace_back("rest"); });
    const auto& deform = graph.addPass<Buffered>(
        "deform", [&](fg::Builder& b, Buffered& d) { d.vertices = b.write(vertices); },
        [&](const fg::Resources& r, const Buffered& d, gl::Context&) {
            EXPECT_EQ(r.object(d.vertices), &vertexObject);
            ran.emplace_back("deform");
        });
    graph.addPass<One>(
        "draw",
        [&](fg::Builder& b, One& d) {
            b.read(deform.vertices);
            d.out = b.write(back);
        },
        [&](const fg::Resources&, const One&, gl::Context&) { ran.emplace_back("draw"); });
    // Reads the deformed vertices but nothing reads its output: culled.
    graph.addPass<One>(
        "unused",
        [&](fg::Builder& b, One& d) {
            b.read(deform.vertices);
            d.out = b.write(b.create("unused.out", kColor));
        },
        [&](const fg::Resources&, const One&, gl::Context&) { ran.emplace_back("unused"); });
    ASSERT_TRUE(graph.compile().ok());
    // "deform" writes an imported buffer: never culled, and its readers run after it.
    EXPECT_EQ(graph.executionOrder(), (std::vector<std::string>{"rest", "deform", "draw"}));
    ASSERT_TRUE(graph.execute(context).ok());
    EXPECT_EQ(ran, (std::vector<std::string>{"rest", "deform", "draw"}));
}

TEST_F(FrameGraph, ReaderOfABufferRunsBeforeItsNextWriter) {
    fg::FrameGraph graph(pool, buffers);
    const auto distances = graph.importBuffer("distances", nullptr);
    struct Buffered {
        fg::BufferHandle out;
    };
    const auto& first = graph.addPass<Buffered>(
        "first", [&](fg::Builder& b, Buffered& d) { d.out = b.write(distances); },
        [](const fg::Resources&, const Buffered&, gl::Context&) {});
    graph.addPass<Buffered>(
        "second", [&](fg::Builder& b, Buffered& d) { d.out = b.write(first.out); },
        [](const fg::Resources&, const Buffered&, gl::Context&) {});
    graph.addPass<Buffered>(
        "reader",
        [&](fg::Builder& b, Buffered&) {
            b.read(first.out);
            b.sideEffect();
        },
        [](const fg::Resources&, const Buffered&, gl::Context&) {});
    ASSERT_TRUE(graph.compile().ok());
    EXPECT_EQ(graph.executionOrder(), (std::vector<std::string>{"first", "reader", "second"}));
}

TEST_F(FrameGraph, FailingPassEndsTheFrameNamingItAndReturnsItsTextures) {
    fg::FrameGraph graph(pool, buffers);
    NoContext context;
    std::vector<std::string> ran;
    const auto back = graph.importTexture("backbuffer", kColor, reinterpret_cast<void*>(8));
    const auto& a = graph.addPass<One>(
        "a", [&](fg::Builder& b, One& d) { d.out = b.write(b.create("a.out", kColor)); },
        [&](const fg::Resources&, const One&, gl::Context&) -> core::Status {
            ran.emplace_back("a");
            return core::Error{"framebuffer 'a' incomplete"};
        });
    graph.addPass<InOut>(
        "b",
        [&](fg::Builder& b, InOut& d) {
            d.in = b.read(a.out);
            d.out = b.write(back);
        },
        [&](const fg::Resources&, const InOut&, gl::Context&) { ran.emplace_back("b"); });
    ASSERT_TRUE(graph.compile().ok());
    const auto executed = graph.execute(context);
    ASSERT_FALSE(executed.ok());
    EXPECT_EQ(executed.error().message,
              "fg::FrameGraph::execute(): pass 'a': framebuffer 'a' incomplete");
    EXPECT_EQ(ran, (std::vector<std::string>{"a"}));
    EXPECT_EQ(allocator.allocations, 1);
    EXPECT_EQ(pool.inUseCount(), 0u); // a.out went back to the pool although 'b' never ran
}

TEST_F(FrameGraph, RejectsReadOfNeverWrittenResource) {
    fg::FrameGraph graph(pool, buffers);
    fg::TextureHandle orphan;
    graph.addPass<One>(
        "maker", [&](fg::Builder& b, One&) { orphan = b.create("orphan", kColor); },
        [](const fg::Resources&, const One&, gl::Context&) {});
    graph.addPass<One>(
        "reader",
        [&](fg::Builder& b, One&) {
            b.read(orphan);
            b.sideEffect();
        },
        [](const fg::Resources&, const One&, gl::Context&) {});
    const auto status = graph.compile();
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().message, "fg::FrameGraph::compile(): pass 'reader' reads 'orphan' "
                                      "(version 0), which no pass writes");
}

TEST_F(FrameGraph, RejectsOutdatedWrite) {
    {
        fg::FrameGraph graph(pool, buffers);
        const auto back = graph.importTexture("backbuffer", kColor, reinterpret_cast<void*>(8));
        graph.addPass<One>(
            "w1", [&](fg::Builder& b, One& d) { d.out = b.write(back); },
            [](const fg::Resources&, const One&, gl::Context&) {});
        graph.addPass<One>(
            "w2", [&](fg::Builder& b, One& d) { d.out = b.write(back); },
            [](const fg::Resources&, const One&, gl::Context&) {});
        const auto status = graph.compile();
        ASSERT_FALSE(status.ok());
        EXPECT_NE(
            status.error().message.find("pass 'w2' writes an outdated version of 'backbuffer'"),
            std::string::npos)
            << status.error().message;
    }
}

// Transient buffers live from their creator to their last reader, from the buffer pool: two
// whose lives do not overlap share one object, and the pool keeps it for the next frame.
TEST_F(FrameGraph, TransientBuffersShareThePoolAcrossPassesAndFrames) {
    NoContext context;
    const gl::BufferDesc words{4096};
    struct Written {
        fg::BufferHandle list;
        fg::TextureHandle out;
    };
    for (int frame = 0; frame < 2; ++frame) {
        fg::FrameGraph graph(pool, buffers);
        const auto back = graph.importTexture("backbuffer", kColor, reinterpret_cast<void*>(8));
        std::vector<void*> seen;
        fg::TextureHandle target = back;
        for (const char* name : {"first", "second"}) {
            const auto& listed = graph.addPass<Written>(
                std::string(name) + ".list",
                [&](fg::Builder& b, Written& d) { d.list = b.write(b.create(name, words)); },
                [&](const fg::Resources& r, const Written& d, gl::Context&) {
                    seen.push_back(r.object(d.list));
                });
            target = graph
                         .addPass<Written>(
                             std::string(name) + ".use",
                             [&, list = listed.list](fg::Builder& b, Written& d) {
                                 d.list = b.read(list);
                                 d.out = b.write(target);
                             },
                             [&](const fg::Resources& r, const Written& d, gl::Context&) {
                                 seen.push_back(r.object(d.list));
                             })
                         .out;
        }
        ASSERT_TRUE(graph.compile().ok());
        ASSERT_TRUE(graph.execute(context).ok());
        ASSERT_EQ(seen.size(), 4u);
        EXPECT_EQ(seen[0], seen[1]); // one object from creator to reader
        EXPECT_EQ(seen[2], seen[0]); // the second list after the first's last reader: the same
        EXPECT_EQ(buffers.allocatedCount(), 1u);
        EXPECT_EQ(buffers.inUseCount(), 0u);
        EXPECT_EQ(buffers.allocatedBytes(), 4096u);
        EXPECT_NE(graph.dump().find("creates 'first' 4096 bytes"), std::string::npos);
        buffers.endFrame();
    }
    EXPECT_EQ(allocator.allocations, 1); // kept across the frames
}

// Resources::buffer reaches only gl::Buffers: a buffer imported as an object of its own (a BVH,
// say) is an error there, not a reinterpretation.
TEST_F(FrameGraphDeathTest, ABufferImportedAsAnObjectIsNotAGlBuffer) {
    fg::FrameGraph graph(pool, buffers);
    NoContext context;
    int tree = 0; // stands for a structure of several buffers
    const fg::BufferHandle imported = graph.importBuffer("tree", &tree);
    struct Read {
        fg::BufferHandle tree;
    };
    graph.addPass<Read>(
        "reader",
        [&](fg::Builder& b, Read& d) {
            d.tree = b.read(imported);
            b.sideEffect();
        },
        [&](const fg::Resources& r, const Read& d, gl::Context&) {
            EXPECT_EQ(r.object(d.tree), &tree);
            r.buffer(d.tree);
        });
    ASSERT_TRUE(graph.compile().ok());
    EXPECT_DEATH((void)graph.execute(context), "'tree' is not a gl::Buffer");
}

TEST_F(FrameGraph, ReadersRunBeforeTheNextWriter) {
    fg::FrameGraph graph(pool, buffers);
    NoContext context;
    const auto back = graph.importTexture("backbuffer", kColor, reinterpret_cast<void*>(8));
    const auto& first = graph.addPass<One>(
        "draw", [&](fg::Builder& b, One& d) { d.out = b.write(back); },
        [](const fg::Resources&, const One&, gl::Context&) {});
    // Declared first but writes the next version: must wait for the reader of version 1.
    graph.addPass<One>(
        "overdraw", [&](fg::Builder& b, One& d) { d.out = b.write(first.out); },
        [](const fg::Resources&, const One&, gl::Context&) {});
    graph.addPass<One>(
        "copy",
        [&](fg::Builder& b, One& d) {
            b.read(first.out);
            d.out = b.write(b.create("copy", kColor));
            b.sideEffect();
        },
        [](const fg::Resources&, const One&, gl::Context&) {});
    ASSERT_TRUE(graph.compile().ok());
    EXPECT_EQ(graph.executionOrder(), (std::vector<std::string>{"draw", "copy", "overdraw"}));
    const auto timings = graph.execute(context);
    ASSERT_TRUE(timings.ok());
    ASSERT_EQ(timings->size(), 3u);
    EXPECT_GE((*timings)[0].cpuMs, 0.0);
}

TEST_F(FrameGraph, AFinalReadRunsAfterAWriterRecordedLater) {
    fg::FrameGraph graph(pool, buffers);
    NoContext context;
    fg::Blackboard board;
    const auto back = graph.importTexture("backbuffer", kColor, reinterpret_cast<void*>(8));
    // The engine's shadows, then its shading, which reads the atlas as the frame leaves it.
    const auto& shadows = graph.addPass<One>(
        "shadows", [&](fg::Builder& b, One& d) { d.out = b.write(b.create("atlas", kColor)); },
        [](const fg::Resources&, const One&, gl::Context&) {});
    board.put("atlas", shadows.out);
    const void* shaded = nullptr;
    graph.addPass<InOut>(
        "shade",
        [&](fg::Builder& b, InOut& d) {
            d.in = b.readFinal<fg::TextureHandle>(board, "atlas");
            d.out = b.write(back);
        },
        [&](const fg::Resources& r, const InOut& d, gl::Context&) { shaded = r.object(d.in); });
    // A plugin recorded after the shading draws its glass into the atlas.
    const auto& glass = graph.addPass<One>(
        "glass", [&](fg::Builder& b, One& d) { d.out = b.write(shadows.out); },
        [](const fg::Resources&, const One&, gl::Context&) {});
    board.put("atlas", glass.out);
    // Writes on top of what nothing reads: culled.
    graph.addPass<One>(
        "late", [&](fg::Builder& b, One& d) { d.out = b.write(b.create("late", kColor)); },
        [](const fg::Resources&, const One&, gl::Context&) {});
    ASSERT_TRUE(graph.compile().ok());
    // "glass" lives because the shading reads its version, and runs before it.
    EXPECT_EQ(graph.executionOrder(), (std::vector<std::string>{"shadows", "glass", "shade"}));
    ASSERT_TRUE(graph.execute(context).ok());
    EXPECT_NE(shaded, nullptr);
    EXPECT_NE(graph.dump().find("reads   'atlas' (version 2)"), std::string::npos) << graph.dump();
}

/** A shading pass that reads the final "atlas" of `board` into a texture of its own. */
const One& addShade(fg::FrameGraph& graph, const fg::Blackboard& board) {
    return graph.addPass<One>(
        "shade",
        [&](fg::Builder& b, One& d) {
            b.readFinal<fg::TextureHandle>(board, "atlas");
            d.out = b.write(b.create("shaded", kColor));
            b.sideEffect();
        },
        [](const fg::Resources&, const One&, gl::Context&) {});
}

TEST_F(FrameGraph, AFinalReadFailsWhereTheKeyHoldsNoVersionOrMakesACycle) {
    {
        fg::FrameGraph graph(pool, buffers);
        fg::Blackboard board;
        board.put("atlas", 1.0f); // another type
        addShade(graph, board);
        const auto compiled = graph.compile();
        ASSERT_FALSE(compiled.ok());
        EXPECT_NE(compiled.error().message.find("pass 'shade' reads the final 'atlas'"),
                  std::string::npos)
            << compiled.error().message;
    }
    fg::FrameGraph graph(pool, buffers);
    fg::Blackboard board;
    // "shade" reads what "glass" writes last, and "glass" draws on what "shade" wrote.
    const One& shade = addShade(graph, board);
    const auto& glass = graph.addPass<One>(
        "glass", [&](fg::Builder& b, One& d) { d.out = b.write(shade.out); },
        [](const fg::Resources&, const One&, gl::Context&) {});
    board.put("atlas", glass.out);
    const auto compiled = graph.compile();
    ASSERT_FALSE(compiled.ok());
    EXPECT_NE(compiled.error().message.find("'shade', 'glass' depend on each other in a cycle"),
              std::string::npos)
        << compiled.error().message;
}

TEST(Blackboard, TypedValues) {
    fg::Blackboard board;
    board.put("scene.color", fg::TextureHandle{3});
    board.put("exposure", 1.5f);
    EXPECT_EQ(board.get<fg::TextureHandle>("scene.color").node, 3u);
    EXPECT_EQ(board.find<int>("exposure"), nullptr);
    EXPECT_FLOAT_EQ(*board.find<float>("exposure"), 1.5f);
    EXPECT_FALSE(board.contains("missing"));
}

} // namespace

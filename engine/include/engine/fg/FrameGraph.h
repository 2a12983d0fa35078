// The frame graph: passes declare the textures they create, read and write; compile() orders
// them, culls what nobody consumes and rejects bad graphs; execute() runs them with transient
// textures from a pool. No GL calls here: GPU objects come through TexturePool's allocator.
#pragma once

#include "engine/core/Result.h"
#include "engine/fg/TexturePool.h"
#include "engine/gl/Types.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace gl {
class Context;
class Texture;
} // namespace gl

namespace fg {

/** A version of a texture resource. Every write() yields a new handle; reads name the version
 *  they consume. Default-constructed handles are invalid. */
struct TextureHandle {
    std::uint32_t node = UINT32_MAX;
    bool valid() const { return node != UINT32_MAX; }
    bool operator==(const TextureHandle&) const = default;
};

class FrameGraph;

/** Declares a pass's resources during setup. */
class Builder {
public:
    /** A transient texture, allocated from the pool for this pass through its last reader. */
    TextureHandle create(const std::string& name, const gl::TextureDesc& desc);
    /** Declares that the pass reads this version. */
    TextureHandle read(TextureHandle handle);
    /** Declares that the pass writes (on top of) this version; returns the new version. */
    TextureHandle write(TextureHandle handle);
    /** The pass is never culled (it has effects outside the graph). */
    void sideEffect();
    /** The pass runs after the pass named `pass` (ordering without a resource between them). */
    void after(const std::string& pass);

private:
    friend class FrameGraph;
    Builder(FrameGraph& graph, std::uint32_t pass) : mGraph(graph), mPass(pass) {}
    FrameGraph& mGraph;
    std::uint32_t mPass;
};

/** Access to the pass's textures while it executes. */
class Resources {
public:
    /** The GPU object behind `handle` (a gl::Texture for the engine's allocator). */
    void* object(TextureHandle handle) const;
    gl::Texture& texture(TextureHandle handle) const {
        return *static_cast<gl::Texture*>(object(handle));
    }
    const gl::TextureDesc& desc(TextureHandle handle) const;

private:
    friend class FrameGraph;
    explicit Resources(const FrameGraph& graph) : mGraph(graph) {}
    const FrameGraph& mGraph;
};

/** Brackets each executed pass (the renderer times it on the GPU with timer queries). */
class PassObserver {
public:
    virtual ~PassObserver() = default;
    virtual void beginPass(const std::string& name) = 0;
    virtual void endPass(const std::string& name) = 0;
};

/** CPU time of one executed pass. */
struct PassTiming {
    std::string name;
    double cpuMs = 0.0;
};

class FrameGraph {
public:
    explicit FrameGraph(TexturePool& pool);
    ~FrameGraph();
    FrameGraph(const FrameGraph&) = delete;
    FrameGraph& operator=(const FrameGraph&) = delete;

    /** Adds a pass: `setup` runs now and declares resources into `Data`; `execute` runs at
     *  execute() time if the pass survives culling. Returns the pass's data. */
    template <class Data>
    const Data& addPass(const std::string& name, std::function<void(Builder&, Data&)> setup,
                        std::function<void(const Resources&, const Data&, gl::Context&)> execute) {
        auto data = std::make_shared<Data>();
        const std::uint32_t pass = addPassNode(name);
        Builder builder(*this, pass);
        setup(builder, *data);
        setExecute(pass, [data, execute = std::move(execute)](const Resources& r, gl::Context& c) {
            execute(r, *data, c);
        });
        return *data;
    }

    /** A texture that lives outside the graph (the backbuffer, history textures). Version 0
     *  counts as written; passes that write it are never culled. */
    TextureHandle importTexture(const std::string& name, const gl::TextureDesc& desc, void* object);

    /** Orders passes (dependencies, then declaration order), culls passes whose outputs nobody
     *  consumes, computes transient lifetimes. Fails on a read of something never written, a
     *  write to an outdated version, an unknown `after` pass or a cycle, naming passes and
     *  resources. */
    core::Status compile();

    /** Runs the compiled passes in order; transient textures are acquired before their first
     *  use and released after their last. Returns each executed pass's CPU time. */
    std::vector<PassTiming> execute(gl::Context& context, PassObserver* observer = nullptr);

    /** The compiled graph as text: passes in order (culled ones marked) with their reads and
     *  writes, and each transient's lifetime. */
    std::string dump() const;

    /** Names of the passes that execute, in order (after compile()). */
    std::vector<std::string> executionOrder() const;

private:
    friend class Builder;
    friend class Resources;
    struct Pass;
    struct Resource;
    struct Node;
    std::uint32_t addPassNode(const std::string& name);
    void setExecute(std::uint32_t pass, std::function<void(const Resources&, gl::Context&)> fn);
    std::uint32_t addNode(std::uint32_t resource, std::uint32_t version, std::uint32_t writer);
    std::string nodeName(std::uint32_t node) const;

    TexturePool& mPool;
    std::vector<Pass> mPasses;
    std::vector<Resource> mResources;
    std::vector<Node> mNodes;
    std::vector<std::uint32_t> mOrder; // executed passes after compile()
    bool mCompiled = false;
};

} // namespace fg

// The frame graph: passes declare the textures and buffers they create, read and write;
// compile() orders them, culls what nobody consumes and rejects bad graphs; execute() runs them
// with transient textures and buffers from pools and stops at a pass that fails. No GL calls
// here: GPU objects come through the pools' allocators or are imported.
#pragma once

#include "engine/core/Result.h"
#include "engine/fg/Blackboard.h"
#include "engine/fg/Pool.h"
#include "engine/gl/Types.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace gl {
class Buffer;
class Context;
class Texture;
} // namespace gl

namespace fg {

/** A version of a resource. Every write() yields a new handle; reads name the version they
 *  consume. Default-constructed handles are invalid. `Kind` keeps textures and buffers apart. */
template <class Kind> struct Handle {
    std::uint32_t node = UINT32_MAX;
    bool valid() const { return node != UINT32_MAX; }
    bool operator==(const Handle&) const = default;
};
struct TextureKind {};
struct BufferKind {};
using TextureHandle = Handle<TextureKind>;
/** A buffer the graph orders passes by: transient (created by a pass, a gl::Buffer from the
 *  pool for this frame) or imported (deformed vertices, a BVH: its GPU objects owned outside the
 *  graph). */
using BufferHandle = Handle<BufferKind>;

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
    /** A transient buffer of `desc.size` bytes, from the pool for this pass through its last
     *  reader; what it holds when acquired is undefined (its first writer fills it). */
    BufferHandle create(const std::string& name, const gl::BufferDesc& desc);
    /** The same for buffers: the pass runs after the version's writer and before its next. */
    BufferHandle read(BufferHandle handle);
    BufferHandle write(BufferHandle handle);
    /** Declares that the pass reads the version `blackboard` holds under `key` once recording
     *  ends, however late the pass that writes it is recorded: the pass runs after that writer.
     *  (The engine's shading reads the shadow atlases so; a plugin draws its glass into them
     *  after the opaque scene is recorded.) `blackboard` outlives compile(), which fails naming
     *  the pass and the key where it holds no H there. The handle is valid in execute. */
    template <class H> H readFinal(const Blackboard& blackboard, const std::string& key) {
        return H{readFinal(key, [&blackboard, key] {
            const H* handle = blackboard.find<H>(key);
            return handle ? handle->node : UINT32_MAX;
        })};
    }
    /** The pass is never culled (it has effects outside the graph). */
    void sideEffect();

private:
    friend class FrameGraph;
    Builder(FrameGraph& graph, std::uint32_t pass) : mGraph(graph), mPass(pass) {}
    std::uint32_t read(std::uint32_t node);
    std::uint32_t write(std::uint32_t node);
    std::uint32_t readFinal(const std::string& key, std::function<std::uint32_t()> resolve);
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
    /** The object an imported buffer was given with, or a transient buffer's gl::Buffer. */
    void* object(BufferHandle handle) const;
    /** A transient buffer, or one imported as a gl::Buffer (checked: a buffer imported as an
     *  object of its own is reached through object()). */
    gl::Buffer& buffer(BufferHandle handle) const;

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
    FrameGraph(TexturePool& textures, BufferPool& buffers);
    ~FrameGraph();
    FrameGraph(const FrameGraph&) = delete;
    FrameGraph& operator=(const FrameGraph&) = delete;

    /** Adds a pass: `setup` runs now and declares resources into `Data`; `execute(resources,
     *  data, context)` runs at execute() time if the pass survives culling, returning void or
     *  a core::Status (an error stops the frame). Returns the pass's data. */
    template <class Data, class Execute>
    const Data& addPass(const std::string& name, std::function<void(Builder&, Data&)> setup,
                        Execute execute) {
        using Returned =
            std::invoke_result_t<Execute&, const Resources&, const Data&, gl::Context&>;
        static_assert(std::is_void_v<Returned> || std::is_same_v<Returned, core::Status>,
                      "a pass's execute returns void or core::Status");
        auto data = std::make_shared<Data>();
        const std::uint32_t pass = addPassNode(name);
        Builder builder(*this, pass);
        setup(builder, *data);
        setExecute(pass,
                   [data, execute = std::move(execute)](const Resources& r,
                                                        gl::Context& c) -> core::Status {
                       if constexpr (std::is_void_v<Returned>) {
                           execute(r, *data, c);
                           return {};
                       } else {
                           return execute(r, *data, c);
                       }
                   });
        return *data;
    }

    /** A texture that lives outside the graph (the backbuffer, history textures). Version 0
     *  counts as written; passes that write it are never culled. */
    TextureHandle importTexture(const std::string& name, const gl::TextureDesc& desc, void* object);
    /** A buffer (or a set of buffers: `object` is whatever its passes need) that lives outside
     *  the graph. Version 0 counts as written; passes that write it are never culled. */
    BufferHandle importBuffer(const std::string& name, void* object);
    /** One gl::Buffer that lives outside the graph, which its passes reach through
     *  Resources::buffer. */
    BufferHandle importBuffer(const std::string& name, gl::Buffer& buffer);

    /** Resolves the final reads, orders passes (dependencies, then declaration order), culls
     *  passes whose outputs nobody consumes, computes transient lifetimes. Fails on a read of
     *  something never written, a write to an outdated version or a cycle, naming passes and
     *  resources. */
    core::Status compile();

    /** Runs the compiled passes in order; transient textures are acquired before their first
     *  use and released after their last. Returns each executed pass's CPU time, or the first
     *  pass error, naming the pass (the passes after it do not run; transients go back). */
    core::Result<std::vector<PassTiming>> execute(gl::Context& context,
                                                  PassObserver* observer = nullptr);

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
    struct FinalRead;
    std::uint32_t addPassNode(const std::string& name);
    void setExecute(std::uint32_t pass,
                    std::function<core::Status(const Resources&, gl::Context&)> fn);
    /** What a resource is: a texture, a gl::Buffer, or a buffer imported as an object of its
     *  own (a BVH: Resources::object only). */
    enum class Kind : std::uint8_t;
    std::uint32_t addImported(const std::string& name, Kind kind, const gl::TextureDesc& desc,
                              void* object);
    std::uint32_t addCreated(const std::string& name, Kind kind, const gl::TextureDesc& texture,
                             const gl::BufferDesc& buffer);
    std::uint32_t addNode(std::uint32_t resource, std::uint32_t version, std::uint32_t writer);
    std::string nodeName(std::uint32_t node) const;
    // compile()'s steps.
    /** Each final read's node becomes the version its key names. */
    core::Status resolveFinalReads();
    /** Every read has a writer (or an import); no version is written twice. */
    core::Status checkVersions() const;
    /** Per pass, the passes after it (data edges and readers before the next writer), and
     *  the passes whose data it reads. */
    struct Edges {
        std::vector<std::vector<std::uint32_t>> successors, consumes;
    };
    Edges dependencyEdges() const;
    /** The passes kept: side effects, writers of imported resources and what they read. */
    std::vector<bool> neededPasses(const Edges& edges) const;
    /** mOrder: the kept passes, each after what it depends on, lowest index first. */
    core::Status orderPasses(const Edges& edges, const std::vector<bool>& needed);
    /** Each resource's first and last use over mOrder. */
    void measureLifetimes();

    TexturePool& mTextures;
    BufferPool& mBuffers;
    std::vector<Pass> mPasses;
    std::vector<Resource> mResources;
    std::vector<Node> mNodes;
    std::vector<FinalRead> mFinalReads;
    std::vector<std::uint32_t> mOrder; // executed passes after compile()
    bool mCompiled = false;
};

} // namespace fg

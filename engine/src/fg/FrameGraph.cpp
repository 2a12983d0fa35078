// Frame graph: versioned resource nodes, culling, ordering, lifetimes, execution.
#include "engine/fg/FrameGraph.h"

#include "engine/core/Check.h"

#include <algorithm>
#include <chrono>
#include <sstream>

namespace fg {

struct FrameGraph::Pass {
    std::string name;
    std::vector<std::uint32_t> reads;   // nodes
    std::vector<std::uint32_t> writes;  // nodes (new versions)
    std::vector<std::uint32_t> creates; // resources
    bool sideEffect = false;
    bool culled = false;
    std::function<core::Status(const Resources&, gl::Context&)> execute;
};

enum class FrameGraph::Kind : std::uint8_t { Texture, Buffer, Object };

struct FrameGraph::Resource {
    std::string name;
    Kind kind = Kind::Texture;
    gl::TextureDesc desc;      // textures only
    gl::BufferDesc bufferDesc; // transient buffers only
    bool imported = false;
    void* object = nullptr; // imported object, or the pooled one while alive
    std::uint32_t latestNode = UINT32_MAX;
    int firstUse = -1, lastUse = -1; // positions in mOrder
};

struct FrameGraph::Node {
    std::uint32_t resource;
    std::uint32_t version;
    std::uint32_t writer; // pass, UINT32_MAX for version 0
    bool final = false;   // a final read's: the version it names, from compile() on
};

struct FrameGraph::FinalRead {
    std::uint32_t node, pass;
    std::string key;
    std::function<std::uint32_t()> resolve; // the node the blackboard holds under key
};

FrameGraph::FrameGraph(TexturePool& textures, BufferPool& buffers)
    : mTextures(textures), mBuffers(buffers) {}
FrameGraph::~FrameGraph() = default;

std::uint32_t FrameGraph::addPassNode(const std::string& name) {
    ENGINE_CHECK(!mCompiled, "addPass() after compile()");
    mPasses.push_back(Pass{});
    mPasses.back().name = name;
    return std::uint32_t(mPasses.size() - 1);
}

void FrameGraph::setExecute(std::uint32_t pass,
                            std::function<core::Status(const Resources&, gl::Context&)> fn) {
    mPasses[pass].execute = std::move(fn);
}

std::uint32_t FrameGraph::addNode(std::uint32_t resource, std::uint32_t version,
                                  std::uint32_t writer) {
    mNodes.push_back(Node{resource, version, writer});
    const auto node = std::uint32_t(mNodes.size() - 1);
    if (mResources[resource].latestNode == UINT32_MAX ||
        version > mNodes[mResources[resource].latestNode].version)
        mResources[resource].latestNode = node;
    return node;
}

std::string FrameGraph::nodeName(std::uint32_t node) const {
    const Node& n = mNodes[node];
    return "'" + mResources[n.resource].name + "' (version " + std::to_string(n.version) + ")";
}

std::uint32_t FrameGraph::addImported(const std::string& name, Kind kind,
                                      const gl::TextureDesc& desc, void* object) {
    ENGINE_CHECK(!mCompiled, "importing '" + name + "' after compile()");
    mResources.push_back(Resource{name, kind, desc, {}, true, object});
    return addNode(std::uint32_t(mResources.size() - 1), 0, UINT32_MAX);
}

std::uint32_t FrameGraph::addCreated(const std::string& name, Kind kind,
                                     const gl::TextureDesc& texture, const gl::BufferDesc& buffer) {
    ENGINE_CHECK(!mCompiled, "creating '" + name + "' after compile()");
    mResources.push_back(Resource{name, kind, texture, buffer, false, nullptr});
    return addNode(std::uint32_t(mResources.size() - 1), 0, UINT32_MAX);
}

TextureHandle FrameGraph::importTexture(const std::string& name, const gl::TextureDesc& desc,
                                        void* object) {
    return TextureHandle{addImported(name, Kind::Texture, desc, object)};
}

BufferHandle FrameGraph::importBuffer(const std::string& name, void* object) {
    return BufferHandle{addImported(name, Kind::Object, {}, object)};
}

BufferHandle FrameGraph::importBuffer(const std::string& name, gl::Buffer& buffer) {
    return BufferHandle{addImported(name, Kind::Buffer, {}, &buffer)};
}

TextureHandle Builder::create(const std::string& name, const gl::TextureDesc& desc) {
    const std::uint32_t node = mGraph.addCreated(name, FrameGraph::Kind::Texture, desc, {});
    mGraph.mPasses[mPass].creates.push_back(mGraph.mNodes[node].resource);
    return TextureHandle{node};
}

BufferHandle Builder::create(const std::string& name, const gl::BufferDesc& desc) {
    const std::uint32_t node = mGraph.addCreated(name, FrameGraph::Kind::Buffer, {}, desc);
    mGraph.mPasses[mPass].creates.push_back(mGraph.mNodes[node].resource);
    return BufferHandle{node};
}

std::uint32_t Builder::read(std::uint32_t node) {
    ENGINE_CHECK(node < mGraph.mNodes.size(), "read() of an invalid handle");
    mGraph.mPasses[mPass].reads.push_back(node);
    return node;
}

std::uint32_t Builder::readFinal(const std::string& key, std::function<std::uint32_t()> resolve) {
    ENGINE_CHECK(!mGraph.mCompiled, "readFinal() after compile()");
    mGraph.mNodes.push_back({UINT32_MAX, 0, UINT32_MAX, true});
    const auto node = std::uint32_t(mGraph.mNodes.size() - 1);
    mGraph.mFinalReads.push_back({node, mPass, key, std::move(resolve)});
    mGraph.mPasses[mPass].reads.push_back(node);
    return node;
}

std::uint32_t Builder::write(std::uint32_t node) {
    ENGINE_CHECK(node < mGraph.mNodes.size(), "write() of an invalid handle");
    ENGINE_CHECK(!mGraph.mNodes[node].final, "write() on a final read");
    const FrameGraph::Node previous = mGraph.mNodes[node];
    // A written version keeps the previous content (draws accumulate), so writing on top of a
    // written or imported version also reads it.
    if (previous.version > 0 || mGraph.mResources[previous.resource].imported)
        mGraph.mPasses[mPass].reads.push_back(node);
    const std::uint32_t next = mGraph.addNode(previous.resource, previous.version + 1, mPass);
    mGraph.mPasses[mPass].writes.push_back(next);
    return next;
}

TextureHandle Builder::read(TextureHandle handle) {
    return TextureHandle{read(handle.node)};
}

TextureHandle Builder::write(TextureHandle handle) {
    return TextureHandle{write(handle.node)};
}

BufferHandle Builder::read(BufferHandle handle) {
    return BufferHandle{read(handle.node)};
}

BufferHandle Builder::write(BufferHandle handle) {
    return BufferHandle{write(handle.node)};
}

void Builder::sideEffect() {
    mGraph.mPasses[mPass].sideEffect = true;
}

void* Resources::object(TextureHandle handle) const {
    ENGINE_CHECK(handle.valid() && handle.node < mGraph.mNodes.size(), "invalid texture handle");
    void* object = mGraph.mResources[mGraph.mNodes[handle.node].resource].object;
    ENGINE_CHECK(object != nullptr, "texture used by a pass that did not declare it");
    return object;
}

const gl::TextureDesc& Resources::desc(TextureHandle handle) const {
    return mGraph.mResources[mGraph.mNodes[handle.node].resource].desc;
}

void* Resources::object(BufferHandle handle) const {
    ENGINE_CHECK(handle.valid() && handle.node < mGraph.mNodes.size(), "invalid buffer handle");
    void* object = mGraph.mResources[mGraph.mNodes[handle.node].resource].object;
    ENGINE_CHECK(object != nullptr, "buffer used by a pass that did not declare it");
    return object;
}

gl::Buffer& Resources::buffer(BufferHandle handle) const {
    void* buffer = object(handle);
    const FrameGraph::Resource& r = mGraph.mResources[mGraph.mNodes[handle.node].resource];
    ENGINE_CHECK(r.kind == FrameGraph::Kind::Buffer,
                 "'" + r.name + "' is not a gl::Buffer (reach it through object())");
    return *static_cast<gl::Buffer*>(buffer);
}

core::Status FrameGraph::resolveFinalReads() {
    for (const FinalRead& read : mFinalReads) {
        const std::uint32_t target = read.resolve();
        if (target >= mNodes.size() || mNodes[target].final)
            return core::Error{"fg::FrameGraph::compile(): pass '" + mPasses[read.pass].name +
                               "' reads the final '" + read.key +
                               "', which the blackboard holds no version of"};
        mNodes[read.node] = mNodes[target];
        mNodes[read.node].final = true;
    }
    return {};
}

core::Status FrameGraph::checkVersions() const {
    const std::string where = "fg::FrameGraph::compile(): ";
    for (const Pass& pass : mPasses) {
        for (std::uint32_t node : pass.reads) {
            const Node& n = mNodes[node];
            if (n.version == 0 && !mResources[n.resource].imported)
                return core::Error{where + "pass '" + pass.name + "' reads " + nodeName(node) +
                                   ", which no pass writes"};
        }
    }
    for (std::uint32_t later = 0; later < mNodes.size(); ++later)
        for (std::uint32_t earlier = 0; earlier < later; ++earlier) {
            const Node& n = mNodes[later];
            if (n.final || mNodes[earlier].final)
                continue; // another name for a version
            if (mNodes[earlier].resource == n.resource && mNodes[earlier].version == n.version)
                return core::Error{where + "pass '" + mPasses[n.writer].name +
                                   "' writes an outdated version of '" +
                                   mResources[n.resource].name + "' (version " +
                                   std::to_string(n.version - 1) + " was already written on)"};
        }
    return {};
}

FrameGraph::Edges FrameGraph::dependencyEdges() const {
    // Writer of a read version -> reader; readers of a version -> the writer of the next
    // version. Only data edges keep a pass alive (`consumes`); both order.
    const auto passCount = std::uint32_t(mPasses.size());
    Edges edges{std::vector<std::vector<std::uint32_t>>(passCount),
                std::vector<std::vector<std::uint32_t>>(passCount)};
    auto edge = [&](std::uint32_t from, std::uint32_t to, bool data) {
        if (from == to || from == UINT32_MAX)
            return;
        edges.successors[from].push_back(to);
        if (data)
            edges.consumes[to].push_back(from);
    };
    for (std::uint32_t p = 0; p < passCount; ++p) {
        for (std::uint32_t node : mPasses[p].reads) {
            edge(mNodes[node].writer, p, true);
            for (std::uint32_t q = 0; q < passCount; ++q) // readers before the next writer
                for (std::uint32_t w : mPasses[q].writes)
                    if (mNodes[w].resource == mNodes[node].resource &&
                        mNodes[w].version == mNodes[node].version + 1)
                        edge(p, q, false);
        }
    }
    return edges;
}

std::vector<bool> FrameGraph::neededPasses(const Edges& edges) const {
    const auto passCount = std::uint32_t(mPasses.size());
    std::vector<bool> needed(passCount, false);
    std::vector<std::uint32_t> stack;
    for (std::uint32_t p = 0; p < passCount; ++p) {
        bool root = mPasses[p].sideEffect;
        for (std::uint32_t w : mPasses[p].writes)
            root = root || mResources[mNodes[w].resource].imported;
        if (root) {
            needed[p] = true;
            stack.push_back(p);
        }
    }
    while (!stack.empty()) {
        const std::uint32_t p = stack.back();
        stack.pop_back();
        for (std::uint32_t q : edges.consumes[p])
            if (!needed[q]) {
                needed[q] = true;
                stack.push_back(q);
            }
    }
    return needed;
}

core::Status FrameGraph::orderPasses(const Edges& edges, const std::vector<bool>& needed) {
    // Kahn's, lowest declaration index first. Edges run from earlier passes to later ones,
    // except a final read's, which may run back to a pass recorded before its writer: a cycle
    // through one is reported, never left to hang.
    const auto passCount = std::uint32_t(mPasses.size());
    std::vector<int> inDegree(passCount, 0);
    for (std::uint32_t p = 0; p < passCount; ++p)
        if (needed[p])
            for (std::uint32_t q : edges.successors[p])
                if (needed[q])
                    ++inDegree[q];
    mOrder.clear();
    std::vector<bool> done(passCount, false);
    for (;;) {
        std::uint32_t next = UINT32_MAX;
        for (std::uint32_t p = 0; p < passCount && next == UINT32_MAX; ++p)
            if (needed[p] && !done[p] && inDegree[p] == 0)
                next = p;
        if (next == UINT32_MAX)
            break;
        done[next] = true;
        mOrder.push_back(next);
        for (std::uint32_t q : edges.successors[next])
            if (needed[q])
                --inDegree[q];
    }
    std::string cycle;
    for (std::uint32_t p = 0; p < passCount; ++p)
        if (needed[p] && !done[p])
            cycle += (cycle.empty() ? "'" : ", '") + mPasses[p].name + "'";
    if (!cycle.empty())
        return core::Error{"fg::FrameGraph::compile(): the passes " + cycle +
                           " depend on each other in a cycle"};
    return {};
}

void FrameGraph::measureLifetimes() {
    for (Resource& r : mResources)
        r.firstUse = r.lastUse = -1;
    for (std::size_t i = 0; i < mOrder.size(); ++i) {
        const Pass& pass = mPasses[mOrder[i]];
        auto touch = [&](std::uint32_t resource) {
            Resource& r = mResources[resource];
            if (r.firstUse < 0)
                r.firstUse = int(i);
            r.lastUse = int(i);
        };
        for (std::uint32_t r : pass.creates)
            touch(r);
        for (std::uint32_t n : pass.reads)
            touch(mNodes[n].resource);
        for (std::uint32_t n : pass.writes)
            touch(mNodes[n].resource);
    }
}

core::Status FrameGraph::compile() {
    if (auto resolved = resolveFinalReads(); !resolved)
        return resolved;
    if (auto valid = checkVersions(); !valid)
        return valid;
    const Edges edges = dependencyEdges();
    const std::vector<bool> needed = neededPasses(edges);
    for (std::size_t p = 0; p < mPasses.size(); ++p)
        mPasses[p].culled = !needed[p];
    if (auto ordered = orderPasses(edges, needed); !ordered)
        return ordered;
    measureLifetimes();
    mCompiled = true;
    return {};
}

core::Result<std::vector<PassTiming>> FrameGraph::execute(gl::Context& context,
                                                          PassObserver* observer) {
    ENGINE_CHECK(mCompiled, "execute() before a successful compile()");
    std::vector<PassTiming> timings;
    const Resources resources(*this);
    for (std::size_t i = 0; i < mOrder.size(); ++i) {
        for (Resource& r : mResources)
            if (!r.imported && r.firstUse == int(i))
                r.object = r.kind == Kind::Buffer ? mBuffers.acquire(r.bufferDesc)
                                                  : mTextures.acquire(r.desc);
        Pass& pass = mPasses[mOrder[i]];
        if (observer)
            observer->beginPass(pass.name);
        const auto start = std::chrono::steady_clock::now();
        const core::Status status =
            pass.execute ? pass.execute(resources, context) : core::Status{};
        const auto end = std::chrono::steady_clock::now();
        if (observer)
            observer->endPass(pass.name);
        timings.push_back(
            {pass.name, std::chrono::duration<double, std::milli>(end - start).count()});
        for (Resource& r : mResources)
            if (!r.imported && r.object && (r.lastUse == int(i) || !status)) {
                if (r.kind == Kind::Buffer)
                    mBuffers.release(r.object);
                else
                    mTextures.release(r.object);
                r.object = nullptr;
            }
        if (!status)
            return core::Error{"fg::FrameGraph::execute(): pass '" + pass.name +
                               "': " + status.error().message};
    }
    return timings;
}

std::vector<std::string> FrameGraph::executionOrder() const {
    std::vector<std::string> names;
    for (std::uint32_t p : mOrder)
        names.push_back(mPasses[p].name);
    return names;
}

std::string FrameGraph::dump() const {
    std::ostringstream out;
    out << "frame graph: " << mOrder.size() << " of " << mPasses.size() << " passes execute\n";
    std::vector<std::uint32_t> listed = mOrder;
    for (std::uint32_t p = 0; p < mPasses.size(); ++p)
        if (mPasses[p].culled)
            listed.push_back(p);
    for (std::uint32_t p : listed) {
        const Pass& pass = mPasses[p];
        out << (pass.culled ? "  [culled] " : "  ") << pass.name << "\n";
        for (std::uint32_t r : pass.creates) {
            const Resource& created = mResources[r];
            out << "      creates '" << created.name << "' ";
            if (created.kind == Kind::Buffer)
                out << created.bufferDesc.size << " bytes\n";
            else
                out << created.desc.size.x << "x" << created.desc.size.y << "\n";
        }
        for (std::uint32_t n : pass.reads)
            out << "      reads   " << nodeName(n) << "\n";
        for (std::uint32_t n : pass.writes)
            out << "      writes  " << nodeName(n) << "\n";
    }
    out << "transients:\n";
    for (const Resource& r : mResources)
        if (!r.imported)
            out << "  '" << r.name << "' "
                << (r.firstUse < 0
                        ? std::string("unused")
                        : "passes " + std::to_string(r.firstUse) + ".." + std::to_string(r.lastUse))
                << "\n";
    return out.str();
}

} // namespace fg

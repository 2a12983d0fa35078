// Bounds-checked accessor decoding. Every offset is checked against its buffer view and buffer
// before a byte is read, so a malformed file can only produce an error.
#include "AccessorReader.h"

#include "LoadError.h"
#include "engine/core/Limits.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace asset::detail {

int componentSize(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return 4;
    default:
        return 0;
    }
}

int typeComponents(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return 1;
    case TINYGLTF_TYPE_VEC2:
        return 2;
    case TINYGLTF_TYPE_VEC3:
        return 3;
    case TINYGLTF_TYPE_VEC4:
    case TINYGLTF_TYPE_MAT2:
        return 4;
    case TINYGLTF_TYPE_MAT3:
        return 9;
    case TINYGLTF_TYPE_MAT4:
        return 16;
    default:
        return 0;
    }
}

double normalizedScale(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
        return 127.0;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return 255.0;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
        return 32767.0;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return 65535.0;
    default:
        return 1.0;
    }
}

namespace {

/** Reads one component at `p`, normalised per glTF §3.11 when `normalized`. */
double readComponent(const unsigned char* p, int componentType, bool normalized) {
    // a signed type's most negative value decodes to -1 too
    const auto decode = [&](double v) {
        return normalized ? std::max(v / normalizedScale(componentType), -1.0) : v;
    };
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
        return decode(double(std::int8_t(*p)));
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return decode(double(*p));
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t v;
        std::memcpy(&v, p, 2);
        return decode(double(v));
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return decode(double(v));
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
        std::int32_t v;
        std::memcpy(&v, p, 4);
        return double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return double(v);
    }
    default: {
        float v;
        std::memcpy(&v, p, 4);
        return double(v);
    }
    }
}

/** Where `count` elements of `elementSize` bytes, `stride` apart, start in their buffer. */
struct Span {
    const unsigned char* data = nullptr;
    std::size_t stride = 0;
};

/** Where `count` elements (`elementBytes` each) start at `byteOffset` within bufferView
 *  `viewIndex`, and their stride (the view's where `allowStride`), checked against the view
 *  and its buffer. `name` and `role` name the accessor (and its part) in errors. */
Span locate(const tinygltf::Model& model, const std::string& name, int viewIndex,
            std::size_t byteOffset, std::size_t count, std::size_t elementBytes, bool allowStride,
            const std::string& role) {
    if (viewIndex < 0 || std::size_t(viewIndex) >= model.bufferViews.size())
        fail(name + " " + role + "references bufferView " + std::to_string(viewIndex) +
             ", file has " + std::to_string(model.bufferViews.size()) + " bufferViews");
    const tinygltf::BufferView& view = model.bufferViews[std::size_t(viewIndex)];
    const std::string viewName = "bufferView " + std::to_string(viewIndex);
    if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size())
        fail(viewName + " references buffer " + std::to_string(view.buffer) + ", file has " +
             std::to_string(model.buffers.size()) + " buffers");
    const std::size_t bufferSize = model.buffers[std::size_t(view.buffer)].data.size();
    if (view.byteOffset > bufferSize || view.byteLength > bufferSize - view.byteOffset)
        fail(viewName + " (offset " + std::to_string(view.byteOffset) + ", length " +
             std::to_string(view.byteLength) + ") runs past the end of buffer " +
             std::to_string(view.buffer) + " (" + std::to_string(bufferSize) + " bytes)");
    std::size_t stride = elementBytes;
    if (allowStride && view.byteStride != 0) {
        if (view.byteStride < elementBytes)
            fail(viewName + " byteStride " + std::to_string(view.byteStride) + " is smaller than " +
                 name + "'s element size " + std::to_string(elementBytes));
        stride = view.byteStride;
    }
    const std::size_t needed = count == 0 ? 0 : (count - 1) * stride + elementBytes;
    if (byteOffset > view.byteLength || needed > view.byteLength - byteOffset)
        fail(name + " " + role + "(offset " + std::to_string(byteOffset) + ", " +
             std::to_string(count) + " elements of " + std::to_string(elementBytes) +
             " bytes, stride " + std::to_string(stride) + ") runs past the end of " + viewName +
             " (" + std::to_string(view.byteLength) + " bytes)");
    const unsigned char* base =
        model.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset + byteOffset;
    return Span{base, stride};
}

/** Accessor `a`'s sparse values written over `out` (`components` a element), its indices
 *  checked: in range, strictly increasing. */
void applySparse(const tinygltf::Model& model, const tinygltf::Accessor& a, const std::string& name,
                 int components, std::vector<double>& out) {
    const int size = componentSize(a.componentType);
    const std::size_t elementSize = std::size_t(size) * std::size_t(components);
    const std::string sparseName = name + " sparse";
    if (a.sparse.count < 1 || std::size_t(a.sparse.count) > a.count)
        fail(sparseName + " count " + std::to_string(a.sparse.count) + " is not within 1.." +
             std::to_string(a.count));
    const std::size_t n = std::size_t(a.sparse.count);
    const int indexType = a.sparse.indices.componentType;
    if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(sparseName + " indices have invalid componentType " + std::to_string(indexType));
    if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
        fail(sparseName + " has a negative byteOffset");
    const Span indices =
        locate(model, name, a.sparse.indices.bufferView, std::size_t(a.sparse.indices.byteOffset),
               n, std::size_t(componentSize(indexType)), false, "sparse indices ");
    const Span values =
        locate(model, name, a.sparse.values.bufferView, std::size_t(a.sparse.values.byteOffset), n,
               elementSize, false, "sparse values ");
    double previous = -1.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double target = readComponent(indices.data + i * indices.stride, indexType, false);
        if (target <= previous || target >= double(a.count))
            fail(sparseName + " index " + std::to_string(i) + " (" +
                 std::to_string(std::uint64_t(target)) +
                 ") is out of range or not strictly increasing");
        previous = target;
        for (int c = 0; c < components; ++c)
            out[std::size_t(target) * std::size_t(components) + std::size_t(c)] =
                readComponent(values.data + i * values.stride + std::size_t(c * size),
                              a.componentType, a.normalized);
    }
}

} // namespace

AccessorReader::AccessorReader(const tinygltf::Model& model, std::uint64_t fileBytes)
    : mModel(model), mZeroFillBudget((std::uint64_t(64) << 20) + 256 * fileBytes) {}

const tinygltf::Accessor& AccessorReader::accessor(int index, const std::string& what) const {
    if (index < 0 || std::size_t(index) >= mModel.accessors.size())
        fail(what + " references accessor " + std::to_string(index) + ", file has " +
             std::to_string(mModel.accessors.size()) + " accessors");
    return mModel.accessors[std::size_t(index)];
}

std::vector<double> AccessorReader::decode(int index, int components, bool allowFloat,
                                           bool allowSigned, const std::string& what) const {
    const tinygltf::Accessor& a = accessor(index, what);
    const std::string name = what + ": accessor " + std::to_string(index);
    const int size = componentSize(a.componentType);
    if (size == 0)
        fail(name + " has invalid componentType " + std::to_string(a.componentType));
    if (typeComponents(a.type) != components)
        fail(name + " has " + std::to_string(typeComponents(a.type)) +
             " components per element, expected " + std::to_string(components));
    if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && !allowFloat)
        fail(name + " has FLOAT components, expected an unsigned integer type");
    const bool isSigned = a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                          a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
                          a.componentType == TINYGLTF_COMPONENT_TYPE_INT;
    if (isSigned && !allowSigned)
        fail(name + " has signed components, expected an unsigned integer type");
    if (a.count > core::limits::kMaxVerticesPerPrimitive)
        fail(name + " count " + std::to_string(a.count) + " is over the limit of " +
             std::to_string(core::limits::kMaxVerticesPerPrimitive));

    const std::size_t elementSize = std::size_t(size) * std::size_t(components);
    const std::size_t total = a.count * std::size_t(components);

    std::vector<double> out;
    if (a.bufferView >= 0) {
        const Span span =
            locate(mModel, name, a.bufferView, a.byteOffset, a.count, elementSize, true, "");
        out.resize(total);
        for (std::size_t i = 0; i < a.count; ++i)
            for (int c = 0; c < components; ++c)
                out[i * std::size_t(components) + std::size_t(c)] =
                    readComponent(span.data + i * span.stride + std::size_t(c * size),
                                  a.componentType, a.normalized);
    } else {
        // No buffer view: zeros (to be replaced by sparse values). Its size is not backed by
        // file bytes, so it gets a budget relative to the file's size.
        if (std::uint64_t(total) * sizeof(float) > mZeroFillBudget)
            fail(name + " has no bufferView and " + std::to_string(a.count) +
                 " elements: more memory than a file of this size can justify");
        out.assign(total, 0.0);
    }

    if (a.sparse.isSparse)
        applySparse(mModel, a, name, components, out);

    for (std::size_t i = 0; i < out.size(); ++i)
        if (!std::isfinite(out[i]))
            fail(name + " element " + std::to_string(i / std::size_t(components)) +
                 " is not finite");
    return out;
}

std::vector<float> AccessorReader::readFloats(int index, int components,
                                              const std::string& what) const {
    const std::vector<double> values = decode(index, components, true, true, what);
    std::vector<float> out(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (std::abs(values[i]) > double(std::numeric_limits<float>::max()))
            fail(what + ": accessor " + std::to_string(index) + " element " +
                 std::to_string(i / std::size_t(components)) + " overflows a float");
        out[i] = float(values[i]);
    }
    return out;
}

std::vector<std::uint32_t> AccessorReader::readUints(int index, int components,
                                                     const std::string& what) const {
    const std::vector<double> values = decode(index, components, false, false, what);
    std::vector<std::uint32_t> out(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        out[i] = std::uint32_t(values[i]);
    return out;
}

} // namespace asset::detail

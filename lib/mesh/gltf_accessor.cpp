// glTF accessors (glTF 2.0, 3.6.2), bounds-checked against their buffers: dense elements read
// through a buffer view, zeros where there is none, then a sparse accessor's substitutions.
#include "mesh/gltf_parts.h"

#include "base/error.h"

#include <algorithm>
#include <cstring>

namespace limn::gltf {

namespace {

// An accessor without a buffer view costs memory, not input bytes: its count is capped.
constexpr size_t kMaxZeroElements = size_t(1) << 26;

double component(const uint8_t* p, int type, bool normalized, const std::string& what) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f;
        std::memcpy(&f, p, 4);
        return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        auto v = static_cast<int8_t>(p[0]);
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    default: throwBadInput(what + ": unsupported component type");
    }
}

// The bytes of `count` elements of `elementSize` bytes, `stride` apart, starting `offset` bytes
// into buffer view `viewIndex`; refused when they run past the view or its buffer.
const uint8_t* viewBytes(const tinygltf::Model& model, int viewIndex, size_t offset, size_t count,
                         size_t elementSize, size_t& stride, const std::string& what) {
    if (viewIndex < 0 || viewIndex >= static_cast<int>(model.bufferViews.size()))
        throwBadInput(what + ": buffer view " + std::to_string(viewIndex) + " does not exist");
    const auto& view = model.bufferViews[viewIndex];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()))
        throwBadInput(what + ": buffer view refers to a missing buffer");
    const auto& buffer = model.buffers[view.buffer].data;
    if (stride == 0) stride = view.byteStride ? view.byteStride : elementSize;
    if (stride < elementSize) throwBadInput(what + ": byte stride smaller than an element");
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
        throwBadInput(what + ": buffer view runs past its buffer");
    if (offset > view.byteLength) throwBadInput(what + ": accessor offset runs past its buffer view");
    const size_t avail = view.byteLength - offset;
    if (count > 0 && (avail < elementSize || count - 1 > (avail - elementSize) / stride))
        throwBadInput(what + ": " + std::to_string(count) + " elements run past the end of the buffer view");
    return buffer.data() + view.byteOffset + offset;
}

} // namespace

AccessorData readAccessor(const tinygltf::Model& model, int index, const std::string& what) {
    if (index < 0 || index >= static_cast<int>(model.accessors.size()))
        throwBadInput(what + ": accessor " + std::to_string(index) + " does not exist");
    const auto& a = model.accessors[index];
    AccessorData out;
    out.components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
    const int componentSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
    if (out.components <= 0 || out.components > 4 || componentSize <= 0)
        throwBadInput(what + ": unsupported accessor type");
    out.count = a.count;
    const size_t elementSize = size_t(out.components) * size_t(componentSize);
    const size_t n = size_t(out.components);
    if (a.bufferView >= 0) {
        size_t stride = 0;
        const uint8_t* base = viewBytes(model, a.bufferView, a.byteOffset, a.count, elementSize, stride, what);
        out.values.resize(a.count * n);
        for (size_t i = 0; i < a.count; ++i)
            for (size_t c = 0; c < n; ++c)
                out.values[i * n + c] = component(base + i * stride + c * size_t(componentSize),
                                                  a.componentType, a.normalized, what);
    } else { // glTF 2.0, 3.6.2.3: without a buffer view the elements are zeros
        if (a.count > kMaxZeroElements)
            throwBadInput(what + ": accessor " + std::to_string(index) + " has " + std::to_string(a.count) +
                          " elements and no buffer view, more than limn reads (" +
                          std::to_string(kMaxZeroElements) + ")");
        out.values.assign(a.count * n, 0.0);
    }
    if (!a.sparse.isSparse) return out;
    const auto& s = a.sparse;
    if (s.count < 0 || size_t(s.count) > a.count)
        throwBadInput(what + ": sparse count " + std::to_string(s.count) + " is more than the accessor's " +
                      std::to_string(a.count) + " elements");
    const int indexType = s.indices.componentType;
    if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        throwBadInput(what + ": sparse indices must be unsigned integers");
    const size_t indexSize = size_t(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(indexType)));
    size_t indexStride = indexSize, valueStride = elementSize; // sparse data is tightly packed
    const uint8_t* indices = viewBytes(model, s.indices.bufferView, size_t(std::max(0, s.indices.byteOffset)),
                                       size_t(s.count), indexSize, indexStride, what + " sparse indices");
    const uint8_t* values = viewBytes(model, s.values.bufferView, size_t(std::max(0, s.values.byteOffset)),
                                      size_t(s.count), elementSize, valueStride, what + " sparse values");
    if (indexStride != indexSize || valueStride != elementSize)
        throwBadInput(what + ": sparse data must not have a byte stride");
    int64_t previous = -1;
    for (size_t k = 0; k < size_t(s.count); ++k) {
        const auto target = static_cast<int64_t>(component(indices + k * indexSize, indexType, false, what));
        if (target <= previous || uint64_t(target) >= a.count)
            throwBadInput(what + ": sparse index " + std::to_string(target) +
                          " is out of range or not increasing (glTF 2.0, 3.6.2.3)");
        previous = target;
        for (size_t c = 0; c < n; ++c)
            out.values[size_t(target) * n + c] =
                component(values + k * elementSize + c * size_t(componentSize), a.componentType, a.normalized, what);
    }
    return out;
}

std::vector<uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& what) {
    if (index >= 0 && index < static_cast<int>(model.accessors.size())) {
        if (model.accessors[index].normalized) throwBadInput(what + ": indices must not be normalized");
        const int type = model.accessors[index].componentType;
        if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            throwBadInput(what + ": indices must be unsigned integers");
    }
    const AccessorData data = readAccessor(model, index, what);
    if (data.components != 1) throwBadInput(what + ": indices must be scalars");
    std::vector<uint32_t> out(data.count);
    for (size_t i = 0; i < data.count; ++i) out[i] = static_cast<uint32_t>(data.values[i]);
    return out;
}

} // namespace limn::gltf

// Private to the asset module: bounds-checked reading of glTF accessors (any component type,
// normalized integers, byte strides, sparse substitution) into flat engine arrays.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

namespace asset::detail {

/** Bytes of one component of a glTF componentType (5120..5126), 0 for another value. */
int componentSize(int componentType);

/** Components of a glTF accessor type (TINYGLTF_TYPE_SCALAR..MAT4), 0 for another value. */
int typeComponents(int type);
/** The largest value of a normalized integer component type, which glTF's decoding divides by
 *  (a signed one clamped to -1 below): 127, 255, 32767, 65535; 1 for the others. */
double normalizedScale(int componentType);

class AccessorReader {
public:
    /** `fileBytes` sizes the budget for accessors that have no buffer view (zero-filled, maybe
     *  sparse): their decoded size must stay within what a file of that size could justify. */
    AccessorReader(const tinygltf::Model& model, std::uint64_t fileBytes);

    /** Reads accessor `index` as `components` floats per element, normalising integer types
     *  when the accessor says so. `what` names the use in errors ("mesh 0 primitive 1
     *  POSITION"). Rejects a wrong type, out-of-range views or buffers, non-finite values. */
    std::vector<float> readFloats(int index, int components, const std::string& what) const;

    /** Reads an unsigned-integer accessor (UNSIGNED_BYTE/SHORT/INT) of `components` per element. */
    std::vector<std::uint32_t> readUints(int index, int components, const std::string& what) const;

private:
    const tinygltf::Accessor& accessor(int index, const std::string& what) const;
    /** Decodes every component of the accessor as double (sparse applied), checked. */
    std::vector<double> decode(int index, int components, bool allowFloat, bool allowSigned,
                               const std::string& what) const;

    const tinygltf::Model& mModel;
    std::uint64_t mZeroFillBudget;
};

} // namespace asset::detail

// PLY output of deformed vertices (x y z nx ny nz as float), binary little-endian or ASCII.
#pragma once

#include "engine/deform/CpuDeformer.h"

#include <string>
#include <vector>

namespace inspect {

/** One block of vertices with a label written as a PLY comment ("node 3 mesh 0 primitive 1"). */
struct PlyBlock {
    std::string label;
    const deform::DeformedPrimitive* vertices = nullptr;
};

/** The whole PLY file as bytes: header (with one comment per block giving its first vertex
 *  and count), then every block's vertices in order. */
std::string makePly(const std::vector<PlyBlock>& blocks, const std::string& comment, bool ascii);

} // namespace inspect

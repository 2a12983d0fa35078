// PLY encoding for glass-inspect --out.
#include "Ply.h"

#include <bit>
#include <cstring>
#include <sstream>

namespace inspect {

std::string makePly(const std::vector<PlyBlock>& blocks, const std::string& comment, bool ascii) {
    static_assert(std::endian::native == std::endian::little, "binary PLY assumes little-endian");
    std::size_t total = 0;
    for (const PlyBlock& block : blocks)
        total += block.vertices->positions.size();
    std::ostringstream out;
    out << "ply\nformat " << (ascii ? "ascii" : "binary_little_endian") << " 1.0\n";
    out << "comment " << comment << "\n";
    std::size_t first = 0;
    for (const PlyBlock& block : blocks) {
        const std::size_t count = block.vertices->positions.size();
        out << "comment " << block.label << " first " << first << " count " << count << "\n";
        first += count;
    }
    out << "element vertex " << total << "\n";
    for (const char* name : {"x", "y", "z", "nx", "ny", "nz"})
        out << "property float " << name << "\n";
    out << "end_header\n";
    out.precision(9);
    for (const PlyBlock& block : blocks) {
        const auto& p = block.vertices->positions;
        const auto& n = block.vertices->normals;
        for (std::size_t v = 0; v < p.size(); ++v) {
            const float values[6] = {float(p[v].x), float(p[v].y), float(p[v].z),
                                     float(n[v].x), float(n[v].y), float(n[v].z)};
            if (ascii) {
                out << values[0] << ' ' << values[1] << ' ' << values[2] << ' ' << values[3] << ' '
                    << values[4] << ' ' << values[5] << '\n';
            } else {
                out.write(reinterpret_cast<const char*>(values), sizeof values);
            }
        }
    }
    return out.str();
}

} // namespace inspect

// The binary seeds of the compressed-data fuzz targets, made with the real encoders: Draco
// streams (sequential and edgebreaker, lossless and quantised) of a 3x3 grid with the attributes
// FuzzDraco.cpp declares, meshopt streams of every mode FuzzMeshopt.cpp reads, each behind the
// header bytes those targets take, and two WebP images. Build target fuzz_make_seeds.
#include <cstring>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <fstream>
#include <meshoptimizer.h>
#include <string>
#include <vector>
#include <webp/encode.h>
static void write(const char* path, const std::vector<unsigned char>& b) {
    std::ofstream(path, std::ios::binary).write((const char*)b.data(), b.size());
}
/** Writes the seeds of fuzz_draco, fuzz_meshopt and the WebP seeds of fuzz_image into DIR. */
int main(int argc, char** argv) {
    if (argc != 2)
        return 2;
    const std::string dir = argv[1];
    // a 3x3 grid of vertices, 8 triangles
    const int V = 9;
    std::vector<float> pos, nrm, uv, wgt;
    std::vector<unsigned char> jnt;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            pos.insert(pos.end(), {float(x), float(y), 0});
            nrm.insert(nrm.end(), {0, 0, 1});
            uv.insert(uv.end(), {x / 2.f, y / 2.f});
            jnt.insert(jnt.end(), {0, 1, 0, 0});
            wgt.insert(wgt.end(), {1 - x / 2.f, x / 2.f, 0, 0});
        }
    std::vector<unsigned> idx;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) {
            unsigned a = y * 3 + x;
            idx.insert(idx.end(), {a, a + 1, a + 4, a, a + 4, a + 3});
        }
    for (int method : {draco::MESH_SEQUENTIAL_ENCODING, draco::MESH_EDGEBREAKER_ENCODING})
        for (int q : {0, 1}) {
            draco::Mesh mesh;
            mesh.set_num_points(V);
            for (size_t f = 0; f < idx.size() / 3; ++f)
                mesh.AddFace({draco::PointIndex(idx[f * 3]), draco::PointIndex(idx[f * 3 + 1]),
                              draco::PointIndex(idx[f * 3 + 2])});
            auto add = [&](draco::GeometryAttribute::Type t, int n, draco::DataType dt,
                           const void* data, int size) {
                draco::GeometryAttribute ga;
                ga.Init(t, nullptr, n, dt, false, size * n, 0);
                int id = mesh.AddAttribute(ga, true, V);
                for (int v = 0; v < V; ++v)
                    mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(v),
                                                          (const char*)data + v * size * n);
            };
            add(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32, pos.data(), 4);
            add(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32, nrm.data(), 4);
            add(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32, uv.data(), 4);
            add(draco::GeometryAttribute::GENERIC, 4, draco::DT_UINT8, jnt.data(), 1);
            add(draco::GeometryAttribute::GENERIC, 4, draco::DT_FLOAT32, wgt.data(), 4);
            draco::Encoder enc;
            enc.SetEncodingMethod(method);
            if (q) {
                enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
                enc.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
                enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
                enc.SetAttributeQuantization(draco::GeometryAttribute::GENERIC, 12);
            }
            draco::EncoderBuffer buf;
            if (!enc.EncodeMeshToBuffer(mesh, &buf).ok())
                return 1;
            std::vector<unsigned char> out(8);
            unsigned v = V, t = idx.size() / 3;
            std::memcpy(out.data(), &v, 4);
            std::memcpy(out.data() + 4, &t, 4);
            out.insert(out.end(), buf.data(), buf.data() + buf.size());
            std::string name =
                std::string((dir + "/draco_").c_str()) +
                (method == draco::MESH_SEQUENTIAL_ENCODING ? "sequential" : "edgebreaker") +
                (q ? "_quantized" : "");
            write(name.c_str(), out);
        }
    // meshopt: attributes (stride 12, 16 and 8 with octahedral), triangles, indices
    auto mo = [&](unsigned char selector, const std::vector<unsigned char>& enc, unsigned count,
                  const char* name) {
        std::vector<unsigned char> out(5);
        out[0] = selector;
        std::memcpy(out.data() + 1, &count, 4);
        out.insert(out.end(), enc.begin(), enc.end());
        write(name, out);
    };
    {
        std::vector<unsigned char> e(meshopt_encodeVertexBufferBound(V, 12));
        e.resize(meshopt_encodeVertexBuffer(e.data(), e.size(), pos.data(), V, 12));
        mo(0 | (2 << 4), e, V, (dir + "/meshopt_attributes12").c_str());
    }
    {
        std::vector<short> oct(V * 4);
        for (int v = 0; v < V; ++v) {
            oct[v * 4] = 0;
            oct[v * 4 + 1] = 0;
            oct[v * 4 + 2] = 32767;
            oct[v * 4 + 3] = 0;
        }
        std::vector<unsigned char> e(meshopt_encodeVertexBufferBound(V, 8));
        e.resize(meshopt_encodeVertexBuffer(e.data(), e.size(), oct.data(), V, 8));
        mo(0 | (1 << 2) | (1 << 4), e, V, (dir + "/meshopt_octahedral8").c_str());
    }
    {
        std::vector<unsigned char> e(meshopt_encodeIndexBufferBound(idx.size(), V));
        e.resize(meshopt_encodeIndexBuffer(e.data(), e.size(), idx.data(), idx.size()));
        mo(1 | 64, e, idx.size(), (dir + "/meshopt_triangles").c_str());
    }
    {
        std::vector<unsigned char> e(meshopt_encodeIndexSequenceBound(idx.size(), V));
        e.resize(meshopt_encodeIndexSequence(e.data(), e.size(), idx.data(), idx.size()));
        mo(2, e, idx.size(), (dir + "/meshopt_indices").c_str());
    }
    // a 4x4 lossy and a lossless WebP
    std::vector<unsigned char> rgba(64);
    for (int i = 0; i < 64; ++i)
        rgba[i] = (unsigned char)(i * 4);
    uint8_t* out = nullptr;
    size_t n = WebPEncodeLosslessRGBA(rgba.data(), 4, 4, 16, &out);
    write((dir + "/tiny_lossless.webp").c_str(), std::vector<unsigned char>(out, out + n));
    WebPFree(out);
    n = WebPEncodeRGBA(rgba.data(), 4, 4, 16, 80, &out);
    write((dir + "/tiny_lossy.webp").c_str(), std::vector<unsigned char>(out, out + n));
    WebPFree(out);
}

// PLY reader: the three encodings, property aliases, polygon handling and hostile headers.
#include "scene/ply_reader.h"

#include <gtest/gtest.h>

#include <bit>
#include <chrono>
#include <cstring>
#include <fstream>

#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

std::string TempPath(const std::string &name) { return ::testing::TempDir() + "ply_" + name; }

// Appends binary values in a chosen byte order.
struct Bytes {
    bool bigEndian = false;
    std::string data;
    template <typename T>
    Bytes &Put(T v) {
        char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        if (bigEndian == (std::endian::native == std::endian::little))
            for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
        data.append(b, sizeof(T));
        return *this;
    }
};

std::string ExpectError(const std::string &path, Diagnostics &diag) {
    try {
        ReadPlyFile(path, diag);
    } catch (const SceneError &e) {
        return e.what();
    }
    ADD_FAILURE() << "no SceneError for " << path;
    return "";
}

TEST(PlyReader, AsciiTriangleAndQuadWithNormalsAndUV) {
    std::string path = WriteScratchFile("ply_ascii.ply",
                                        "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\n"
                                        "element vertex 4\r\n"
                                        "property float x\nproperty float y\nproperty float z\n"
                                        "property float nx\nproperty float ny\nproperty float nz\n"
                                        "property float u\nproperty float v\n"
                                        "element face 2\nproperty list uchar int vertex_indices\n"
                                        "end_header\n"
                                        "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 0 0 1 1 1\n"
                                        "0 1 0 0 0 1 0 1\n"
                                        "3 0 1 2\n4 0 1 2 3\n");
    Diagnostics diag;
    PlyMesh m = ReadPlyFile(path, diag);
    ASSERT_EQ(m.P.size(), 4u);
    EXPECT_EQ(m.P[2], Vec3f(1, 1, 0));
    ASSERT_EQ(m.N.size(), 4u);
    EXPECT_EQ(m.N[3], Vec3f(0, 0, 1));
    ASSERT_EQ(m.uv.size(), 4u);
    EXPECT_EQ(m.uv[2], Vec2f(1, 1));
    EXPECT_EQ(m.indices, (std::vector<int>{0, 1, 2, 0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(diag.Count(), 0u);
}

// Little-endian binary with "s t" texture coordinates, a skipped colour property and an
// unrelated element between vertices and faces that must be skipped byte-exactly.
TEST(PlyReader, BinaryLittleEndianSkipsOtherElements) {
    Bytes b;
    for (int i = 0; i < 3; ++i)
        b.Put<float>(float(i))
            .Put<float>(2.f * i)
            .Put<float>(-1.f)
            .Put<uint8_t>(200)
            .Put<float>(0.25f * i)
            .Put<float>(0.5f);
    // element material 2: uchar id, list uchar float weights
    b.Put<uint8_t>(7).Put<uint8_t>(2).Put<float>(1).Put<float>(2);
    b.Put<uint8_t>(8).Put<uint8_t>(0);
    // face: int flags, list uchar uint vertex_index
    b.Put<int32_t>(42).Put<uint8_t>(3).Put<uint32_t>(2).Put<uint32_t>(1).Put<uint32_t>(0);
    // edge element after faces
    b.Put<int32_t>(0).Put<int32_t>(1);
    std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
        "property float32 x\nproperty float32 y\nproperty float32 z\nproperty uchar red\n"
        "property float s\nproperty float t\n"
        "element material 2\nproperty uchar id\nproperty list uchar float weights\n"
        "element face 1\nproperty int flags\nproperty list uint8 uint vertex_index\n"
        "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
    Diagnostics diag;
    PlyMesh m = ReadPlyFile(WriteScratchFile("ply_le.ply", header + b.data), diag);
    ASSERT_EQ(m.P.size(), 3u);
    EXPECT_EQ(m.P[2], Vec3f(2, 4, -1));
    EXPECT_TRUE(m.N.empty());
    ASSERT_EQ(m.uv.size(), 3u);
    EXPECT_EQ(m.uv[1], Vec2f(0.25f, 0.5f));
    EXPECT_EQ(m.indices, (std::vector<int>{2, 1, 0}));
}

TEST(PlyReader, BinaryBigEndianDoublesAndTextureUV) {
    Bytes b;
    b.bigEndian = true;
    const double pts[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 5}};
    for (int i = 0; i < 4; ++i)
        b.Put<double>(pts[i][0])
            .Put<double>(pts[i][1])
            .Put<double>(pts[i][2])
            .Put<float>(float(i))
            .Put<float>(1.f);
    b.Put<int32_t>(4).Put<uint16_t>(0).Put<uint16_t>(1).Put<uint16_t>(2).Put<uint16_t>(3);
    std::string header =
        "ply\nformat binary_big_endian 1.0\nelement vertex 4\n"
        "property double x\nproperty float64 y\nproperty double z\n"
        "property float texture_u\nproperty float texture_v\n"
        "element face 1\nproperty list int ushort vertex_indices\nend_header\n";
    Diagnostics diag;
    PlyMesh m = ReadPlyFile(WriteScratchFile("ply_be.ply", header + b.data), diag);
    ASSERT_EQ(m.P.size(), 4u);
    EXPECT_EQ(m.P[3], Vec3f(0, 1, 5));
    ASSERT_EQ(m.uv.size(), 4u);
    EXPECT_EQ(m.uv[3], Vec2f(3, 1));
    EXPECT_EQ(m.indices, (std::vector<int>{0, 1, 2, 0, 2, 3}));
}

TEST(PlyReader, UVAliasesTextureST) {
    std::string path =
        WriteScratchFile("ply_st.ply",
                         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                         "property float y\nproperty float z\nproperty float texture_s\n"
                         "property float texture_t\nelement face 1\n"
                         "property list uchar int vertex_indices\nend_header\n"
                         "0 0 0 0.5 0.25\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n");
    Diagnostics diag;
    PlyMesh m = ReadPlyFile(path, diag);
    ASSERT_EQ(m.uv.size(), 3u);
    EXPECT_EQ(m.uv[0], Vec2f(0.5f, 0.25f));
}

TEST(PlyReader, PentagonsAreFannedWithOneWarning) {
    std::string path =
        WriteScratchFile("ply_penta.ply",
                         "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\n"
                         "property float y\nproperty float z\nelement face 4\n"
                         "property list uchar int vertex_indices\nend_header\n"
                         "0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 1 0\n"
                         "5 0 1 2 3 4\n5 4 3 2 1 0\n2 0 1\n3 0 1 2\n");
    Diagnostics diag;
    PlyMesh m = ReadPlyFile(path, diag);
    EXPECT_EQ(m.indices.size(), (3u + 3u + 1u) * 3u);
    EXPECT_EQ(std::vector<int>(m.indices.begin(), m.indices.begin() + 9),
              (std::vector<int>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
    std::vector<Warning> w = diag.Warnings();
    ASSERT_EQ(w.size(), 2u);
    bool fanned = false, skipped = false;
    for (const Warning &x : w) {
        fanned |= x.message == "2 faces with more than 4 vertices were fanned into triangles";
        skipped |= x.message == "1 faces with fewer than 3 vertices were skipped";
    }
    EXPECT_TRUE(fanned);
    EXPECT_TRUE(skipped);
}

TEST(PlyReader, TruncatedBinaryData) {
    Bytes b;
    for (int i = 0; i < 10; ++i) b.Put<float>(1).Put<float>(2).Put<float>(3);
    b.Put<float>(1);  // a partial eleventh vertex
    std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 24\n"
        "property float x\nproperty float y\nproperty float z\nend_header\n";
    // Fixed-size binary elements are checked against the file size before reading.
    Diagnostics diag;
    std::string msg = ExpectError(WriteScratchFile("ply_trunc.ply", header + b.data), diag);
    EXPECT_NE(msg.find("file ends after 10 of 24 vertices"), std::string::npos) << msg;

    // ascii: 3 values per vertex need 6 bytes each by the size rule, so this header passes
    // the up-front check and the truncation is found while reading.
    std::string ascii =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
        "property float y\nproperty float z\nend_header\n"
        "0 0 0\n1 0 0\n1 1 0\n1.5        ";
    msg = ExpectError(WriteScratchFile("ply_trunc_ascii.ply", ascii), diag);
    EXPECT_NE(msg.find("file ends after 3 of 4 vertices"), std::string::npos) << msg;
}

TEST(PlyReader, TruncatedFacesReportsCounts) {
    Bytes b;
    for (int i = 0; i < 3; ++i) b.Put<float>(float(i)).Put<float>(0).Put<float>(0);
    b.Put<uint8_t>(3).Put<int32_t>(0).Put<int32_t>(1).Put<int32_t>(2);
    b.Put<uint8_t>(3).Put<int32_t>(0);  // second face cut short
    std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
        "property float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
    Diagnostics diag;
    std::string msg = ExpectError(WriteScratchFile("ply_truncf.ply", header + b.data), diag);
    EXPECT_NE(msg.find("file ends after 1 of 2 faces"), std::string::npos) << msg;
}

TEST(PlyReader, HugeHeaderCountIsRejectedWithoutAllocating) {
    std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\n"
        "property float x\nproperty float y\nproperty float z\nend_header\n";
    Diagnostics diag;
    auto t0 = std::chrono::steady_clock::now();
    std::string msg =
        ExpectError(WriteScratchFile("ply_huge.ply", header + std::string(64, '\0')), diag);
    double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_LT(sec, 1.0);
    EXPECT_NE(msg.find("1000000000000 vertices"), std::string::npos) << msg;
    EXPECT_NE(msg.find("huge.ply:3:1"), std::string::npos) << msg;

    // Same for an element we would only skip, and for a property-less element.
    header =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nelement junk 999999999999\nproperty int a\nend_header\n0 0 0\n";
    msg = ExpectError(WriteScratchFile("ply_huge2.ply", header), diag);
    EXPECT_NE(msg.find("999999999999"), std::string::npos) << msg;
    header =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nelement empty 999999999999\nend_header\n0 0 0\n";
    Diagnostics d2;
    PlyMesh m = ReadPlyFile(WriteScratchFile("ply_huge3.ply", header), d2);
    EXPECT_EQ(m.P.size(), 1u);
}

TEST(PlyReader, HugeListCountIsTruncationNotAllocation) {
    Bytes b;
    for (int i = 0; i < 3; ++i) b.Put<float>(float(i)).Put<float>(0).Put<float>(0);
    b.Put<uint32_t>(0xFFFFFFFFu).Put<int32_t>(0);
    std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
        "property float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uint int vertex_indices\nend_header\n";
    Diagnostics diag;
    std::string msg = ExpectError(WriteScratchFile("ply_hugelist.ply", header + b.data), diag);
    EXPECT_NE(msg.find("file ends after 0 of 1 faces"), std::string::npos) << msg;
}

TEST(PlyReader, IndexOutOfRange) {
    std::string data =
        "ply\nformat ascii 1.0\nelement vertex 24\nproperty float x\n"
        "property float y\nproperty float z\nelement face 8\n"
        "property list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < 24; ++i) data += std::to_string(i) + " 0 0\n";
    for (int f = 0; f < 7; ++f) data += "3 0 1 2\n";
    data += "3 0 99 2\n";
    Diagnostics diag;
    std::string msg = ExpectError(WriteScratchFile("ply_range.ply", data), diag);
    EXPECT_NE(msg.find("face 7 references vertex 99, but there are 24 vertices"), std::string::npos)
        << msg;
}

TEST(PlyReader, HeaderErrorsCarryLocations) {
    Diagnostics diag;
    std::string msg =
        ExpectError(WriteScratchFile("ply_notply.ply", "solid cube\nfacet normal 0 0 1\n"), diag);
    EXPECT_NE(msg.find("notply.ply:1:1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("not a PLY file"), std::string::npos) << msg;

    msg = ExpectError(WriteScratchFile("ply_badfmt.ply",
                                       "ply\nformat binary_middle_endian 1.0\n"
                                       "end_header\n"),
                      diag);
    EXPECT_NE(msg.find("badfmt.ply:2:8"), std::string::npos) << msg;
    EXPECT_NE(msg.find("bad format line"), std::string::npos) << msg;

    msg = ExpectError(WriteScratchFile("ply_badtype.ply",
                                       "ply\nformat ascii 1.0\nelement vertex 1\n"
                                       "property quad x\nend_header\n0\n"),
                      diag);
    EXPECT_NE(msg.find("badtype.ply:4:10"), std::string::npos) << msg;
    EXPECT_NE(msg.find("unknown property type \"quad\""), std::string::npos) << msg;

    msg = ExpectError(WriteScratchFile("ply_badnum.ply",
                                       "ply\nformat ascii 1.0\nelement vertex 1\n"
                                       "property float x\nproperty float y\n"
                                       "property float z\nend_header\n0 zero 0\n"),
                      diag);
    EXPECT_NE(msg.find("badnum.ply:8"), std::string::npos) << msg;
    EXPECT_NE(msg.find("bad number \"zero\""), std::string::npos) << msg;

    msg = ExpectError(TempPath("does_not_exist.ply"), diag);
    EXPECT_NE(msg.find("cannot open file"), std::string::npos) << msg;

    msg = ExpectError(
        WriteScratchFile("ply_noend.ply", "ply\nformat ascii 1.0\nelement vertex 0\n"), diag);
    EXPECT_NE(msg.find("end_header"), std::string::npos) << msg;
}

}  // namespace
}  // namespace prism

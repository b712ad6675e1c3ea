#include "support/status_table.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <vector>

#include "assembly/build_scene.h"
#include "image/image_io.h"
#include "scene/load_scene.h"
#include "support/bsdf_file.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism::test {

namespace fs = std::filesystem;

std::vector<SharedProbe> SharedDirectiveProbes() {
    using W = SharedProbe::Where;
    const std::string object =
        "ObjectBegin \"o\"\nShape \"sphere\"\nObjectEnd\nObjectInstance \"o\"\n";
    const std::string identity = "[1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]\n";
    return {
        {"AttributeBegin", W::World, "AttributeBegin\nAttributeEnd\n"},
        {"AttributeEnd", W::World, "AttributeBegin\nAttributeEnd\n"},
        {"Identity", W::World, "Identity\n"},
        {"ReverseOrientation", W::World, "ReverseOrientation\n"},
        {"Translate", W::World, "Translate 1 0 0\n"},
        {"Scale", W::World, "Scale 1 2 1\n"},
        {"Rotate", W::World, "Rotate 30 0 1 0\n"},
        {"LookAt", W::BeforeCamera, "LookAt 0 0 -5 0 0 0 0 1 0\n"},
        {"CoordinateSystem", W::World, "CoordinateSystem \"c\"\n"},
        {"CoordSysTransform", W::World, "CoordinateSystem \"c\"\nCoordSysTransform \"c\"\n"},
        {"Transform", W::World, "Transform " + identity},
        {"ConcatTransform", W::World, "ConcatTransform " + identity},
        {"TransformTimes", W::Options, "TransformTimes 0 1\n"},
        {"ActiveTransform", W::World,
         "ActiveTransform EndTime\nTranslate 0.1 0 0\nActiveTransform All\n"},
        {"ObjectBegin", W::World, object},
        {"ObjectEnd", W::World, object},
        {"ObjectInstance", W::World, object},
        {"Include", W::World, "Include \"part.pbrt\"\n"},
    };
}

std::map<StatusKey, std::string> StatusTableRows(const std::string &doc) {
    std::ifstream in(Source + "/" + doc);
    EXPECT_TRUE(in) << doc;
    std::map<StatusKey, std::string> rows;
    std::string line;
    auto cell = [](std::string s) {
        size_t a = s.find_first_not_of(' '), b = s.find_last_not_of(' ');
        s = a == std::string::npos ? "" : s.substr(a, b - a + 1);
        if (s.size() >= 2 && s.front() == '`' && s.back() == '`') s = s.substr(1, s.size() - 2);
        return s;
    };
    while (std::getline(in, line)) {
        if (line.rfind("| ", 0) != 0) continue;
        std::vector<std::string> cells;
        std::stringstream ss(line.substr(1));
        std::string c;
        while (std::getline(ss, c, '|')) cells.push_back(cell(c));
        if (cells.size() < 3 || cells[0] == "directive" || cells[0].rfind("---", 0) == 0) continue;
        EXPECT_TRUE(rows.emplace(StatusKey{cells[0], cells[1]}, cells[2]).second)
            << "twice: " << cells[0] << " " << cells[1];
    }
    return rows;
}

void WriteStatusProbeInputs(const fs::path &dir) {
    std::ofstream(dir / "lens.dat") << "# radius thickness eta aperture\n"
                                       "20 4 1.5 16\n-20 2 1 16\n0 28 0 8\n";
    std::ofstream(dir / "part.pbrt") << "Shape \"sphere\" \"float radius\" 0.5\n";
    std::ofstream(dir / "quad.ply")
        << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
           "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
           "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    Image t(4, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) t.SetRGB(x, y, RGB(0.5f));
    WriteImage((dir / "t.png").string(), t);
    WriteImage((dir / "env.exr").string(), t);
    std::ofstream(dir / "m.bsdf", std::ios::binary) << LambertianFourierBsdf(0.5f);
}

std::pair<std::string, std::string> ObserveStatusProbe(const fs::path &dir,
                                                       const std::string &text) {
    const fs::path file = dir / "probe.pbrt";
    std::ofstream(file) << text;
    Diagnostics diag(false);
    try {
        SceneDescription desc = LoadScene(file.string(), diag);
        BuildSettings settings;
        settings.resolution = {8, 8};
        BuildRenderScene(desc, settings, diag);
    } catch (const SceneError &e) {
        return {"rejected", e.what()};
    }
    if (!diag.Warnings().empty()) return {"warned", diag.Warnings()[0].ToString()};
    return {"simulated", ""};
}

void CheckStatusTable(const std::string &doc, const std::string &scratch,
                      const std::map<StatusKey, std::string> &probes) {
    const fs::path dir = ScratchDir(scratch);
    WriteStatusProbeInputs(dir);
    const std::map<StatusKey, std::string> rows = StatusTableRows(doc);
    for (const auto &[key, text] : probes) {
        SCOPED_TRACE(key.first + " " + key.second);
        const auto [status, message] = ObserveStatusProbe(dir, text);
        auto row = rows.find(key);
        if (row == rows.end()) {
            ADD_FAILURE() << doc << " has no row for " << key.first << " | " << key.second << " | "
                          << status << " | " << message;
            continue;
        }
        EXPECT_EQ(status, row->second) << message << "\nscene:\n" << text;
    }
    for (const auto &[key, status] : rows)
        EXPECT_TRUE(probes.count(key))
            << doc << " lists " << key.first << " " << key.second << ", which has no probe";
}

}  // namespace prism::test

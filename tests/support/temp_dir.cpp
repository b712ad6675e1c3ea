#include "support/temp_dir.h"

#include <unistd.h>

#include <fstream>
#include <sstream>

namespace prism::test {

namespace fs = std::filesystem;

fs::path ScratchDir(const std::string &name) {
    fs::path d = fs::path(::testing::TempDir()) / name;
    fs::create_directories(d);
    return d;
}

fs::path TempDir(const std::string &name) {
    const ::testing::TestInfo *info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string leaf = info ? std::string(info->test_suite_name()) + "." + info->name() : "none";
    // The process id keeps two runs of one test (repeated, or two suites of one build) apart.
    leaf += "_" + std::to_string(::getpid());
    if (!name.empty()) leaf += "_" + name;
    // A parameterised test's name carries a "/0", and a caller's name may have a '/' too.
    for (char &c : leaf)
        if (c == '/') c = '_';
    fs::path d = fs::path(::testing::TempDir()) / leaf;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string WriteTestFile(const fs::path &path, const std::string &contents) {
    if (path.has_parent_path()) fs::create_directories(path.parent_path());
    fs::path tmp = path;
    tmp += ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(tmp, std::ios::binary);
        out << contents;
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {  // e.g. path is a directory: write in place, as before
        fs::remove(tmp, ec);
        std::ofstream(path, std::ios::binary) << contents;
    }
    return path.string();
}

std::string WriteScratchFile(const std::string &name, const std::string &contents) {
    return WriteTestFile(fs::path(::testing::TempDir()) / name, contents);
}

std::string ReadFile(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void FreshDirTest::SetUp() { dir_ = TempDir(""); }

void FreshDirTest::TearDown() { fs::remove_all(dir_); }

std::set<std::string> FreshDirTest::ListDir() const {
    std::set<std::string> names;
    for (const auto &e : fs::directory_iterator(dir_)) names.insert(e.path().filename());
    return names;
}

}  // namespace prism::test

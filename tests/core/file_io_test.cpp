// The shared file reader: regular files only (never blocking on a device or FIFO), the OS
// reason on failure, and the size limit checked before reading.
#include "core/file_io.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/memory.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

std::string TempPath(const std::string &name) {
    return (fs::path(::testing::TempDir()) / ("file_io_" + name)).string();
}

TEST(FileIo, ReadsRegularFilesWhole) {
    std::string path = TempPath("text.txt");
    std::string data(200000, 'x');
    data[123] = '\0';  // binary-safe
    std::ofstream(path, std::ios::binary) << data;
    std::string text;
    FileReadError err;
    ASSERT_TRUE(ReadFileContents(path, &text, &err)) << err.reason;
    EXPECT_EQ(text, data);
    std::vector<unsigned char> bytes;
    ASSERT_TRUE(ReadFileContents(path, &bytes, &err));
    EXPECT_EQ(bytes.size(), data.size());
    EXPECT_EQ(ReadFileOrThrow(path, FileLoc{path}), data);
}

TEST(FileIo, RefusesWhatIsNotARegularFile) {
    std::string text;
    FileReadError err;
    EXPECT_FALSE(ReadFileContents("/dev/zero", &text, &err));  // would never end
    EXPECT_EQ(err.reason, "not a regular file");
    EXPECT_FALSE(ReadFileContents(::testing::TempDir(), &text, &err));
    EXPECT_EQ(err.reason, "Is a directory");
    EXPECT_FALSE(ReadFileContents(TempPath("does-not-exist"), &text, &err));
    EXPECT_EQ(err.reason, "No such file or directory");

    // A FIFO without a writer: opening it must not block.
    std::string fifo = TempPath("fifo");
    ::unlink(fifo.c_str());
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_FALSE(ReadFileContents(fifo, &text, &err));
    EXPECT_EQ(err.reason, "not a regular file");
    ::unlink(fifo.c_str());

    try {
        ReadFileOrThrow("/dev/zero", FileLoc{"s.pbrt", 3, 1});
        FAIL() << "no error";
    } catch (const SceneError &e) {
        EXPECT_STREQ(e.what(),
                     "s.pbrt:3:1: error: cannot open file \"/dev/zero\": not a regular file");
    }
}

TEST(FileIo, SizeLimitIsCheckedBeforeReading) {
    std::string path = TempPath("limit.txt");
    std::ofstream(path) << std::string(5000, 'a');
    std::string text;
    FileReadError err;
    EXPECT_TRUE(ReadFileContents(path, &text, &err, 5000));
    EXPECT_FALSE(ReadFileContents(path, &text, &err, 4999));
    EXPECT_TRUE(err.tooLarge);
    EXPECT_EQ(err.size, 5000u);
    try {
        ReadFileOrThrow(path, FileLoc{path}, 1024);
        FAIL() << "no error";
    } catch (const MemoryBudgetError &e) {
        // The library reports the limit; the app names the flag (tests/app/cli_test.cpp).
        EXPECT_EQ(e.Message(), "file is 4.9 KiB, more than the memory budget of 1.0 KiB");
    }
}

TEST(FileIo, ReadingChargesTheBudgetAndRefusesWhatDoesNotFit) {
    std::string path = TempPath("charged.txt");
    std::ofstream(path) << std::string(3000, 'a');
    MemoryBudget budget(8000);
    EXPECT_EQ(ReadFileOrThrow(path, FileLoc{path}, budget, "scene file").size(), 3000u);
    EXPECT_EQ(ReadFileOrThrow(path, FileLoc{path}, budget, "scene file").size(), 3000u);
    EXPECT_EQ(budget.Used(), 6000u);
    // The third copy alone fits the limit but not what remains: refused before it is read.
    try {
        ReadFileOrThrow(path, FileLoc{path, 2, 1}, budget, "included file \"c.pbrt\"");
        FAIL() << "no error";
    } catch (const MemoryBudgetError &e) {
        EXPECT_EQ(e.Message(),
                  "included file \"c.pbrt\" needs about 2.9 KiB; with 5.9 KiB already "
                  "committed that exceeds the memory budget of 7.8 KiB");
        EXPECT_EQ(e.Loc().line, 2);
        EXPECT_EQ(e.Requested(), 3000u);
        EXPECT_EQ(e.Committed(), 6000u);
    }
    EXPECT_EQ(budget.Used(), 6000u);
}

TEST(FileIo, PathHelpers) {
    EXPECT_EQ(LowerExtension("a/Scene.PBRT"), ".pbrt");
    EXPECT_EQ(LowerExtension("a.b/noext"), "");
    EXPECT_EQ(DirectoryOf("scenes/a.pbrt"), "scenes");
    EXPECT_EQ(DirectoryOf("a.pbrt"), "");
    EXPECT_EQ(CanonicalPath("/tmp/../tmp/./x"), CanonicalPath("/tmp/x"));
    EXPECT_TRUE(fs::path(CanonicalPath("relative")).is_absolute());
}

// --confine's policy: inside the folder after symlinks, regular files only; restored when the
// scope ends; ReadFileOrThrow's message names the file, not where it resolves or the folder.
TEST(FileIo, ReadConfinement) {
    fs::path root = TempPath("confine");
    fs::remove_all(root);
    fs::create_directories(root / "in/sub");
    std::ofstream(root / "in/sub/ok.txt") << "ok";
    std::ofstream(root / "out.txt") << "secret";
    fs::create_symlink("../out.txt", root / "in/link.txt");
    fs::create_symlink("sub/ok.txt", root / "in/inner_link.txt");
    ASSERT_EQ(::mkfifo((root / "in/fifo").c_str(), 0600), 0);
    std::string text;
    FileReadError err;
    {
        ScopedReadConfinement confine((root / "in").string());
        EXPECT_EQ(ReadConfinementFolder(), CanonicalPath((root / "in").string()));
        EXPECT_TRUE(ReadFileContents((root / "in/sub/ok.txt").string(), &text, &err));
        EXPECT_TRUE(ReadFileContents((root / "in/inner_link.txt").string(), &text, &err));
        EXPECT_TRUE(ReadFileContents((root / "in/sub/../sub/ok.txt").string(), &text, &err));
        for (const std::string &bad :
             {(root / "out.txt").string(), (root / "in/../out.txt").string(),
              (root / "in/link.txt").string(), std::string("/dev/zero"),
              std::string("/proc/self/environ")}) {
            SCOPED_TRACE(bad);
            EXPECT_FALSE(ReadFileContents(bad, &text, &err));
            EXPECT_TRUE(err.refused);
            EXPECT_NE(err.reason.find("outside the confined folder"), std::string::npos)
                << err.reason;
        }
        EXPECT_FALSE(ReadFileContents((root / "in/fifo").string(), &text, &err));
        EXPECT_TRUE(err.refused);
        EXPECT_NE(err.reason.find("not a regular file"), std::string::npos) << err.reason;
        // A missing file inside is not refused: opening it fails as usual.
        EXPECT_FALSE(ReadFileContents((root / "in/missing").string(), &text, &err));
        EXPECT_FALSE(err.refused);
        try {
            ReadFileOrThrow((root / "in/link.txt").string(), FileLoc{"a.pbrt", 3, 1});
            FAIL() << "not refused";
        } catch (const SceneError &e) {
            EXPECT_EQ(e.Loc().line, 3);
            EXPECT_NE(e.Message().find("link.txt"), std::string::npos) << e.Message();
            // Neither where it resolves nor the folder (no server paths for an upload).
            EXPECT_NE(e.Message().find("it lies outside the confined folder"), std::string::npos)
                << e.Message();
            EXPECT_EQ(e.Message().find(CanonicalPath((root / "out.txt").string())),
                      std::string::npos)
                << e.Message();
            EXPECT_EQ(e.Message().find(CanonicalPath((root / "in").string()) + "\""),
                      std::string::npos)
                << e.Message();
        }
        EXPECT_THROW(CheckReadConfinement((root / "out.txt").string(), FileLoc{"a.pbrt", 1, 1},
                                          "texture file", "../out.txt"),
                     SceneError);
        EXPECT_NO_THROW(CheckReadConfinement((root / "in/sub/ok.txt").string(), FileLoc{},
                                             "texture file", "ok.txt"));
    }
    EXPECT_EQ(ReadConfinementFolder(), "");
    EXPECT_TRUE(ReadFileContents((root / "in/link.txt").string(), &text, &err)) << err.reason;
    EXPECT_EQ(text, "secret");
}

}  // namespace
}  // namespace prism

// The manual (docs/USAGE.md) against the command line: every flag `prism <command> --help`
// prints is named there, so a new flag cannot land undocumented.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <regex>
#include <set>
#include <string>

#include "support/process.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

// The long flags of a --help text ("--spp", "--env-rotate"), without --help itself.
std::set<std::string> LongFlags(const std::string &help) {
    std::set<std::string> flags;
    static const std::regex flag("--[a-z0-9][a-z0-9-]*");
    for (auto it = std::sregex_iterator(help.begin(), help.end(), flag);
         it != std::sregex_iterator(); ++it)
        if (it->str() != "--help") flags.insert(it->str());
    return flags;
}

// Whether text names `flag` as a whole token: "--env" is not named by "--env-rotate" alone.
bool Names(const std::string &text, const std::string &flag) {
    for (size_t at = text.find(flag); at != std::string::npos; at = text.find(flag, at + 1)) {
        const size_t end = at + flag.size();
        const char next = end < text.size() ? text[end] : ' ';
        if (!(std::isalnum(static_cast<unsigned char>(next)) || next == '-')) return true;
    }
    return false;
}

TEST(Docs, UsageNamesEveryFlag) {
    const std::string usage = test::ReadFile(Source + "/docs/USAGE.md");
    ASSERT_FALSE(usage.empty());
    const fs::path dir = TempDir("usage");
    size_t checked = 0;
    for (const char *command : {"render", "batch", "info", "trace", "pick", "validate", "study",
                                "bench ceiling", "bench compare", "bench knot", "bench suite"}) {
        const test::RunResult r = test::RunPrism(std::string(command) + " --help", dir);
        ASSERT_EQ(r.exitCode, 0) << command << ": " << r.err;
        const std::set<std::string> flags = LongFlags(r.out);
        EXPECT_FALSE(flags.empty()) << command;
        for (const std::string &f : flags) {
            EXPECT_TRUE(Names(usage, f))
                << "prism " << command << " " << f << " is not in docs/USAGE.md";
            ++checked;
        }
    }
    EXPECT_GT(checked, 100u);  // the render command alone has dozens
}

// The front door stays one: under 200 lines, pointing to the manual.
TEST(Docs, ReadmeIsAFrontDoor) {
    const std::string readme = test::ReadFile(Source + "/README.md");
    size_t lines = 0;
    for (char c : readme) lines += c == '\n';
    EXPECT_LT(lines, 200u);
    EXPECT_NE(readme.find("docs/USAGE.md"), std::string::npos);
}

// Every document in docs/ is listed in the README, and every docs/*.md file that the README,
// the docs, the sources, the tests, the tools or the scenes cite exists: a merged or renamed
// document leaves no dangling reference behind.
TEST(Docs, EveryDocIsListedAndEveryCitedDocExists) {
    const std::string readme = test::ReadFile(Source + "/README.md");
    size_t docs = 0;
    for (const auto &e : fs::directory_iterator(Source + "/docs")) {
        if (e.path().extension() != ".md") continue;
        ++docs;
        const std::string name = "docs/" + e.path().filename().string();
        EXPECT_NE(readme.find("`" + name + "`"), std::string::npos)
            << name << " is not in the README's documentation table";
    }
    EXPECT_GE(docs, 5u);
    const std::regex cited(R"(docs/([A-Z][A-Z_0-9]*)\.md)");
    size_t references = 0;
    for (const char *dir : {"src", "tests", "tools", "scenes", "docs", "bench"}) {
        for (const auto &e : fs::recursive_directory_iterator(Source + "/" + dir)) {
            const std::string ext = e.path().extension().string();
            if (!e.is_regular_file() || (ext != ".md" && ext != ".cpp" && ext != ".h" &&
                                         ext != ".sh" && ext != ".py" && ext != ".pbrt"))
                continue;
            const std::string text = test::ReadFile(e.path());
            for (std::sregex_iterator m(text.begin(), text.end(), cited), end; m != end; ++m) {
                if ((*m)[1] == "X") continue;  // USAGE.md's "docs/X.md" placeholder
                ++references;
                EXPECT_TRUE(fs::exists(Source + "/docs/" + (*m)[1].str() + ".md"))
                    << e.path() << " cites " << m->str() << ", which does not exist";
            }
        }
    }
    EXPECT_GT(references, 50u);
}

// docs/PARAMETERS.md is what tools/param_tables.py generates from the comment tables beside
// each Create, every registered integrator, light and material has a table, and every name a
// table lists is one its code reads (the script's --check).
TEST(Docs, ParameterTablesMatchTheCode) {
    RunResult r = RunShell("python3 " + ShellQuoted(Source + "/tools/param_tables.py") + " --check",
                           TempDir("params"));
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

}  // namespace
}  // namespace prism

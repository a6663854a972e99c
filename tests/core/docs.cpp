// The documentation cannot rot: every ```cpp block of docs/*.md and README.md is an excerpt —
// a run of consecutive lines, indentation aside — of a program compiled in the build
// (examples/*.cpp, examples/docs/*.cpp). So a snippet that does not compile, or drifts from
// the code, fails here.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::vector<std::string> lines_of(const fs::path& p) {
    std::ifstream in(p);
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

std::string trimmed(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return {};
    const auto e = s.find_last_not_of(" \t\r");
    return s.substr(b, e - b + 1);
}

struct snippet {
    std::string where;
    std::vector<std::string> lines;  // trimmed, blank lines at both ends removed
};

std::vector<snippet> cpp_snippets(const fs::path& md) {
    std::vector<snippet> out;
    const auto lines = lines_of(md);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (trimmed(lines[i]) != "```cpp") continue;
        snippet s{md.filename().string() + ":" + std::to_string(i + 1), {}};
        for (++i; i < lines.size() && trimmed(lines[i]) != "```"; ++i) s.lines.push_back(trimmed(lines[i]));
        while (!s.lines.empty() && s.lines.back().empty()) s.lines.pop_back();
        while (!s.lines.empty() && s.lines.front().empty()) s.lines.erase(s.lines.begin());
        out.push_back(std::move(s));
    }
    return out;
}

bool contains_run(const std::vector<std::string>& file, const std::vector<std::string>& run) {
    if (run.empty()) return true;
    for (std::size_t i = 0; i + run.size() <= file.size(); ++i)
        if (std::equal(run.begin(), run.end(), file.begin() + static_cast<std::ptrdiff_t>(i))) return true;
    return false;
}

}  // namespace

TEST_CASE("every C++ snippet of the documentation is an excerpt of a compiled example") {
    const fs::path root = CERTIPOSE_SOURCE_DIR;
    std::vector<std::vector<std::string>> programs;
    for (const fs::path& dir : {root / "examples", root / "examples" / "docs"})
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().extension() == ".cpp") {
                auto l = lines_of(e.path());
                for (auto& x : l) x = trimmed(x);
                programs.push_back(std::move(l));
            }
    REQUIRE(programs.size() >= 10);
    std::vector<fs::path> pages{root / "README.md"};
    for (const auto& e : fs::directory_iterator(root / "docs"))
        if (e.path().extension() == ".md") pages.push_back(e.path());
    std::size_t checked = 0;
    for (const auto& page : pages)
        for (const auto& s : cpp_snippets(page)) {
            CAPTURE(s.where);
            const bool found = std::any_of(programs.begin(), programs.end(),
                                           [&](const auto& p) { return contains_run(p, s.lines); });
            CHECK_MESSAGE(found, s.where << ": this ```cpp block is not an excerpt of examples/*.cpp or "
                                            "examples/docs/*.cpp; put it in the page's example program");
            ++checked;
        }
    MESSAGE(checked << " snippets checked");
    CHECK(checked >= 12);
}

TEST_CASE("the documentation, headers, examples, scripts and benchmarks point nowhere outside the repository") {
    // Users get the repository and nothing beside it: no design notes, no test data. So no file
    // they read may send them to "DESIGN.md" or to "../shared" (the developers' data folder, which
    // the tests alone may read): the conventions and formats are docs/conventions.md.
    const fs::path root = CERTIPOSE_SOURCE_DIR;
    const std::vector<std::string> outside{"DESIGN.md", "../shared"};
    std::vector<fs::path> files{root / "README.md"};
    for (const char* dir : {"docs", "include", "examples", "scripts", "bench", "python"})
        for (const auto& e : fs::recursive_directory_iterator(root / dir))
            if (e.is_regular_file()) files.push_back(e.path());
    REQUIRE(files.size() >= 100);
    std::size_t found = 0;
    for (const auto& file : files) {
        const auto lines = lines_of(file);
        for (std::size_t i = 0; i < lines.size(); ++i)
            for (const auto& word : outside)
                if (lines[i].find(word) != std::string::npos) {
                    ++found;
                    FAIL_CHECK(fs::relative(file, root).string()
                               << ":" << i + 1 << " mentions \"" << word
                               << "\", which users do not have; point into the repository instead "
                                  "(docs/conventions.md, or the page that says it)");
                }
    }
    MESSAGE(files.size() << " files checked");
    CHECK(found == 0);
}

TEST_CASE("no test case name holds a semicolon, which CTest would cut off so that the test runs nothing") {
    // doctest_discover_tests registers each case as `--test-case=<name>`, and CMake reads a ';'
    // in a name as a list separator: the case is registered under the part before it, a filter
    // no case matches, and CTest reports "Passed" for a test that ran nothing.
    const fs::path root = CERTIPOSE_SOURCE_DIR;
    std::size_t cases = 0, bad = 0;
    for (const auto& e : fs::recursive_directory_iterator(root / "tests")) {
        if (!e.is_regular_file() || e.path().extension() != ".cpp") continue;
        const auto lines = lines_of(e.path());
        for (std::size_t i = 0; i < lines.size(); ++i) {
            const auto at = lines[i].find("TEST_CASE(\"");
            if (at == std::string::npos) continue;
            ++cases;
            const auto begin = at + 11, end = lines[i].find('"', begin);
            const std::string name = lines[i].substr(begin, end == std::string::npos ? std::string::npos : end - begin);
            if (name.find(';') != std::string::npos) {
                ++bad;
                FAIL_CHECK(fs::relative(e.path(), root).string() << ":" << i + 1 << ": \"" << name << "\" holds a ';'");
            }
        }
    }
    MESSAGE(cases << " test cases checked");
    CHECK(cases > 200);
    CHECK(bad == 0);
}

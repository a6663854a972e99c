// A downstream program of the whole-part solver's target: <certipose/part.hpp> with certipose::part
// alone (certipose::certipose + oneTBB, no CGAL), so that the package's TBB dependency reaches the
// consumer's compile and link lines (tests/consumer/*/CMakeLists.txt).
#include <certipose/part.hpp>

#include <oneapi/tbb/info.h>

#include <cstdio>
#include <vector>

int main() {
    const std::vector<std::size_t> facets = certipose::parse_facet_selection("0,5,2-3", 10);
    const certipose::part_options options{};  // threads = 0: oneTBB's default concurrency
    const int threads = oneapi::tbb::info::default_concurrency();  // links libtbb
    const bool ok = facets == std::vector<std::size_t>{0, 5, 2, 3} && options.threads == 0 && threads >= 1;
    std::printf("consumer (part): %zu facets, %d threads: %s\n", facets.size(), threads, ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}

// certipose/io/read_mesh.hpp — read OFF, OBJ, PLY or STL into a validated triangle_mesh (CGAL).
//
// `read_mesh` is how parts and occluders enter the library (docs/conventions.md#files: every
// program reads OFF, OBJ, PLY or STL). Parsing is CGAL's (CGAL::IO::read_OFF / read_OBJ / read_PLY /
// read_STL, the readers behind read_polygon_soup); this header only chooses the reader from
// the extension (case-insensitive), turns every failure into a certipose exception naming the
// path, optionally welds and scales, and builds the triangle_mesh, whose validation rejects
// NaN/inf coordinates and degenerate faces. Polygons with more than three vertices are
// REJECTED, not triangulated: the face order of the file is kept exactly, so a facet index
// means the same face in the file, in MeshLab and in certipose's result JSON. STL soups need no
// welding tolerance: CGAL's STL reader already merges exactly coincident points. Needs
// certipose::cgal. The writer, write_mesh_off, is in certipose/io/write_mesh.hpp (no CGAL).
#pragma once

#include "certipose/detail/config.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/io/write_mesh.hpp"

#include <filesystem>
#include <optional>

namespace certipose {

/// Options of read_mesh.
struct read_options {
    /// Unset: no welding. Set: merge vertices closer than this, in FILE units (before `scale`);
    /// see `welded`. Throws invalid_argument("weld_tolerance") if negative or non-finite.
    std::optional<double> weld_tolerance{};
    /// Multiplies every coordinate after reading (e.g. 0.0254 for inches → metres).
    /// Throws invalid_argument("scale") unless finite and > 0.
    double scale = 1.0;
};

/// Reads a triangle mesh from `path` (.off, .obj, .ply or .stl, any letter case).
/// Throws certipose::io_error(path) when the extension is unknown, the file is missing or
/// unreadable, CGAL cannot parse it, or it holds no face; certipose::mesh_error (message
/// prefixed with the path) when a polygon is not a triangle or the mesh fails triangle_mesh's
/// validation or welding; certipose::invalid_argument for bad options. Faces keep file order.
/// CGAL's PLY reader writes its complaints to std::cerr: while a .ply file is parsed, std::cerr
/// is redirected and what it printed becomes part of the io_error (so do not log to std::cerr
/// from another thread during that call).
triangle_mesh read_mesh(const std::filesystem::path& path, const read_options& opt = {});

}  // namespace certipose

// The definition (CGAL's readers), unless the certipose::precompiled library has it
// (detail/config.hpp).
#if CERTIPOSE_DETAIL_WITH_DEFINITIONS

#include "certipose/interval/detail/fenv.hpp"

#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/io/write_mesh.hpp"

#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace certipose {

namespace detail::io {

/// Point type for CGAL's STL reader, which merges points through a std::map<Point, int>. With
/// CGAL's points (or std::array) a NaN compares equivalent to anything in that coordinate, so
/// a NaN vertex could silently merge into another vertex; this order is a strict weak order
/// that keeps NaN points apart (NaN after every number, NaNs equal), so triangle_mesh sees them.
struct stl_point {
    double c[3]{};
    double& operator[](std::size_t i) noexcept { return c[i]; }
    const double& operator[](std::size_t i) const noexcept { return c[i]; }
    friend bool operator<(const stl_point& a, const stl_point& b) noexcept {
        for (int i = 0; i < 3; ++i) {
            const bool na = std::isnan(a.c[i]), nb = std::isnan(b.c[i]);
            if (na || nb) {
                if (na != nb) return nb;
                continue;
            }
            if (a.c[i] < b.c[i]) return true;
            if (b.c[i] < a.c[i]) return false;
        }
        return false;
    }
};

/// Captures what CGAL's PLY reader prints on std::cerr ("Error: incorrect file format line 1 of
/// file", whatever its `verbose` flag says) so that the caller sees one line, ours, with CGAL's
/// words folded into it. std::cerr is process-wide, so the capture covers the PLY reader only
/// (the other readers print nothing unless asked to); read_mesh's comment says so.
class captured_cerr {
public:
    captured_cerr() : old_(std::cerr.rdbuf(text_.rdbuf())) {}
    captured_cerr(const captured_cerr&) = delete;
    captured_cerr& operator=(const captured_cerr&) = delete;
    ~captured_cerr() { std::cerr.rdbuf(old_); }
    /// The captured text on one line, without CGAL's "Error: " prefixes; empty if none.
    std::string one_line() const {
        std::string out;
        std::istringstream in(text_.str());
        for (std::string line; std::getline(in, line);) {
            if (line.rfind("Error: ", 0) == 0) line.erase(0, 7);
            while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
            if (line.empty()) continue;
            out += (out.empty() ? "" : "; ") + line;
        }
        return out;
    }

private:
    std::ostringstream text_;
    std::streambuf* old_;
};

/// Screens an OFF file before CGAL reads it. CGAL 5.5's OFF scanner reads past its buffers on
/// hostile input (a COFF vertex without its colour entries, a face with a colour index, an index
/// beyond 2^64 converted from a double: found by tests/fuzz), so only files whose every line has
/// the expected shape reach it: an OFF or COFF header (the vertex, face and edge counts on it or
/// on the next line, the edge count one CGAL can double in an int), vertex lines of 3 finite
/// numbers (COFF: 3 more or 4 more for the colour), face lines of a count n ≥ 1, n vertex indices
/// in range and no colour or 3 or 4 colour values in [0, 255]. Counts beyond what the file's size
/// can hold are refused before anything is allocated. Returns why the file is refused
/// ("PATH line N: ..."), or nothing.
inline std::string screen_off(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    const std::uintmax_t bytes = ec ? 0 : size;
    std::string line;
    std::size_t line_no = 0;
    std::vector<std::string> words;
    bool commented = false;  // the last line read had a comment
    const auto next_line = [&] {
        while (std::getline(in, line)) {
            ++line_no;
            commented = false;
            if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash), commented = true;
            words.clear();
            std::istringstream split(line);
            for (std::string w; split >> w;) words.push_back(w);
            if (!words.empty()) return true;
        }
        return false;
    };
    const std::string at = path.string() + " line ";
    const auto where = [&] { return at + std::to_string(line_no) + ": "; };
    // CGAL ends a line (and a comment) at a lone carriage return too, and then may read a
    // "BINARY" keyword this screen never saw: control characters have no place in ASCII OFF.
    {
        std::ifstream raw(path, std::ios::binary);
        std::size_t n = 1;
        char prev = 0;
        for (char ch; raw.get(ch); prev = ch) {
            const auto u = static_cast<unsigned char>(ch);
            if (prev == '\r' && ch != '\n')
                return at + std::to_string(n) + ": a carriage return not followed by a line feed";
            if (ch == '\n') ++n;
            if ((u < 0x20 && ch != '\n' && ch != '\r' && ch != '\t') || u == 0x7f)
                return at + std::to_string(n) + ": control character " + std::to_string(static_cast<int>(u)) +
                       " (an ASCII OFF file has none)";
        }
    }
    const auto number = [](const std::string& w, double& v) {
        const auto [end, e] = std::from_chars(w.data(), w.data() + w.size(), v);
        return e == std::errc{} && end == w.data() + w.size() && std::isfinite(v);
    };
    const auto count = [](const std::string& w, std::uint64_t& v) {
        if (w.empty() || w.size() > 19 || w.find_first_not_of("0123456789") != std::string::npos) return false;
        const auto [end, e] = std::from_chars(w.data(), w.data() + w.size(), v);
        return e == std::errc{} && end == w.data() + w.size();
    };
    if (!next_line()) return path.string() + ": empty (no OFF header)";
    const std::string head = words[0];
    // CGAL reads a header keyword through a '#' ("OFF#BINARY" is binary OFF to it).
    if (commented) return where() + "a comment on the header line";
    if (head != "OFF" && head != "COFF")
        return where() + "header '" + head + "' is not supported (plain OFF or COFF, ASCII)";
    const bool colours = head == "COFF";
    std::size_t first = 1;
    if (words.size() == 1) {
        if (!next_line()) return path.string() + ": ends after the header";
        first = 0;
    } else if (commented) {
        return where() + "a comment on the header line";
    }
    // All three counts, on one line: CGAL reads the edge count wherever the next number is (a
    // vertex's coordinate, a face's count, a stray line after the faces) and doubles it in an int.
    std::uint64_t nv = 0, nf = 0, ne = 0;
    if (words.size() != first + 3 || !count(words[first], nv) || !count(words[first + 1], nf) ||
        !count(words[first + 2], ne))
        return where() + "expected the vertex, face and edge counts";
    constexpr std::uint64_t int_max = std::numeric_limits<int>::max();
    if (ne > int_max / 2) return where() + "edge count " + std::to_string(ne) + " is beyond what CGAL reads (at most " +
                                 std::to_string(int_max / 2) + ")";
    // A vertex takes at least 6 bytes ("0 0 0\n"), a face 8: more than the file holds is a lie.
    if (nv > bytes / 6 + 1 || nf > bytes / 8 + 1 || ne > bytes)
        return where() + "counts " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
               " faces do not fit a file of " + std::to_string(bytes) + " bytes";
    for (std::uint64_t v = 0; v < nv; ++v) {
        if (!next_line()) return path.string() + ": ends after " + std::to_string(v) + " of " + std::to_string(nv) + " vertices";
        const std::size_t want = colours ? 6 : 3;
        if (words.size() != want && !(colours && words.size() == 7))
            return where() + "vertex " + std::to_string(v) + " has " + std::to_string(words.size()) + " values, expected " +
                   (colours ? "6 or 7 (x y z and a colour)" : "3");
        for (std::size_t k = 0; k < words.size(); ++k) {
            double x = 0;
            if (!number(words[k], x))
                return where() + "vertex " + std::to_string(v) + " has " + (k < 3 ? "coordinate" : "colour value") + " '" +
                       words[k] + "', not a finite number";
        }
    }
    for (std::uint64_t f = 0; f < nf; ++f) {
        if (!next_line()) return path.string() + ": ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces";
        std::uint64_t n = 0;
        if (!count(words[0], n) || n < 1 || n > words.size() - 1)
            return where() + "face " + std::to_string(f) + " has no valid vertex count ('" + words[0] + "')";
        for (std::size_t k = 1; k <= n; ++k) {
            std::uint64_t idx = 0;
            if (!count(words[k], idx) || idx >= nv)
                return where() + "face " + std::to_string(f) + " refers to vertex " + words[k] + ", out of range (the file has " +
                       std::to_string(nv) + " vertices)";
        }
        const std::size_t extra = words.size() - 1 - n;
        if (extra != 0 && extra != 3 && extra != 4)
            return where() + "face " + std::to_string(f) + " has " + std::to_string(extra) +
                   " values after its indices (a colour has 3 or 4)";
        for (std::size_t k = n + 1; k < words.size(); ++k) {
            double c = 0;
            if (!number(words[k], c) || c < 0 || c > 255)
                return where() + "face " + std::to_string(f) + " has colour value '" + words[k] + "', not in [0, 255]";
        }
    }
    return {};
}

/// A PLY scalar type: its name (PLY has two spellings of each), bytes per value, and whether it
/// is an integer type and a signed one.
struct ply_type {
    std::string_view name;
    std::size_t bytes;
    bool integer;
    bool is_signed;
};

/// The type named `t`, or null when PLY has no such type.
inline const ply_type* find_ply_type(std::string_view t) {
    static constexpr ply_type types[] = {
        {"char", 1, true, true},    {"uchar", 1, true, false},  {"short", 2, true, true},    {"ushort", 2, true, false},
        {"int", 4, true, true},     {"uint", 4, true, false},   {"float", 4, false, true},   {"double", 8, false, true},
        {"int8", 1, true, true},    {"uint8", 1, true, false},  {"int16", 2, true, true},    {"uint16", 2, true, false},
        {"int32", 4, true, true},   {"uint32", 4, true, false}, {"float32", 4, false, true}, {"float64", 8, false, true}};
    for (const auto& type : types)
        if (type.name == t) return &type;
    return nullptr;
}

/// One element of a PLY header: its name, count and properties (a list property has a count
/// type; a scalar one only `type`).
struct ply_property {
    const ply_type* type = nullptr;
    const ply_type* count_type = nullptr;  // null: a scalar property
};
struct ply_element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<ply_property> properties;
};

/// Reads a binary file's bytes in blocks, for the body screen (one read per block, not per value).
class ply_bytes {
public:
    explicit ply_bytes(std::istream& in) : in_(in) {}
    bool skip(std::uint64_t n) {
        while (n > 0) {
            if (pos_ == end_ && !fill()) return false;
            const std::uint64_t k = std::min<std::uint64_t>(n, end_ - pos_);
            pos_ += static_cast<std::size_t>(k);
            n -= k;
        }
        return true;
    }
    bool take(unsigned char* out, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) {
            if (pos_ == end_ && !fill()) return false;
            out[i] = static_cast<unsigned char>(buf_[pos_++]);
        }
        return true;
    }

private:
    bool fill() {
        in_.read(buf_.data(), static_cast<std::streamsize>(buf_.size()));
        end_ = static_cast<std::size_t>(in_.gcount());
        pos_ = 0;
        return end_ > 0;
    }
    std::istream& in_;
    std::vector<char> buf_ = std::vector<char>(std::size_t{1} << 16);
    std::size_t pos_ = 0, end_ = 0;
};

/// Walks a PLY body as its header declares it and checks every list count before CGAL reads it:
/// CGAL 5.5 resizes a vector to a list's count as read (a count of 2e9 int32 indices is an 8 GB
/// allocation: tests/fuzz/regressions/mesh_ply), so a count is refused when it is negative, not
/// a whole number, or more items than the bytes left in the file can hold. `left` is the body's
/// size in bytes. Returns why the file is refused, or nothing.
inline std::string screen_ply_body(std::istream& in, const std::string& format,
                                   const std::vector<ply_element>& elements, std::uint64_t left,
                                   const std::string& name) {
    const auto where = [&](const ply_element& e, std::uint64_t r) {
        return name + ": element '" + e.name + "' record " + std::to_string(r) + " ";
    };
    if (format == "ascii") {
        std::string token;
        for (const auto& e : elements)
            for (std::uint64_t r = 0; r < e.count; ++r)
                for (const auto& p : e.properties) {
                    if (!(in >> token)) return where(e, r) + "is cut short: the file ends";
                    if (!p.count_type) continue;
                    std::uint64_t n = 0;
                    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), n);
                    if (ec != std::errc{} || end != token.data() + token.size())
                        return where(e, r) + "has list count '" + token.substr(0, 40) + "', not a whole number >= 0";
                    if (n > (left + 1) / 2)  // n items take at least 2n - 1 bytes (digit, separator)
                        return where(e, r) + "lists " + token + " items; the file's " + std::to_string(left) +
                               " body bytes cannot hold them";
                    for (std::uint64_t k = 0; k < n; ++k)
                        if (!(in >> token)) return where(e, r) + "is cut short: the file ends inside a list";
                }
        return {};
    }
    const bool big = format == "binary_big_endian";
    ply_bytes bytes(in);
    for (const auto& e : elements) {
        if (e.properties.empty()) continue;
        for (std::uint64_t r = 0; r < e.count; ++r)
            for (const auto& p : e.properties) {
                if (!p.count_type) {
                    const std::size_t size = p.type->bytes;
                    if (size > left || !bytes.skip(size)) return where(e, r) + "is cut short: the file ends";
                    left -= size;
                    continue;
                }
                const std::size_t size = p.count_type->bytes;
                unsigned char raw[8] = {};
                if (size > left || !bytes.take(raw, size)) return where(e, r) + "is cut short: the file ends";
                left -= size;
                if (big) std::reverse(raw, raw + size);
                std::uint64_t n = 0;
                for (std::size_t k = size; k-- > 0;) n = (n << 8) | raw[k];
                if (p.count_type->is_signed && (raw[size - 1] & 0x80))
                    return where(e, r) + "has a negative list count";
                const std::uint64_t item = p.type->bytes;
                if (n > left / item)
                    return where(e, r) + "lists " + std::to_string(n) + " items of " + std::to_string(item) +
                           " bytes; only " + std::to_string(left) + " bytes are left";
                if (!bytes.skip(n * item)) return where(e, r) + "is cut short: the file ends";
                left -= n * item;
            }
    }
    return {};
}

/// Screens a PLY file before CGAL reads it (CGAL 5.5's PLY reader runs off its buffers on a
/// malformed element line and allocates whatever a list count says: tests/fuzz): "ply", a
/// format line, then only comment, obj_info, element NAME COUNT and property lines with PLY's
/// types (list counts of an integer type), up to end_header, with element counts the file's
/// size can hold; then the body, walked as declared (screen_ply_body). Returns why the file is
/// refused, or nothing.
inline std::string screen_ply(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    const std::uintmax_t bytes = ec ? 0 : size;
    const std::string at = path.string() + " line ";
    std::string line;
    std::string format;
    std::vector<ply_element> elements;
    std::size_t line_no = 0;
    while (std::getline(in, line) && line_no < 10000) {
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream split(line);
        std::vector<std::string> w;
        for (std::string x; split >> x;) w.push_back(x);
        const auto bad = [&](const std::string& why) { return at + std::to_string(line_no) + ": " + why; };
        if (line_no == 1) {
            if (line != "ply") return bad("expected 'ply'");
            continue;
        }
        if (line_no == 2) {
            if (w.size() != 3 || w[0] != "format" ||
                (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian") || w[2] != "1.0")
                return bad("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
            format = w[1];
            continue;
        }
        if (w.empty()) return bad("empty header line");
        if (w[0] == "comment" || w[0] == "obj_info") continue;
        if (w[0] == "end_header") {
            if (w.size() != 1) return bad("text after end_header");
            const auto body = in.tellg();
            const std::uint64_t left = body < 0 || static_cast<std::uintmax_t>(body) > bytes
                                           ? 0
                                           : bytes - static_cast<std::uintmax_t>(body);
            return screen_ply_body(in, format, elements, left, path.string());
        }
        if (w[0] == "element") {
            std::uint64_t n = 0;
            const bool digits = w.size() == 3 && !w[2].empty() && w[2].size() <= 19 &&
                                w[2].find_first_not_of("0123456789") == std::string::npos;
            if (!digits || std::from_chars(w[2].data(), w[2].data() + w[2].size(), n).ec != std::errc{})
                return bad("expected 'element NAME COUNT'");
            if (n > bytes) return bad("element count " + w[2] + " does not fit a file of " + std::to_string(bytes) + " bytes");
            elements.push_back({w[1], n, {}});
            continue;
        }
        if (w[0] == "property") {
            if (elements.empty()) return bad("a property before any element");
            if (const ply_type* type = w.size() == 3 ? find_ply_type(w[1]) : nullptr) {
                elements.back().properties.push_back({type, nullptr});
                continue;
            }
            const ply_type* count = w.size() == 5 && w[1] == "list" ? find_ply_type(w[2]) : nullptr;
            if (const ply_type* item = count ? find_ply_type(w[3]) : nullptr) {
                if (!count->integer) return bad("list count type '" + w[2] + "' is not an integer type");
                elements.back().properties.push_back({item, count});
                continue;
            }
            return bad("expected 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
        }
        return bad("unknown header line '" + line.substr(0, 40) + "'");
    }
    return path.string() + ": no end_header";
}

/// Why an ASCII OFF or OBJ file that CGAL refused is bad, naming the line and the value: a
/// coordinate that is not a finite number, a face index out of range, a short line. Empty when
/// it finds nothing (CGAL's reason then stands). Run only after a failed read.
inline std::string diagnose_ascii_mesh(const std::filesystem::path& path, const std::string& ext) {
    std::ifstream in(path);
    std::string line;
    std::size_t line_no = 0;
    const auto next_line = [&](std::istringstream& words) {
        while (std::getline(in, line)) {
            ++line_no;
            const auto hash = line.find('#');
            if (hash != std::string::npos) line.erase(hash);
            if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
            words = std::istringstream(line);
            return true;
        }
        return false;
    };
    const auto number = [](const std::string& w, double& v) {
        const char* b = w.data();
        const auto [end, ec] = std::from_chars(b, b + w.size(), v);
        return ec == std::errc{} && end == b + w.size();
    };
    const std::string at = path.string() + " line ";
    const auto where = [&] { return at + std::to_string(line_no) + ": "; };
    // Three finite coordinates for vertex v on the current line, or what is wrong.
    const auto bad_vertex = [&](std::istringstream& words, std::size_t v) -> std::string {
        for (int k = 0; k < 3; ++k) {
            std::string w;
            double x = 0;
            if (!(words >> w)) return where() + "vertex " + std::to_string(v) + " has " + std::to_string(k) + " coordinates, expected 3";
            if (!number(w, x) || !std::isfinite(x))
                return where() + "vertex " + std::to_string(v) + " has coordinate '" + w + "', not a finite number";
        }
        return {};
    };
    std::istringstream words;
    if (ext == ".off") {
        if (!next_line(words)) return {};
        std::string head;
        words >> head;
        if (head != "OFF") return {};
        std::size_t nv = 0, nf = 0;
        if (!(words >> nv >> nf) && (!next_line(words) || !(words >> nv >> nf)))
            return where() + "expected the vertex and face counts";
        for (std::size_t v = 0; v < nv; ++v) {
            if (!next_line(words)) return path.string() + ": ends after " + std::to_string(v) + " of " + std::to_string(nv) + " vertices";
            if (std::string why = bad_vertex(words, v); !why.empty()) return why;
        }
        for (std::size_t f = 0; f < nf; ++f) {
            if (!next_line(words)) return path.string() + ": ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces";
            long long n = 0;
            if (!(words >> n) || n < 1) return where() + "face " + std::to_string(f) + " has no valid vertex count";
            for (long long k = 0; k < n; ++k) {
                long long idx = 0;
                if (!(words >> idx)) return where() + "face " + std::to_string(f) + " has fewer than " + std::to_string(n) + " vertex indices";
                if (idx < 0 || static_cast<unsigned long long>(idx) >= nv)
                    return where() + "face " + std::to_string(f) + " refers to vertex " + std::to_string(idx) +
                           ", out of range (the file has " + std::to_string(nv) + " vertices)";
            }
        }
        return {};
    }
    if (ext == ".obj") {
        std::size_t nv = 0, nf = 0;
        while (next_line(words)) {
            std::string tag;
            words >> tag;
            if (tag == "v") {
                if (std::string why = bad_vertex(words, nv); !why.empty()) return why;
                ++nv;
            } else if (tag == "f") {
                for (std::string w; words >> w;) {
                    long long idx = 0;
                    const char* b = w.data();
                    const auto [end, ec] = std::from_chars(b, b + w.size(), idx);  // "7/3/2": the vertex is first
                    if (ec != std::errc{} || idx == 0 || (idx > 0 && static_cast<unsigned long long>(idx) > nv) ||
                        (idx < 0 && static_cast<unsigned long long>(-idx) > nv))
                        return where() + "face " + std::to_string(nf) + " refers to vertex '" + w +
                               "', out of range (" + std::to_string(nv) + " vertices so far; OBJ indices start at 1)";
                }
                ++nf;
            }
        }
    }
    return {};
}

inline std::string lowercase_extension(const std::filesystem::path& p) {
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    return ext;
}

}  // namespace detail::io

CERTIPOSE_DECL triangle_mesh read_mesh(const std::filesystem::path& path, const read_options& opt) {
    // Decimal parsing and scaling must round to nearest even when the caller holds an interval
    // rounding_guard (upward, "0.3" would parse to the next double up).
    const detail::round_to_nearest_scope nearest{};
    const std::string name = path.string();
    if (!(opt.scale > 0.0) || !std::isfinite(opt.scale))
        throw invalid_argument("scale", "read_mesh: scale must be finite and > 0, got " +
                                            detail::mesh::format(opt.scale));
    if (opt.weld_tolerance &&
        (!(*opt.weld_tolerance >= 0.0) || !std::isfinite(*opt.weld_tolerance)))
        throw invalid_argument("weld_tolerance",
                               "read_mesh: weld_tolerance must be finite and >= 0, got " +
                                   detail::mesh::format(*opt.weld_tolerance));

    const std::string ext = detail::io::lowercase_extension(path);
    if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl")
        throw io_error(name, "read_mesh: unknown mesh format '" + path.extension().string() +
                                 "' of " + name + " (supported: .off, .obj, .ply, .stl)");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw io_error(name, "read_mesh: no such file: " + name);
    if (!std::ifstream(path, std::ios::binary))
        throw io_error(name, "read_mesh: cannot open " + name);

    if (const std::string why = ext == ".off"   ? detail::io::screen_off(path)
                                : ext == ".ply" ? detail::io::screen_ply(path)
                                                : std::string{};
        !why.empty())
        throw io_error(name, "read_mesh: cannot parse " + why);

    triangle_soup soup;
    std::vector<std::vector<std::size_t>> polygons;
    bool ok = false;
    std::string cgal_says;
    try {
        if (ext == ".stl") {
            std::vector<detail::io::stl_point> points;
            ok = CGAL::IO::read_STL(name, points, polygons);
            soup.vertices.reserve(points.size());
            for (const auto& p : points) soup.vertices.emplace_back(p[0], p[1], p[2]);
        } else {
            std::vector<CGAL::Simple_cartesian<double>::Point_3> points;
            if (ext == ".off")
                ok = CGAL::IO::read_OFF(name, points, polygons);
            else if (ext == ".obj")
                ok = CGAL::IO::read_OBJ(name, points, polygons);
            else {
                const detail::io::captured_cerr quiet;
                ok = CGAL::IO::read_PLY(name, points, polygons);
                cgal_says = quiet.one_line();
            }
            soup.vertices.reserve(points.size());
            for (const auto& p : points) soup.vertices.emplace_back(p.x(), p.y(), p.z());
        }
    } catch (const std::exception& e) {  // e.g. bad_alloc on an absurd vertex count
        throw io_error(name, "read_mesh: cannot parse " + name + ": " + e.what());
    }
    const std::string format = ext.substr(1);
    if (!ok) {
        if (ext == ".off" || ext == ".obj")
            if (const std::string why = detail::io::diagnose_ascii_mesh(path, ext); !why.empty())
                throw io_error(name, "read_mesh: cannot parse " + why);
        throw io_error(name, "read_mesh: cannot parse " + name + " as " + format +
                                 (cgal_says.empty() ? std::string(" (malformed, truncated or an index out of range)")
                                                    : " (CGAL: " + cgal_says + ")"));
    }
    if (polygons.empty())
        throw io_error(name, "read_mesh: " + name + " contains no faces (empty, or not a " +
                                 format + " file)");

    soup.faces.reserve(polygons.size());
    for (std::size_t f = 0; f < polygons.size(); ++f) {
        const auto& poly = polygons[f];
        if (poly.size() != 3)
            throw mesh_error(name + ": face " + std::to_string(f) + " has " +
                             std::to_string(poly.size()) +
                             " vertices; only triangle meshes are supported (triangulate it "
                             "first, e.g. in MeshLab)");
        face_indices t{};
        for (int k = 0; k < 3; ++k) {
            if (poly[k] >= soup.vertices.size() ||
                poly[k] > std::numeric_limits<std::uint32_t>::max())
                throw mesh_error(name + ": face " + std::to_string(f) + " refers to vertex " +
                                 std::to_string(poly[k]) + ", out of range (the file has " +
                                 std::to_string(soup.vertices.size()) + " vertices)");
            t[k] = static_cast<std::uint32_t>(poly[k]);
        }
        soup.faces.push_back(t);
    }
    polygons.clear();

    try {
        triangle_mesh m =
            opt.weld_tolerance ? welded(soup, *opt.weld_tolerance) : triangle_mesh(std::move(soup));
        return opt.scale == 1.0 ? m : scaled(m, opt.scale);
    } catch (const mesh_error& e) {
        throw mesh_error(name + ": " + e.what());
    }
}

}  // namespace certipose

#endif  // CERTIPOSE_DETAIL_WITH_DEFINITIONS

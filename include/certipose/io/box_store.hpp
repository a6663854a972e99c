// certipose/io/box_store.hpp — boxes.cpbx, the compact binary box store of a whole-part run
// (docs/part.md#the-binary-box-store-boxescpbx): written beside (or instead of) boxes.jsonl, read back by
// certipose-plan, by C++ (`read_box_store`) and from Python with numpy alone
// (scripts/box_store.py).
//
// Little-endian throughout. A 32-byte header:
//   0  char[8]  magic "CPBOXES\0"
//   8  u32      version (1)
//  12  u32      header bytes (32)
//  16  u32      record bytes (104)
//  20  u32      flags: bit 0 set when occlusion was checked (as boxes.jsonl's "occlusion" field)
//  24  u64      the number of records (written when the store is complete; 0 in a store cut
//               short before that, which a reader then counts by size)
// then one 104-byte record per box, in facet order then box order (as boxes.jsonl):
//   0  u32      facet
//   4  u8       class: 0 valid, 1 boundary
//   5  u8       BOUNDARY reason (boundary_reason's value), 255 for a VALID box
//   6  u16      0
//   8  f64[6]   position  x_lo, x_hi, y_lo, y_hi, z_lo, z_hi   (metres)
//  56  f64[6]   orientation φ_lo, φ_hi, γ_lo, γ_hi, β_lo, β_hi (radians, ZXZ)
// The bounds are the certified interval bounds, bit for bit (no decimal round trip). A file whose
// size is not 32 + 104 × the recorded count is refused as truncated.
// numpy: np.dtype([("facet","<u4"),("cls","u1"),("reason","u1"),("pad","<u2"),
//                  ("position","<f8",(3,2)),("orientation","<f8",(3,2))]).
#pragma once

#include "certipose/error.hpp"
#include "certipose/io/part_files.hpp"
#include "certipose/io/result_document.hpp"
#include "certipose/part/part_solver.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>
#include <tuple>
#include <vector>

namespace certipose {

static_assert(std::endian::native == std::endian::little,
              "certipose/io/box_store.hpp writes its little-endian records as they are in memory");

/// The layout of boxes.cpbx (see the header comment).
struct box_store_layout {
    static constexpr char magic[8] = {'C', 'P', 'B', 'O', 'X', 'E', 'S', '\0'};
    static constexpr std::uint32_t version = 1;
    static constexpr std::uint32_t header_bytes = 32;
    static constexpr std::uint32_t record_bytes = 104;
    static constexpr std::uint32_t occlusion_checked_flag = 1;
    static constexpr std::uint8_t no_reason = 255;
};

namespace detail::box_store {

inline void put_u32(char* at, std::uint32_t v) { std::memcpy(at, &v, 4); }
inline std::uint32_t get_u32(const char* at) {
    std::uint32_t v;
    std::memcpy(&v, at, 4);
    return v;
}

/// One record, laid out as the header comment says.
inline void encode(char* out, std::size_t facet, const box_record& r) {
    std::memset(out, 0, box_store_layout::record_bytes);
    put_u32(out, static_cast<std::uint32_t>(facet));
    out[4] = static_cast<char>(r.cls == box_class::valid ? 0 : 1);
    out[5] = static_cast<char>(r.reason ? static_cast<std::uint8_t>(*r.reason) : box_store_layout::no_reason);
    std::array<double, 12> b{};
    for (std::size_t k = 0; k < 3; ++k) {
        b[2 * k] = r.position[k][0], b[2 * k + 1] = r.position[k][1];
        b[6 + 2 * k] = r.orientation[k][0], b[7 + 2 * k] = r.orientation[k][1];
    }
    std::memcpy(out + 8, b.data(), 96);
}

}  // namespace detail::box_store

/// A PartSink writing boxes.cpbx records to a binary stream, one facet at a time (the header
/// first, at construction). Throws invalid_argument for a facet index beyond 32 bits or a box with
/// a non-finite or empty bound, io_error when the stream fails.
template <Interval I>
class box_store_sink {
public:
    box_store_sink(std::ostream& out, bool occlusion_checked) : out_(&out) {
        char h[box_store_layout::header_bytes] = {};
        std::memcpy(h, box_store_layout::magic, 8);
        detail::box_store::put_u32(h + 8, box_store_layout::version);
        detail::box_store::put_u32(h + 12, box_store_layout::header_bytes);
        detail::box_store::put_u32(h + 16, box_store_layout::record_bytes);
        detail::box_store::put_u32(h + 20, occlusion_checked ? box_store_layout::occlusion_checked_flag : 0u);
        out_->write(h, sizeof h);
        check();
    }

    /// A sink appending to `out` at its current position: a new store (the header first) when
    /// that is 0, else the continuation of a store whose header and whole records `out` already
    /// holds up to there (a resumed run, io/run_journal.hpp).
    static box_store_sink append_to(std::ostream& out, bool occlusion_checked) {
        const auto at = static_cast<std::size_t>(out.tellp());
        if (at == 0) return box_store_sink(out, occlusion_checked);
        return box_store_sink(out, (at - box_store_layout::header_bytes) / box_store_layout::record_bytes);
    }

    void facet(const facet_outcome<I>& o) {
        if (o.record.index > 0xffffffffu)
            throw invalid_argument("facet", "boxes.cpbx: facet index " + std::to_string(o.record.index) +
                                                " does not fit the store's 32 bits");
        buffer_.resize(o.boxes.size() * box_store_layout::record_bytes);
        char* at = buffer_.data();
        for (const auto& b : o.boxes) {
            const box_record r = to_record(b);
            for (const auto* bounds : {&r.position, &r.orientation})
                for (const auto& c : *bounds)
                    if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !(c[0] <= c[1]))
                        throw invalid_argument("box", "boxes.cpbx: facet " + std::to_string(o.record.index) +
                                                          " has a box with a non-finite or empty interval");
            detail::box_store::encode(at, o.record.index, r);
            at += box_store_layout::record_bytes;
        }
        out_->write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
        records_ += o.boxes.size();
        check();
    }
    std::size_t records() const noexcept { return records_; }

    /// Writes the record count into the header (the stream must be seekable; a file is), so a
    /// reader can tell a store cut at a record boundary from a whole one. Call once, at the end.
    void finish() {
        const auto end = out_->tellp();
        const std::uint64_t n = records_;
        out_->seekp(24);
        out_->write(reinterpret_cast<const char*>(&n), 8);
        out_->seekp(end);
        check();
    }

private:
    box_store_sink(std::ostream& out, std::size_t records) : out_(&out), records_(records) {}
    void check() const {
        if (!*out_) throw io_error("boxes.cpbx", "boxes.cpbx: write failed (disk full?)");
    }
    std::ostream* out_;
    std::vector<char> buffer_;
    std::size_t records_ = 0;
};

/// Calls `visit(part_box)` for every record of `path` (a boxes.cpbx), in order, reading it in
/// chunks. Throws io_error(path) when it cannot be read, and invalid_argument naming the file and
/// the record ("boxes.cpbx: record 12: ...") for a bad header, a truncated file, an unknown class
/// or reason, or a non-finite or empty bound.
inline void read_box_store(const std::filesystem::path& path, const std::function<void(const part_box&)>& visit) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw io_error(path.string(), "read_box_store: cannot open " + path.string());
    const std::string name = path.filename().string();
    const auto bad = [&](const std::string& what) { throw invalid_argument("box store", name + ": " + what); };
    char h[box_store_layout::header_bytes];
    if (!in.read(h, sizeof h)) bad("shorter than its 32-byte header (not a certipose box store, or truncated)");
    if (std::memcmp(h, box_store_layout::magic, 8) != 0) bad("not a certipose box store (no CPBOXES magic)");
    using detail::box_store::get_u32;
    if (get_u32(h + 8) != box_store_layout::version)
        bad("version " + std::to_string(get_u32(h + 8)) + ", this reader knows version 1");
    if (get_u32(h + 12) != box_store_layout::header_bytes || get_u32(h + 16) != box_store_layout::record_bytes)
        bad("header of " + std::to_string(get_u32(h + 12)) + " bytes and records of " + std::to_string(get_u32(h + 16)) +
            " bytes; version 1 has 32 and 104");
    const bool occlusion_checked = (get_u32(h + 20) & box_store_layout::occlusion_checked_flag) != 0;
    std::uint64_t recorded = 0;
    std::memcpy(&recorded, h + 24, 8);
    {
        std::error_code ec;
        const auto size = std::filesystem::file_size(path, ec);
        if (!ec && recorded != 0 && size != box_store_layout::header_bytes + recorded * box_store_layout::record_bytes)
            bad("truncated: " + std::to_string(size) + " bytes hold " +
                std::to_string((size - box_store_layout::header_bytes) / box_store_layout::record_bytes) + " of the " +
                std::to_string(recorded) + " records its header counts");
    }
    constexpr std::size_t chunk = 4096;
    std::vector<char> buf(chunk * box_store_layout::record_bytes);
    std::size_t index = 0;
    while (in) {
        in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
        const auto got = static_cast<std::size_t>(in.gcount());
        if (got % box_store_layout::record_bytes != 0)
            bad("truncated: its last record has " + std::to_string(got % box_store_layout::record_bytes) + " of 104 bytes");
        for (std::size_t at = 0; at < got; at += box_store_layout::record_bytes, ++index) {
            const char* r = buf.data() + at;
            const auto where = [&] { return "record " + std::to_string(index) + ": "; };
            part_box b;
            b.facet = get_u32(r);
            b.occlusion_checked = occlusion_checked;
            const auto cls = static_cast<std::uint8_t>(r[4]), reason = static_cast<std::uint8_t>(r[5]);
            if (cls > 1) bad(where() + "unknown class " + std::to_string(cls));
            b.box.cls = cls == 0 ? box_class::valid : box_class::boundary;
            if (cls == 1) {
                if (reason >= boundary_reason_count) bad(where() + "unknown BOUNDARY reason " + std::to_string(reason));
                b.box.reason = static_cast<boundary_reason>(reason);
            } else if (reason != box_store_layout::no_reason) {
                bad(where() + "a VALID box with a BOUNDARY reason " + std::to_string(reason));
            }
            if (r[6] != 0 || r[7] != 0) bad(where() + "nonzero padding (a damaged record)");
            std::array<double, 12> v{};
            std::memcpy(v.data(), r + 8, 96);
            for (std::size_t k = 0; k < 3; ++k) {
                b.box.position[k] = {v[2 * k], v[2 * k + 1]};
                b.box.orientation[k] = {v[6 + 2 * k], v[7 + 2 * k]};
            }
            for (std::size_t k = 0; k < 12; k += 2)
                if (!std::isfinite(v[k]) || !std::isfinite(v[k + 1]) || !(v[k] <= v[k + 1]))
                    bad(where() + "a non-finite or empty interval");
            visit(b);
        }
    }
    if (in.bad()) throw io_error(path.string(), "read_box_store: read error in " + path.string());
}

/// The boxes of a certipose-part output folder whose summary says the run wrote `stores`
/// (settings.box_store: "jsonl", "binary" or "both"; a summary without it wrote boxes.jsonl):
/// boxes.cpbx when the run wrote it (it is read ~50× faster; with "both", boxes.jsonl when only
/// that one was kept), else boxes.jsonl. A store the summary does not name is never read: it may
/// be left from another run. Throws io_error when the file is missing.
inline void read_part_boxes(const std::filesystem::path& dir, const std::string& stores,
                            const std::function<void(const part_box&)>& visit) {
    std::error_code ec;
    if (stores == "binary" || (stores == "both" && std::filesystem::exists(dir / "boxes.cpbx", ec)))
        return read_box_store(dir / "boxes.cpbx", visit);
    return read_boxes_jsonl(dir / "boxes.jsonl", visit);
}

}  // namespace certipose

// tools/common/gzip_text.hpp: data files stored gzip-compressed (zlib, Debian zlib1g-dev),
// read the same way as plain ones.
//
//   const std::string text = cloudmath::tools::read_data_file("docs/data/truth_ground.csv.gz");
//   const std::string bytes = cloudmath::tools::gzip_compress(text);  // then write_file_atomically
//
// Why: the path-traced truths are CSV text (6 significant digits a value), 0.6 MB an image;
// gzip keeps every byte of the text (the reports regenerate to the byte) at about a third of
// the size, and zlib is on every Debian machine. Measured on the stored truths (160 x 90):
// 627 kB of text -> 221 kB at level 9, inflated in about 3 ms.
//
// read_data_file(path): the whole file; inflated when it starts with gzip's magic bytes
//   (1f 8b), so a plain file is read as it is. Throws std::runtime_error naming the path on
//   a file that cannot be read, a damaged or truncated stream, trailing bytes after it, or
//   more than max_inflated bytes of text (a guard against a corrupt length).
// gzip_compress(text, level): a gzip stream (RFC 1952) of text. Deterministic: no file name,
//   modification time 0, so the same text gives the same bytes with the same zlib.
// is_gzip(bytes): whether bytes start with gzip's magic.
#ifndef CLOUDMATH_TOOLS_COMMON_GZIP_TEXT_HPP
#define CLOUDMATH_TOOLS_COMMON_GZIP_TEXT_HPP

#include <algorithm>
#include <cstddef>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include <zlib.h>

namespace cloudmath::tools {

inline bool is_gzip(std::string_view bytes) {
    return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f && static_cast<unsigned char>(bytes[1]) == 0x8b;
}

namespace gzip_detail {

// zlib counts in uInt: feed and drain at most this much per call.
inline constexpr std::size_t chunk = std::size_t{1} << 20;

// windowBits 15 + 16: a gzip wrapper with a default header (no name, mtime 0).
inline constexpr int gzip_window_bits = 15 + 16;

}  // namespace gzip_detail

[[nodiscard]] inline std::string gzip_compress(std::string_view text, int level = 9) {
    namespace d = gzip_detail;
    z_stream z{};
    if (deflateInit2(&z, level, Z_DEFLATED, d::gzip_window_bits, 9, Z_DEFAULT_STRATEGY) != Z_OK)
        throw std::runtime_error("gzip: deflateInit2 failed (level " + std::to_string(level) + ")");
    std::string out;
    std::string buffer(d::chunk, '\0');
    std::size_t offset = 0;
    int status = Z_OK;
    do {
        const std::size_t feed = std::min(d::chunk, text.size() - offset);
        z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data() + offset));
        z.avail_in = static_cast<uInt>(feed);
        offset += feed;
        const int flush = offset == text.size() ? Z_FINISH : Z_NO_FLUSH;
        do {
            z.next_out = reinterpret_cast<Bytef*>(buffer.data());
            z.avail_out = static_cast<uInt>(buffer.size());
            status = deflate(&z, flush);
            if (status == Z_STREAM_ERROR) {
                deflateEnd(&z);
                throw std::runtime_error("gzip: deflate failed");
            }
            out.append(buffer.data(), buffer.size() - z.avail_out);
        } while (z.avail_out == 0);
    } while (status != Z_STREAM_END);
    deflateEnd(&z);
    return out;
}

// The text of one gzip stream; name is for the messages.
[[nodiscard]] inline std::string gunzip(std::string_view bytes, const std::string& name,
                                        std::size_t max_inflated = std::size_t{1} << 30) {
    namespace d = gzip_detail;
    z_stream z{};
    if (inflateInit2(&z, d::gzip_window_bits) != Z_OK) throw std::runtime_error(name + ": inflateInit2 failed");
    std::string out;
    std::string buffer(d::chunk, '\0');
    std::size_t offset = 0;
    int status = Z_OK;
    while (status != Z_STREAM_END) {
        if (z.avail_in == 0) {
            const std::size_t feed = std::min(d::chunk, bytes.size() - offset);
            if (feed == 0) {
                inflateEnd(&z);
                throw std::runtime_error(name + ": the gzip stream is truncated");
            }
            z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + offset));
            z.avail_in = static_cast<uInt>(feed);
            offset += feed;
        }
        z.next_out = reinterpret_cast<Bytef*>(buffer.data());
        z.avail_out = static_cast<uInt>(buffer.size());
        status = inflate(&z, Z_NO_FLUSH);
        if (status != Z_OK && status != Z_STREAM_END) {
            const std::string why = z.msg != nullptr ? z.msg : "error " + std::to_string(status);
            inflateEnd(&z);
            throw std::runtime_error(name + ": damaged gzip data (" + why + ")");
        }
        out.append(buffer.data(), buffer.size() - z.avail_out);
        if (out.size() > max_inflated) {
            inflateEnd(&z);
            throw std::runtime_error(name + ": inflates to more than " + std::to_string(max_inflated) + " bytes");
        }
    }
    const std::size_t left = z.avail_in + (bytes.size() - offset);
    inflateEnd(&z);
    if (left != 0) throw std::runtime_error(name + ": " + std::to_string(left) + " bytes after the end of the gzip stream");
    return out;
}

// See the top of the file.
[[nodiscard]] inline std::string read_data_file(const std::string& path, std::size_t max_inflated = std::size_t{1} << 30) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (in.bad()) throw std::runtime_error("cannot read " + path);
    std::string raw = std::move(bytes).str();
    if (!is_gzip(raw)) return raw;
    return gunzip(raw, path, max_inflated);
}

}  // namespace cloudmath::tools

#endif  // CLOUDMATH_TOOLS_COMMON_GZIP_TEXT_HPP

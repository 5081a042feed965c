#pragma once
// Compressed drawings (.svgz: an SVG file gzip-compressed, as Inkscape saves them and librsvg
// reads them), inflated through zlib within the same limit on size as any input.
#include <cstdint>
#include <string>
#include <string_view>

namespace curvemesh::base {

// Whether `bytes` begin as a gzip stream does (RFC 1952: 0x1f 0x8b), as librsvg tells a
// compressed drawing, whatever its file's name.
bool is_gzip(std::string_view bytes);

// The bytes a gzip stream holds (members one after another, as `cat a.gz b.gz` makes, read as
// one), at most `max_bytes` of them: beyond, it stops inflating (a small file that inflates to
// gigabytes costs no more memory than the limit) and throws InputFileError naming `path` and
// `limit_option`, as read_input_file does. A stream that is not gzip or ends early: InputFileError.
std::string gunzip(std::string_view compressed, std::uint64_t max_bytes, const std::string& path,
                   const std::string& limit_option);

}  // namespace curvemesh::base

#include "base/gzip.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <climits>

#include "base/files.hpp"

namespace curvemesh::base {

namespace {

// zlib's inflate state, ended however the reading ends.
class Inflater {
 public:
  Inflater() {
    // 16 + MAX_WBITS: a gzip header and trailer around the deflate data (zlib's inflateInit2).
    if (inflateInit2(&z_, 16 + MAX_WBITS) != Z_OK) throw std::bad_alloc();
  }
  ~Inflater() { inflateEnd(&z_); }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;
  z_stream& operator*() { return z_; }

 private:
  z_stream z_{};
};

}  // namespace

bool is_gzip(std::string_view bytes) {
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
         static_cast<unsigned char>(bytes[1]) == 0x8b;
}

std::string gunzip(std::string_view compressed, std::uint64_t max_bytes, const std::string& path,
                   const std::string& limit_option) {
  Inflater inflater;
  z_stream& z = *inflater;
  std::string out;
  std::array<unsigned char, 1 << 16> chunk;
  std::size_t fed = 0;  // bytes of `compressed` given to zlib, at most UINT_MAX at a time
  for (;;) {
    if (z.avail_in == 0 && fed < compressed.size()) {
      const std::size_t n = std::min<std::size_t>(compressed.size() - fed, UINT_MAX);
      z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data() + fed));
      z.avail_in = static_cast<uInt>(n);
      fed += n;
    }
    z.next_out = chunk.data();
    z.avail_out = static_cast<uInt>(chunk.size());
    const int status = inflate(&z, Z_NO_FLUSH);
    out.append(reinterpret_cast<const char*>(chunk.data()), chunk.size() - z.avail_out);
    if (out.size() > max_bytes)
      throw InputFileError(path + ": the drawing is larger than the limit of " + mebibytes(max_bytes) +
                           " once decompressed" + (limit_option.empty() ? "" : " (" + limit_option + " raises it)"));
    const bool input_left = z.avail_in > 0 || fed < compressed.size();
    if (status == Z_STREAM_END) {
      if (!input_left) return out;
      if (inflateReset(&z) != Z_OK) break;  // a further member follows
      continue;
    }
    if (status == Z_BUF_ERROR && !input_left)
      throw InputFileError(path + ": the compressed drawing ends early (a gzip stream cut short)");
    if (status != Z_OK && status != Z_BUF_ERROR) break;
  }
  throw InputFileError(path + ": not a valid gzip stream (" + std::string(z.msg ? z.msg : "zlib error") + ")");
}

}  // namespace curvemesh::base

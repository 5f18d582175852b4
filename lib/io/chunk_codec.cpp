#include "io/chunk_codec.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <mutex>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace frac::io {
namespace {

// HDF5's shuffle (H5Z_filter_shuffle) of a chunk of `chunk_bytes` bytes, whole elements of `size` bytes,
// that holds `in` and then zeros: byte k of element i goes to k·n + i (n elements in the chunk); the zeros'
// bytes are set as such, not moved.
void shuffle(std::span<const unsigned char> in, std::size_t size, std::size_t chunk_bytes, unsigned char* out) {
  const std::size_t n = chunk_bytes / size, filled = in.size() / size;
  const unsigned char* src = in.data();
  if (size == 8) {  // the common case, float64 and int64: one pass, eight output streams
    for (std::size_t i = 0; i < filled; ++i, src += 8)
      for (std::size_t k = 0; k < 8; ++k) out[k * n + i] = src[k];
  } else {
    for (std::size_t i = 0; i < filled; ++i, src += size)
      for (std::size_t k = 0; k < size; ++k) out[k * n + i] = src[k];
  }
  for (std::size_t k = 0; k < size; ++k) std::fill(out + k * n + filled, out + (k + 1) * n, 0);
}

// The stream is deflated in parts of this many bytes, each on its own (no match reaches back into the part
// before: with the run-length strategy, none reaches further than the byte before anyway) and in its own
// deflate blocks, so that the threads share a chunk; the parts do not depend on the thread count, nor does
// the stream.
constexpr std::size_t kPartBytes = 64 * 1024;

// A raw deflate stream of one thread, set up once (its state is ~270 KB) and reset for every part.
class Deflater {
 public:
  Deflater() {
    if (deflateInit2(&z_, 1, Z_DEFLATED, -15, 8, Z_RLE) != Z_OK) throw RuntimeError("zlib: cannot start deflate");
  }
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;
  ~Deflater() { deflateEnd(&z_); }
  // The deflate blocks of `in` into `out`: the last of the stream (`last`), or ending on a byte boundary after
  // an empty stored block (a sync flush), so that the next part's blocks can follow. A part that would not
  // compress (noise: the low mantissa bytes of doubles) goes into stored blocks, which cost a copy.
  void part(std::span<const unsigned char> in, bool last, std::vector<unsigned char>& out) {
    deflateReset(&z_);
    const bool store = incompressible(in);
    if (store != stored_) {
      if (deflateParams(&z_, store ? 0 : 1, store ? Z_DEFAULT_STRATEGY : Z_RLE) != Z_OK)
        throw RuntimeError("zlib: cannot set the deflate level");
      stored_ = store;
    }
    out.resize(compressBound(static_cast<uLong>(in.size())) + 16);
    z_.next_in = const_cast<unsigned char*>(in.data());  // (zlib's API is not const-correct; it only reads)
    z_.avail_in = static_cast<uInt>(in.size());
    z_.next_out = out.data();
    z_.avail_out = static_cast<uInt>(out.size());
    const int status = deflate(&z_, last ? Z_FINISH : Z_SYNC_FLUSH);
    if (status != (last ? Z_STREAM_END : Z_OK) || z_.avail_in != 0)
      throw RuntimeError("zlib: deflate failed (status " + std::to_string(status) + ")");
    out.resize(out.size() - z_.avail_out);
  }

 private:
  // Whether the bytes' entropy, which bounds what a code for single bytes saves, is above 7.9 bits a byte
  // (at most 1.25 % to gain; runs, which the run-length strategy would find, lower the entropy too).
  static bool incompressible(std::span<const unsigned char> in) {
    if (in.size() < 4096) return false;
    std::array<std::uint32_t, 256> count{};
    for (const unsigned char b : in) ++count[b];
    double sum = 0.0;  // Σ c·log2 c
    for (const std::uint32_t c : count)
      if (c > 0) sum += static_cast<double>(c) * std::log2(static_cast<double>(c));
    const auto n = static_cast<double>(in.size());
    const double entropy = std::log2(n) - sum / n;  // bits a byte
    return entropy > 7.9;
  }
  z_stream z_{};
  bool stored_ = false;  // the stream's level: 0 (stored) or 1 with the run-length strategy
};

// The calling thread's buffers: the shuffled chunk, the stream, the parts' deflate blocks.
struct CodecBuffers {
  std::vector<unsigned char> shuffled, stream;
  std::vector<std::vector<unsigned char>> parts;
};
thread_local CodecBuffers buffers;

}  // namespace

void release_codec_buffers() { buffers = CodecBuffers{}; }

std::span<const unsigned char> shuffle_deflate(std::span<const unsigned char> data, std::size_t element_size,
                                               std::size_t chunk_bytes) {
  if (element_size == 0 || chunk_bytes % element_size != 0 || data.size() % element_size != 0 ||
      data.size() > chunk_bytes)
    throw RuntimeError("shuffle_deflate: " + std::to_string(data.size()) + " bytes in a chunk of " +
                       std::to_string(chunk_bytes) + " are not whole elements of " + std::to_string(element_size));
  auto& [shuffled, stream, parts] = buffers;
  std::span<const unsigned char> input = data;
  if (element_size > 1 || data.size() < chunk_bytes) {  // (a shuffle of single bytes moves none: HDF5 skips it)
    shuffled.resize(chunk_bytes);
    if (element_size > 1) {
      shuffle(data, element_size, chunk_bytes, shuffled.data());
    } else {
      std::copy(data.begin(), data.end(), shuffled.begin());
      std::fill(shuffled.begin() + static_cast<std::ptrdiff_t>(data.size()), shuffled.end(), 0);
    }
    input = shuffled;
  }
  // The parts on the threads, each with its Adler-32 checksum; then the zlib stream: header, the parts in
  // order, the checksum of the whole (RFC 1950).
  const std::size_t count = std::max<std::size_t>(1, (chunk_bytes + kPartBytes - 1) / kPartBytes);
  if (parts.size() < count) parts.resize(count);
  auto& out = parts;  // (this thread's buffers: a thread_local named in the region would be each thread's own)
  std::vector<uLong> adler(count);
  std::exception_ptr error;
  std::mutex error_mutex;
  std::atomic<std::size_t> next{0};  // (the parts dealt out one at a time, to whichever thread is free)
  as_team(count > 1, [&] {
    for (std::size_t p; (p = next.fetch_add(1, std::memory_order_relaxed)) < count;) {
      try {
        thread_local Deflater deflater;
        const auto in = input.subspan(p * kPartBytes, std::min(kPartBytes, chunk_bytes - p * kPartBytes));
        deflater.part(in, p + 1 == count, out[p]);
        adler[p] = adler32(adler32(0, nullptr, 0), in.data(), static_cast<uInt>(in.size()));
      } catch (...) {  // (no exception may leave the team: the first is rethrown after it)
        const std::lock_guard lock(error_mutex);
        if (!error) error = std::current_exception();
      }
    }
  });
  if (error) std::rethrow_exception(error);
  stream.assign({0x78, 0x01});  // deflate, 32 KiB window, fastest level; (0x7801 % 31 == 0)
  uLong checksum = adler32(0, nullptr, 0);
  for (std::size_t p = 0; p < count; ++p) {
    stream.insert(stream.end(), parts[p].begin(), parts[p].end());
    const std::size_t size = std::min(kPartBytes, chunk_bytes - p * kPartBytes);
    checksum = adler32_combine(checksum, adler[p], static_cast<z_off_t>(size));
  }
  for (int shift = 24; shift >= 0; shift -= 8) stream.push_back(static_cast<unsigned char>(checksum >> shift));
  return stream;
}

}  // namespace frac::io

// io/chunk_codec: the chunks that io/series encodes itself must decode, with zlib's inflate and HDF5's
// un-shuffle, to exactly the chunk's bytes, and must not depend on the thread count.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "io/chunk_codec.hpp"
#include "test_support.hpp"

using namespace frac;

namespace {

// What HDF5 does on reading: inflate (zlib stream, checksum checked), then un-shuffle.
std::vector<unsigned char> decode(std::span<const unsigned char> stream, std::size_t element_size,
                                  std::size_t chunk_bytes) {
  std::vector<unsigned char> shuffled(chunk_bytes + 1);  // (one byte more: a stream too long shows)
  uLongf size = static_cast<uLongf>(shuffled.size());
  EXPECT_EQ(uncompress(shuffled.data(), &size, stream.data(), static_cast<uLong>(stream.size())), Z_OK);
  EXPECT_EQ(size, chunk_bytes);
  std::vector<unsigned char> out(chunk_bytes);
  const std::size_t n = chunk_bytes / element_size;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < element_size; ++k) out[i * element_size + k] = shuffled[k * n + i];
  return out;
}

// Doubles with noisy mantissas (as cell positions are) and some runs, `count` of them.
std::vector<unsigned char> sample_doubles(std::size_t count) {
  std::vector<double> v(count);
  std::uint64_t s = 12345;
  for (std::size_t i = 0; i < count; ++i) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    v[i] = (i % 97 < 10) ? 0.0 : 0.2 * static_cast<double>(s >> 11) / 9007199254740992.0 - 0.1;
  }
  std::vector<unsigned char> bytes(count * sizeof(double));
  std::memcpy(bytes.data(), v.data(), bytes.size());
  return bytes;
}

}  // namespace

TEST(ChunkCodec, DecodesToTheChunkWithZerosAfterTheData) {
  // Chunks of one part and of several (64 KiB parts, the last one short), full or partly filled, of 8-byte
  // and 1-byte elements.
  for (const std::size_t elements : {std::size_t{100}, std::size_t{8192}, std::size_t{65536}, std::size_t{70001}}) {
    for (const std::size_t element_size : {std::size_t{8}, std::size_t{1}}) {
      const std::size_t chunk_bytes = elements * element_size;
      auto data = sample_doubles((chunk_bytes + 7) / 8);
      data.resize(chunk_bytes);
      for (const std::size_t filled : {elements, elements / 3, std::size_t{0}}) {
        const std::span<const unsigned char> in(data.data(), filled * element_size);
        const auto stream = io::shuffle_deflate(in, element_size, chunk_bytes);
        const std::vector<unsigned char> copy(stream.begin(), stream.end());
        const auto out = decode(copy, element_size, chunk_bytes);
        ASSERT_EQ(out.size(), chunk_bytes);
        for (std::size_t b = 0; b < chunk_bytes; ++b)
          ASSERT_EQ(out[b], b < in.size() ? in[b] : 0)
              << "byte " << b << " of " << chunk_bytes << ", " << filled << " elements of " << element_size;
      }
    }
  }
}

TEST(ChunkCodec, SameStreamOnAnyThreadCountAndSmallerThanTheData) {
  const auto data = sample_doubles(65536);  // 512 KiB: 8 parts
  std::vector<std::vector<unsigned char>> streams;
  for (const int threads : {1, 2, 3}) {
    const test::ThreadCount thread_count(threads);
    const auto s = io::shuffle_deflate(data, 8, data.size());
    streams.emplace_back(s.begin(), s.end());
  }
  EXPECT_EQ(streams[0], streams[1]);
  EXPECT_EQ(streams[0], streams[2]);
  // The shuffled exponent bytes and the zeros compress (ratio ~1.2 on these values); the noise does not.
  EXPECT_LT(static_cast<double>(streams[0].size()), 0.9 * static_cast<double>(data.size()));
}

TEST(ChunkCodec, RefusesPartialElements) {
  const std::vector<unsigned char> data(12);
  EXPECT_THROW(io::shuffle_deflate(data, 8, 16), RuntimeError);
  EXPECT_THROW(io::shuffle_deflate(data, 8, 8), RuntimeError);
}

TEST(ChunkCodec, NoiseGoesIntoStoredBlocksAndTheRestIsCompressed) {
  // 512 KiB of bytes: 256 KiB of noise (4 parts), then 256 KiB of short runs of a few values. The noise is
  // stored (a copy: its size, plus a 5-byte header per stored block of at most 65535 bytes); the runs compress
  // to a small fraction; both decode to the data.
  const std::size_t half = 256 * 1024;
  std::vector<unsigned char> data(2 * half);
  std::uint64_t s = 99;
  for (std::size_t i = 0; i < half; ++i) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    data[i] = static_cast<unsigned char>(s >> 56);
  }
  for (std::size_t i = half; i < data.size(); ++i) data[i] = static_cast<unsigned char>((i / 64) % 4);
  const auto stream = io::shuffle_deflate(data, 1, data.size());
  const std::vector<unsigned char> copy(stream.begin(), stream.end());
  EXPECT_EQ(decode(copy, 1, data.size()), data);
  // The first block, after the zlib header: not final, type 00 (stored), then (byte-aligned) its length.
  ASSERT_GT(copy.size(), 7u);
  EXPECT_EQ(copy[2] & 0x07, 0);
  EXPECT_EQ(copy[3] | copy[4] << 8, 65535);
  const double stored_noise = static_cast<double>(half) + 5.0 * 8;  // 4 parts, two blocks each
  EXPECT_GT(static_cast<double>(copy.size()), static_cast<double>(half));
  EXPECT_LT(static_cast<double>(copy.size()), stored_noise + 0.05 * static_cast<double>(half));
}

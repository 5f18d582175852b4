#pragma once
// HDF5's "shuffle, then deflate" filter pipeline, applied by us to whole chunks that go to the file through
// H5Dwrite_chunk (io/series.cpp). Every HDF5 reader decodes them with the dataset's own pipeline (un-deflate,
// un-shuffle), as if the library had encoded them.
//
// Why not the library's own filters: HDF5's deflate filter calls zlib at the dataset's level with the default
// strategy, which reaches 50-60 MB/s on the shuffled bytes of float64 trajectories here (their mantissas are
// noise), so the paper-scale explosion spent 0.13 s of its 1.1 s writing 4 MB of frames. Deflate with zlib's
// run-length strategy (Z_RLE: runs of one byte, which is what the shuffled exponent and high mantissa bytes
// are) runs ~3 times as fast for a ratio within a few per cent of level 1's (1.16 against 1.23 on cell
// positions, 1.15 against 1.14 on beam strains); the stream is a standard zlib stream either way.
#include <cstddef>
#include <span>

namespace frac::io {

// The zlib stream of a chunk of `chunk_bytes` bytes that holds `data` (a whole number of elements of
// `element_size` bytes) followed by zeros (a chunk that is not full), shuffled as HDF5's shuffle filter does
// (byte k of every element, for k = 0 .. element_size − 1, one after another) and deflated with the
// run-length strategy. The result lives in a buffer of the calling thread, valid until its next call.
std::span<const unsigned char> shuffle_deflate(std::span<const unsigned char> data, std::size_t element_size,
                                               std::size_t chunk_bytes);

// Frees the calling thread's buffers of shuffle_deflate (the span it returned dies): after a large chunk, so that
// they do not hold three times its size until the next one.
void release_codec_buffers();
inline constexpr std::size_t kKeptCodecBytes = std::size_t{1} << 22;  // chunks up to this size keep them

}  // namespace frac::io

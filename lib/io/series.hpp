#pragma once
// H5MD time series, written frame by frame: a group <name> holding step [T] (int64), time [T] (s) and
// value [T, ...] (one frame of fixed shape per entry), extendible, chunked and compressed, so a run can
// append frames as it goes and never holds its trajectory in memory. Frames are buffered up to one chunk of
// the value dataset (at most 64 Ki values) and written a chunk at a time: one HDF5 write per chunk instead of
// three per frame (an observable sampled every few steps otherwise costs more than the step). A compressed
// value chunk (frames of 64 values or more) is encoded here (io/chunk_codec) and written whole with
// H5Dwrite_chunk; a frame that fills a chunk by itself is encoded from the caller's memory, without a copy.
// flush() writes what is buffered (a partly filled chunk is kept and written again, whole, when it fills);
// the owner calls it before the file is closed. Read back whole, or one frame.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "io/checksum.hpp"
#include "io/hdf5.hpp"

namespace frac::io {

enum class SeriesType { float64, int64, uint8 };

class SeriesWriter {
 public:
  // Creates <parent>/<name>/{step,time,value}; `frame_dims` is the shape of one frame ({} = a scalar).
  SeriesWriter(Group& parent, std::string_view name, std::vector<hsize_t> frame_dims, std::string_view unit,
               SeriesType type = SeriesType::float64);
  void append(std::int64_t step, double time, std::span<const double> frame);
  void append(std::int64_t step, double time, std::span<const std::uint8_t> frame);
  void append(std::int64_t step, double time, std::span<const std::int64_t> frame);
  // Writes the buffered frames to the file.
  void flush();
  // Appends every frame of the series <parent>/<name> (a checkpoint's copy of this series): InputError if its
  // frames have another shape, or if they do not match the checksum its group carries (attribute "checksum").
  void replay(const Group& parent, std::string_view name);
  std::size_t frames() const { return frames_; }  // appended, written or not
  // A running checksum (io/checksum) of every frame appended (step, time, values): a checkpoint keeps it with its
  // copy of the series, and replay() checks the copy against it.
  std::uint64_t checksum() const { return checksum_.h; }

 private:
  void append_raw(std::int64_t step, double time, hid_t mem_type, const void* frame, std::size_t count);
  // The step and time of the frames after the ones in the file (`rows` of them).
  void write_steps(const std::int64_t* step, const double* time, std::size_t rows);
  // The value chunk that starts at frame `first`, from `rows` frames of values (compressed: encoded and written
  // whole, padded with zeros to a full chunk; else: those frames written after the ones in the file).
  void write_values(std::size_t first, const void* values, std::size_t rows);
  Group group_;
  Hid step_, time_, value_;
  std::vector<hsize_t> frame_dims_;
  SeriesType type_;
  std::size_t frame_size_ = 1;
  hid_t value_type_ = -1;  // memory type of the values (the native type of the series' file type)
  std::size_t value_bytes_ = 0;
  bool compressed_ = false;  // value chunks are encoded here and written whole
  Checksum checksum_;
  std::size_t frames_ = 0;   // appended
  std::size_t written_ = 0;  // in the file
  std::size_t rows_per_chunk_ = 1;
  std::size_t chunk_first_ = 0;              // first frame of the chunk being filled, whose values are buffered
  std::vector<std::int64_t> step_buffer_;    // frames [written_, frames_)
  std::vector<double> time_buffer_;          // frames [written_, frames_)
  std::vector<unsigned char> value_buffer_;  // frames [chunk_first_, frames_)
};

struct SeriesInfo {
  std::vector<std::int64_t> step;
  std::vector<double> time;
  std::vector<hsize_t> frame_dims;
};
// Steps, times and frame shape of the series <parent>/<name>; InputError naming it if malformed.
SeriesInfo read_series_info(const Group& parent, std::string_view name);
// One frame (index into step/time; negative counts from the end) of a series, converted to T.
template <class T>
std::vector<T> read_series_frame(const Group& parent, std::string_view name, long long frame);

}  // namespace frac::io

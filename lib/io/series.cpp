#include "io/series.hpp"

#include <algorithm>
#include <new>
#include <type_traits>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "io/atomic_file.hpp"

namespace frac::io {
namespace {

// Rows per chunk of a series whose frames hold `frame` values: about 64 Ki values, many small frames per
// chunk, or one large frame.
hsize_t chunk_rows(hsize_t frame) {
  return std::max<hsize_t>(1, std::min<hsize_t>(1024, (1u << 16) / std::max<hsize_t>(frame, 1)));
}

Hid create_extendible(const Group& g, const char* name, hid_t file_type, const std::vector<hsize_t>& frame_dims,
                      bool compress) {
  std::vector<hsize_t> dims{0}, maxdims{H5S_UNLIMITED}, chunk{1};
  hsize_t frame = 1;
  for (auto d : frame_dims) {
    dims.push_back(d);
    maxdims.push_back(d);
    chunk.push_back(std::max<hsize_t>(d, 1));
    frame *= d;
  }
  chunk[0] = chunk_rows(frame);
  Hid space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data()));
  Hid dcpl(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_obj_track_times(dcpl.get(), 0);
  H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data());
  if (compress) {
    H5Pset_shuffle(dcpl.get());
    H5Pset_deflate(dcpl.get(), 1);
  }
  Hid d(H5Dcreate2(g.id(), name, file_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT));
  if (d.get() < 0)
    throw RuntimeError(g.where(name) + ": cannot create dataset (" + write_failure(g.file(), errno) + ")");
  return d;
}

// Writes `rows` rows from `data` at row `row`, extending the dataset to row + rows.
void append_rows(const Group& g, const char* name, const Hid& d, hid_t mem_type, const void* data, std::size_t row,
                 std::size_t rows, const std::vector<hsize_t>& frame_dims) {
  std::vector<hsize_t> dims{row + rows}, start{row}, count{rows};
  for (auto fd : frame_dims) {
    dims.push_back(fd);
    start.push_back(0);
    count.push_back(fd);
  }
  if (H5Dset_extent(d.get(), dims.data()) < 0)
    throw RuntimeError(g.where(name) + ": cannot extend dataset (" + write_failure(g.file(), errno) + ")");
  Hid fspace(H5Dget_space(d.get()));
  H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
  Hid mspace(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr));
  if (H5Dwrite(d.get(), mem_type, mspace.get(), fspace.get(), H5P_DEFAULT, data) < 0)
    throw RuntimeError(g.where(name) + ": cannot write frames " + std::to_string(row) + " to " +
                       std::to_string(row + rows - 1) + " (" + write_failure(g.file(), errno) + ")");
}

}  // namespace

SeriesWriter::SeriesWriter(Group& parent, std::string_view name, std::vector<hsize_t> frame_dims, std::string_view unit,
                           SeriesType type)
    : group_(parent.create_group(name)), frame_dims_(std::move(frame_dims)), type_(type) {
  for (auto d : frame_dims_) frame_size_ *= d;
  rows_per_chunk_ = chunk_rows(frame_size_);
  step_ = create_extendible(group_, "step", H5T_STD_I64LE, {}, false);
  time_ = create_extendible(group_, "time", H5T_IEEE_F64LE, {}, false);
  const hid_t ftype = type == SeriesType::float64 ? H5T_IEEE_F64LE
                      : type == SeriesType::int64 ? H5T_STD_I64LE
                                                  : H5T_STD_U8LE;
  value_type_ = type == SeriesType::float64 ? H5T_NATIVE_DOUBLE
                : type == SeriesType::int64 ? H5T_NATIVE_INT64
                                            : H5T_NATIVE_UINT8;
  value_bytes_ = type == SeriesType::uint8 ? 1 : 8;
  const bool compress = frame_size_ >= 64;
  value_ = create_extendible(group_, "value", ftype, frame_dims_, compress);
  compressed_ = compress && encodes_chunks(value_type_, ftype);
  // The frames of a chunk are buffered until it is full: room for them at once (no copies as it grows).
  if (rows_per_chunk_ > 1) value_buffer_.reserve(rows_per_chunk_ * frame_size_ * value_bytes_);
  group_.set_attr("unit", "s", "time");
  if (!unit.empty()) group_.set_attr("unit", unit, "value");
}

void SeriesWriter::append_raw(std::int64_t step, double time, hid_t mem_type, const void* frame, std::size_t count) {
  if (count != frame_size_)
    throw RuntimeError(group_.where("value") + ": frame of " + std::to_string(count) + " values, expected " +
                       std::to_string(frame_size_));
  if (H5Tequal(mem_type, value_type_) <= 0)
    throw RuntimeError(group_.where("value") + ": frame of another type than the series'");
  checksum_.add_value(step);
  checksum_.add_value(time);
  checksum_.add(frame, count * value_bytes_);
  if (rows_per_chunk_ == 1) {
    // A frame fills a chunk: written at once, from the caller's memory (no copy of a large frame).
    write_steps(&step, &time, 1);
    write_values(frames_, frame, 1);
    written_ = ++frames_;
    chunk_first_ = frames_;
    return;
  }
  step_buffer_.push_back(step);
  time_buffer_.push_back(time);
  const auto* bytes = static_cast<const unsigned char*>(frame);
  value_buffer_.insert(value_buffer_.end(), bytes, bytes + count * value_bytes_);
  ++frames_;
  if (frames_ - chunk_first_ >= rows_per_chunk_) flush();
}

void SeriesWriter::write_steps(const std::int64_t* step, const double* time, std::size_t rows) {
  append_rows(group_, "step", step_, H5T_NATIVE_INT64, step, written_, rows, {});
  append_rows(group_, "time", time_, H5T_NATIVE_DOUBLE, time, written_, rows, {});
}

void SeriesWriter::write_values(std::size_t first, const void* values, std::size_t rows) {
  if (!compressed_) {
    append_rows(group_, "value", value_, value_type_, values, first, rows, frame_dims_);
    return;
  }
  std::vector<hsize_t> dims{first + rows}, offset{first};
  for (auto d : frame_dims_) {
    dims.push_back(d);
    offset.push_back(0);
  }
  if (H5Dset_extent(value_.get(), dims.data()) < 0)
    throw RuntimeError(group_.where("value") + ": cannot extend dataset (" + write_failure(group_.file(), errno) + ")");
  const std::size_t row_bytes = frame_size_ * value_bytes_;  // (a chunk not yet full is encoded with zeros)
  if (write_encoded_chunk(value_.get(), offset, {static_cast<const unsigned char*>(values), rows * row_bytes},
                          value_bytes_, rows_per_chunk_ * row_bytes) < 0)
    throw RuntimeError(group_.where("value") + ": cannot write frames " + std::to_string(first) + " to " +
                       std::to_string(first + rows - 1) + " (" + write_failure(group_.file(), errno) + ")");
}

void SeriesWriter::flush() {
  const std::size_t rows = frames_ - written_;
  if (rows == 0) return;
  write_steps(step_buffer_.data(), time_buffer_.data(), rows);
  write_values(chunk_first_, value_buffer_.data(), frames_ - chunk_first_);
  written_ = frames_;
  step_buffer_.clear();
  time_buffer_.clear();
  // A partly filled compressed chunk stays buffered: the frames still to come are encoded with it.
  if (!compressed_ || frames_ - chunk_first_ >= rows_per_chunk_) {
    value_buffer_.clear();
    chunk_first_ = frames_;
  }
}

void SeriesWriter::append(std::int64_t step, double time, std::span<const double> frame) {
  append_raw(step, time, H5T_NATIVE_DOUBLE, frame.data(), frame.size());
}
void SeriesWriter::append(std::int64_t step, double time, std::span<const std::uint8_t> frame) {
  append_raw(step, time, H5T_NATIVE_UINT8, frame.data(), frame.size());
}
void SeriesWriter::append(std::int64_t step, double time, std::span<const std::int64_t> frame) {
  append_raw(step, time, H5T_NATIVE_INT64, frame.data(), frame.size());
}

SeriesInfo read_series_info(const Group& parent, std::string_view name) {
  const Group g = parent.group(name);
  SeriesInfo info;
  info.step = g.read<std::int64_t>("step", nullptr, 1);
  info.time = g.read<double>("time", nullptr, 1);
  if (info.step.size() != info.time.size()) throw InputError(g.where() + ": step and time have different lengths");
  Hid d(H5Dopen2(g.id(), "value", H5P_DEFAULT));
  if (d.get() < 0) throw InputError(g.where("value") + ": no such dataset");
  Hid space(H5Dget_space(d.get()));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  if (dims.empty() || dims[0] != info.step.size())
    throw InputError(g.where("value") + ": its first dimension does not match step");
  info.frame_dims.assign(dims.begin() + 1, dims.end());
  return info;
}

template <class T>
std::vector<T> read_series_rows(const Group& parent, std::string_view name, const SeriesInfo& info, std::size_t first,
                                std::size_t count) {
  const Group g = parent.group(name);
  if (first > info.step.size() || count > info.step.size() - first)
    throw InputError(g.where() + ": no frames " + std::to_string(first) + " to " + std::to_string(first + count) +
                     " (it has " + std::to_string(info.step.size()) + ")");
  Hid d(H5Dopen2(g.id(), "value", H5P_DEFAULT));
  Hid ftype(H5Dget_type(d.get()));
  if (d.get() < 0 || ftype.get() < 0) throw InputError(g.where("value") + ": damaged dataset");
  require_number_type(ftype.get(), !std::is_same_v<T, double>, g.where("value"));
  std::vector<hsize_t> start{static_cast<hsize_t>(first)}, counts{static_cast<hsize_t>(count)};
  hsize_t size = count;
  for (auto fd : info.frame_dims) {
    start.push_back(0);
    counts.push_back(fd);
    if (fd != 0 && size > (hsize_t{1} << 40) / fd) throw InputError(g.where("value") + ": damaged dataspace");
    size *= fd;
  }
  require_fits_storage(d.get(), ftype.get(), size, g.where("value"));
  Hid fspace(H5Dget_space(d.get()));
  H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start.data(), nullptr, counts.data(), nullptr);
  Hid mspace(H5Screate_simple(static_cast<int>(counts.size()), counts.data(), nullptr));
  std::vector<T> out;
  try {
    out.resize(size);
  } catch (const std::bad_alloc&) {
    throw OutOfMemory("reading " + g.where("value"), size * sizeof(T));
  }
  hid_t mem = std::is_same_v<T, double>         ? H5T_NATIVE_DOUBLE
              : std::is_same_v<T, std::int64_t> ? H5T_NATIVE_INT64
                                                : H5T_NATIVE_UINT8;
  if (size > 0 && H5Dread(d.get(), mem, mspace.get(), fspace.get(), H5P_DEFAULT, out.data()) < 0)
    read_failed(g.where("value"),
                "cannot read frames " + std::to_string(first) + " to " + std::to_string(first + count - 1),
                size * sizeof(T));
  return out;
}

template <class T>
std::vector<T> read_series_frame(const Group& parent, std::string_view name, long long frame) {
  const SeriesInfo info = read_series_info(parent, name);
  const auto frames = static_cast<long long>(info.step.size());
  const long long k = frame < 0 ? frames + frame : frame;
  if (k < 0 || k >= frames)
    throw InputError(parent.group(name).where() + ": no frame " + std::to_string(frame) + " (it has " +
                     std::to_string(frames) + ")");
  return read_series_rows<T>(parent, name, info, static_cast<std::size_t>(k), 1);
}

void SeriesWriter::replay(const Group& parent, std::string_view name) {
  const SeriesInfo info = read_series_info(parent, name);
  const Group copy = parent.group(name);
  if (!copy.has_attr("checksum")) throw InputError(copy.where() + ": no checksum (not a checkpoint's copy)");
  if (info.frame_dims != frame_dims_)
    throw InputError(parent.group(name).where() + ": frames of another shape than this run's");
  const std::size_t frames = info.step.size();
  for (std::size_t first = 0; first < frames; first += rows_per_chunk_) {
    const std::size_t rows = std::min(rows_per_chunk_, frames - first);
    auto append_rows_of = [&](const auto& values, hid_t mem_type) {
      for (std::size_t r = 0; r < rows; ++r)
        append_raw(info.step[first + r], info.time[first + r], mem_type, values.data() + r * frame_size_, frame_size_);
    };
    switch (type_) {
      case SeriesType::float64:
        append_rows_of(read_series_rows<double>(parent, name, info, first, rows), H5T_NATIVE_DOUBLE);
        break;
      case SeriesType::int64:
        append_rows_of(read_series_rows<std::int64_t>(parent, name, info, first, rows), H5T_NATIVE_INT64);
        break;
      case SeriesType::uint8:
        append_rows_of(read_series_rows<std::uint8_t>(parent, name, info, first, rows), H5T_NATIVE_UINT8);
        break;
    }
  }
  if (static_cast<std::int64_t>(checksum_.h) != copy.attr_int("checksum"))
    throw InputError(copy.where() + ": damaged (its frames do not match their checksum)");
}

template std::vector<double> read_series_frame<double>(const Group&, std::string_view, long long);
template std::vector<std::int64_t> read_series_frame<std::int64_t>(const Group&, std::string_view, long long);
template std::vector<std::uint8_t> read_series_frame<std::uint8_t>(const Group&, std::string_view, long long);

}  // namespace frac::io

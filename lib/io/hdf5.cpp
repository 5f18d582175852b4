#include "io/hdf5.hpp"

#include <hdf5_hl.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <limits>
#include <type_traits>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "io/atomic_file.hpp"
#include "io/chunk_codec.hpp"
#include "io/hdf5_image.hpp"
#include "io/hdf5_probe.hpp"

namespace frac::io {

Hid::Hid(hid_t id) : id_(id) {}

Hid& Hid::operator=(Hid&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = o.id_;
    o.id_ = H5I_INVALID_HID;
  }
  return *this;
}

namespace {
// Whether `id` belongs to a file open for reading only (not when its file is unknown: half closed).
bool in_read_only_file(hid_t id) {
  const hid_t file = H5Iget_file_id(id);
  if (file < 0) return false;
  unsigned intent = 0;
  const bool read_only = H5Fget_intent(file, &intent) >= 0 && !(intent & H5F_ACC_RDWR);
  H5Idec_ref(file);
  return read_only;
}
}  // namespace

void Hid::reset() {
  if (id_ < 0) return;
  // An output abandoned by an exception (a failed write: a full disk) is not closed: libhdf5 1.10 may
  // crash flushing a file whose writes failed. Its temporary file is removed (io/atomic_file) and the
  // process is ending with the error.
  if (std::uncaught_exceptions() > 0 && H5Iis_valid(id_) > 0 && !in_read_only_file(id_)) {
    id_ = H5I_INVALID_HID;
    return;
  }
  if (H5Iis_valid(id_) > 0) {
    switch (H5Iget_type(id_)) {
      case H5I_FILE:
        H5Fclose(id_);
        break;
      case H5I_GROUP:
        H5Gclose(id_);
        break;
      case H5I_DATASET:
        H5Dclose(id_);
        break;
      case H5I_DATASPACE:
        H5Sclose(id_);
        break;
      case H5I_DATATYPE:
        H5Tclose(id_);
        break;
      case H5I_ATTR:
        H5Aclose(id_);
        break;
      case H5I_GENPROP_LST:
        H5Pclose(id_);
        break;
      default:
        H5Idec_ref(id_);
        break;
    }
  }
  id_ = H5I_INVALID_HID;
}

namespace {
// libhdf5 closes what is still open from an atexit handler; after a failed write (a full disk) a file
// that would not close makes that handler crash (H5F__close_cb). Every output is closed explicitly or
// abandoned (its temporary removed), so the handler has nothing to do: it is not installed. This must
// run before any other HDF5 call, hence a static initialiser.
const bool g_no_atexit = [] {
  H5dont_atexit();
  return true;
}();
}  // namespace

void silence_hdf5_errors() {
  (void)g_no_atexit;
  static const bool done = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

bool hdf5_out_of_memory() {
  bool found = false;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* e, void* data) -> herr_t {
        if (e->maj_num == H5E_RESOURCE || e->min_num == H5E_NOSPACE || e->min_num == H5E_CANTALLOC)
          *static_cast<bool*>(data) = true;
        return 0;
      },
      &found);
  return found;
}

void read_failed(const std::string& where, const std::string& why, std::size_t bytes) {
  if (hdf5_out_of_memory()) throw OutOfMemory("reading " + where, bytes);
  throw InputError(where + ": " + why);
}

namespace {

std::string join(const std::string& path, std::string_view name) {
  if (name.empty() || name == ".") return path;
  if (name.front() == '/') return std::string(name);
  return (path == "/" ? "/" : path + "/") + std::string(name);
}

Hid vlen_string_type() {
  Hid t(H5Tcopy(H5T_C_S1));
  H5Tset_size(t.get(), H5T_VARIABLE);
  H5Tset_cset(t.get(), H5T_CSET_UTF8);
  return t;
}

Hid simple_space(const std::vector<hsize_t>& dims) {
  if (dims.empty()) return Hid(H5Screate(H5S_SCALAR));
  return Hid(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr));
}

template <class T>
hid_t native_type();
template <>
hid_t native_type<double>() {
  return H5T_NATIVE_DOUBLE;
}
template <>
hid_t native_type<std::int64_t>() {
  return H5T_NATIVE_INT64;
}
template <>
hid_t native_type<std::uint8_t>() {
  return H5T_NATIVE_UINT8;
}

// Datasets at least this many elements are chunked and compressed (shuffle + deflate 1).
constexpr std::size_t kCompressFrom = 1u << 16;

// A transfer property list whose type-conversion buffers hold `count` elements of the larger of the two
// types, no more: HDF5's default (1 MiB, zeroed on every transfer that converts, such as variable-length
// strings) cost dem-run 24 ms of start-up for its provenance strings.
Hid transfer_for(hid_t mem_type, hid_t file_type, hsize_t count) {
  Hid dxpl(H5Pcreate(H5P_DATASET_XFER));
  const std::size_t element = std::max(H5Tget_size(mem_type), H5Tget_size(file_type));
  H5Pset_buffer(dxpl.get(), std::max<std::size_t>(element * std::max<hsize_t>(count, 1), 64), nullptr, nullptr);
  return dxpl;
}

// The number of elements of a dataset of shape `dims`, refused (InputError naming `where`) when the
// product overflows or the values cannot fit the dataset's storage (require_fits_storage).
hsize_t checked_extent(hid_t d, hid_t file_type, const std::vector<hsize_t>& dims, const std::string& where) {
  hsize_t count = 1;
  for (auto n : dims) {
    if (n != 0 && count > std::numeric_limits<hsize_t>::max() / n) throw InputError(where + ": damaged dataspace");
    count *= n;
  }
  if (count > 0) require_fits_storage(d, file_type, count, where);
  return count;
}

}  // namespace

bool standard_number_type(hid_t t) {
  // (a damaged integer or float description, its precision or offset, sends libhdf5's conversion out of
  // bounds: only the standard layouts are converted)
  for (hid_t s :
       {H5T_STD_I8LE,  H5T_STD_I16LE, H5T_STD_I32LE,  H5T_STD_I64LE,  H5T_STD_U8LE,   H5T_STD_U16LE, H5T_STD_U32LE,
        H5T_STD_U64LE, H5T_STD_I8BE,  H5T_STD_I16BE,  H5T_STD_I32BE,  H5T_STD_I64BE,  H5T_STD_U8BE,  H5T_STD_U16BE,
        H5T_STD_U32BE, H5T_STD_U64BE, H5T_IEEE_F32LE, H5T_IEEE_F64LE, H5T_IEEE_F32BE, H5T_IEEE_F64BE})
    if (H5Tequal(t, s) > 0) return true;
  return false;
}

void require_number_type(hid_t file_type, bool integers, const std::string& where) {
  const H5T_class_t cls = H5Tget_class(file_type);
  if (cls != H5T_INTEGER && cls != H5T_FLOAT) throw InputError(where + ": not a numeric dataset");
  if (!standard_number_type(file_type)) throw InputError(where + ": damaged or unusual number type");
  if (integers && cls != H5T_INTEGER)
    throw InputError(where + ": holds floating-point values where integers (indices, counts, flags) belong");
}

void require_fits_storage(hid_t d, hid_t file_type, hsize_t values, const std::string& where) {
  // Contiguous data takes exactly its size, compressed chunks at most 1/1032 of theirs (deflate's best
  // ratio): a damaged shape never drives an allocation.
  const std::size_t file_bytes = H5Tget_size(file_type);
  if (file_bytes == 0) throw InputError(where + ": damaged datatype");
  const hsize_t storage = H5Dget_storage_size(d);
  const hsize_t limit = std::numeric_limits<hsize_t>::max() / 2048 / std::max<std::size_t>(file_bytes, 8);
  if (values > limit || storage == 0 || values * file_bytes > 1100 * storage + (1u << 16))
    throw InputError(where + ": " + std::to_string(values) + " values do not fit the " + std::to_string(storage) +
                     " bytes the file holds for them (damaged file)");
}

bool encodes_chunks(hid_t mem_type, hid_t file_type) { return H5Tequal(mem_type, file_type) > 0; }

herr_t write_encoded_chunk(hid_t d, const std::vector<hsize_t>& offset, std::span<const unsigned char> data,
                           std::size_t element_size, std::size_t chunk_bytes) {
  const auto encoded = shuffle_deflate(data, element_size, chunk_bytes);
  const herr_t status = H5Dwrite_chunk(d, H5P_DEFAULT, 0, offset.data(), encoded.size(), encoded.data());
  if (chunk_bytes > kKeptCodecBytes) release_codec_buffers();
  return status;
}

Group::Group(Hid id, std::string file, std::string path, std::shared_ptr<void> keep_alive,
             std::shared_ptr<const WalkedStrings> walked)
    : keep_alive_(std::move(keep_alive)),
      walked_(std::move(walked)),
      hid_(std::move(id)),
      file_(std::move(file)),
      path_(std::move(path)) {}

std::string Group::where(std::string_view name) const { return file_ + ":" + join(path_, name); }

bool Group::has(std::string_view name) const {
  // H5Lexists needs every parent to exist: test the path one component at a time.
  if (name.empty()) return false;
  std::string prefix;
  std::size_t start = 0;
  if (name.front() == '/') {
    prefix.push_back('/');
    start = 1;
  }
  while (start < name.size()) {
    std::size_t slash = name.find('/', start);
    if (slash == std::string_view::npos) slash = name.size();
    if (slash > start) {
      if (!prefix.empty() && prefix.back() != '/') prefix.push_back('/');
      prefix.append(name.data() + start, slash - start);
      if (H5Lexists(id(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    }
    start = slash + 1;
  }
  return true;
}

Group Group::group(std::string_view name) const {
  if (!has(name)) throw InputError(where(name) + ": no such group");
  Hid g(H5Gopen2(id(), std::string(name).c_str(), H5P_DEFAULT));
  if (g.get() < 0) throw InputError(where(name) + ": not a group");
  return Group(std::move(g), file_, join(path_, name), keep_alive_, walked_);
}

Group Group::create_group(std::string_view name) {
  if (has(name)) return group(name);
  Hid lcpl(H5Pcreate(H5P_LINK_CREATE));
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  Hid gcpl(H5Pcreate(H5P_GROUP_CREATE));
  H5Pset_obj_track_times(gcpl.get(), 0);
  Hid g(H5Gcreate2(id(), std::string(name).c_str(), lcpl.get(), gcpl.get(), H5P_DEFAULT));
  if (g.get() < 0) throw RuntimeError(where(name) + ": cannot create group");
  return Group(std::move(g), file_, join(path_, name), keep_alive_, walked_);
}

void Group::write_raw(std::string_view name, hid_t mem_type, hid_t file_type, const void* data,
                      const std::vector<hsize_t>& dims, std::size_t count, std::string_view unit) {
  hsize_t expected = 1;
  for (auto n : dims) expected *= n;
  if (expected != count)
    throw RuntimeError(where(name) + ": " + std::to_string(count) + " values do not fill a dataset of " +
                       std::to_string(expected));
  Hid space = simple_space(dims);
  Hid lcpl(H5Pcreate(H5P_LINK_CREATE));
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  Hid dcpl(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_obj_track_times(dcpl.get(), 0);
  hsize_t chunk_rows = 0, row = 1;  // (chunked: rows a chunk, and values a row)
  if (count >= kCompressFrom && !dims.empty()) {
    std::vector<hsize_t> chunk = dims;
    for (std::size_t k = 1; k < dims.size(); ++k) row *= dims[k];
    chunk_rows = chunk[0] = std::max<hsize_t>(1, std::min<hsize_t>(dims[0], (1u << 16) / std::max<hsize_t>(1, row)));
    H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data());
    H5Pset_shuffle(dcpl.get());
    H5Pset_deflate(dcpl.get(), 1);
  }
  Hid d(H5Dcreate2(id(), std::string(name).c_str(), file_type, space.get(), lcpl.get(), dcpl.get(), H5P_DEFAULT));
  if (d.get() < 0) throw RuntimeError(where(name) + ": cannot create dataset (" + write_failure(file_, errno) + ")");
  if (count > 0 && chunk_rows > 0 && encodes_chunks(mem_type, file_type)) {
    // Compressed: chunk by chunk, encoded here (io/chunk_codec: ~3 times as fast as HDF5's deflate filter).
    const std::size_t element = H5Tget_size(file_type), row_bytes = element * row;
    const auto* bytes = static_cast<const unsigned char*>(data);
    std::vector<hsize_t> offset(dims.size(), 0);
    for (hsize_t first = 0; first < dims[0]; first += chunk_rows) {
      const hsize_t rows = std::min(chunk_rows, dims[0] - first);
      offset[0] = first;
      if (write_encoded_chunk(d.get(), offset, {bytes + first * row_bytes, rows * row_bytes}, element,
                              chunk_rows * row_bytes) < 0)
        throw RuntimeError(where(name) + ": cannot write dataset (" + write_failure(file_, errno) + ")");
    }
  } else if (count > 0 &&
             H5Dwrite(d.get(), mem_type, H5S_ALL, H5S_ALL, transfer_for(mem_type, file_type, count).get(), data) < 0) {
    throw RuntimeError(where(name) + ": cannot write dataset (" + write_failure(file_, errno) + ")");
  }
  if (!unit.empty()) set_attr("unit", unit, name);
}

void Group::write(std::string_view name, std::span<const double> data, const std::vector<hsize_t>& dims,
                  std::string_view unit) {
  write_raw(name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, data.data(), dims, data.size(), unit);
}
void Group::write(std::string_view name, std::span<const std::int64_t> data, const std::vector<hsize_t>& dims,
                  std::string_view unit) {
  write_raw(name, H5T_NATIVE_INT64, H5T_STD_I64LE, data.data(), dims, data.size(), unit);
}
void Group::write(std::string_view name, std::span<const std::uint8_t> data, const std::vector<hsize_t>& dims,
                  std::string_view unit) {
  write_raw(name, H5T_NATIVE_UINT8, H5T_STD_U8LE, data.data(), dims, data.size(), unit);
}

void Group::write_strings(std::string_view name, const std::vector<std::string>& data) {
  std::vector<const char*> ptrs;
  ptrs.reserve(data.size());
  for (const auto& s : data) ptrs.push_back(s.c_str());
  Hid t = vlen_string_type();
  write_raw(name, t.get(), t.get(), ptrs.data(), {data.size()}, data.size(), "");
}

template <class T>
std::vector<T> Group::read(std::string_view name, std::vector<hsize_t>* dims_out, int rank, hsize_t columns) const {
  if (!has(name)) throw InputError(where(name) + ": no such dataset");
  Hid d(H5Dopen2(id(), std::string(name).c_str(), H5P_DEFAULT));
  if (d.get() < 0) throw InputError(where(name) + ": not a dataset");
  Hid ftype(H5Dget_type(d.get()));
  require_number_type(ftype.get(), !std::is_floating_point_v<T>, where(name));
  Hid space(H5Dget_space(d.get()));
  const int r = H5Sget_simple_extent_ndims(space.get());
  if (r < 0 || r > H5S_MAX_RANK) throw InputError(where(name) + ": damaged dataspace");
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(r, 0)));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  if (rank > 0 && r != rank)
    throw InputError(where(name) + ": expected " + std::to_string(rank) + " dimensions, found " + std::to_string(r));
  if (columns > 0 && (dims.empty() || dims.back() != columns))
    throw InputError(where(name) + ": expected " + std::to_string(columns) + " columns");
  const hsize_t count = checked_extent(d.get(), ftype.get(), dims, where(name));
  std::vector<T> out;
  try {
    out.resize(count);
  } catch (const std::bad_alloc&) {
    throw OutOfMemory("reading " + where(name), count * sizeof(T));
  }
  if (count > 0 && H5Dread(d.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    read_failed(where(name), "cannot read dataset (corrupt, or values out of range)", count * sizeof(T));
  if (dims_out) *dims_out = dims;
  return out;
}
template std::vector<double> Group::read<double>(std::string_view, std::vector<hsize_t>*, int, hsize_t) const;
template std::vector<std::int64_t> Group::read<std::int64_t>(std::string_view, std::vector<hsize_t>*, int,
                                                             hsize_t) const;
template std::vector<std::uint8_t> Group::read<std::uint8_t>(std::string_view, std::vector<hsize_t>*, int,
                                                             hsize_t) const;

namespace {
// Reads strings of either kind (variable or fixed length) from a dataset or attribute.
template <class ReadFn>
std::vector<std::string> read_string_values(hid_t ftype, hsize_t count, ReadFn&& read_fn, const std::string& where) {
  if (H5Tget_class(ftype) != H5T_STRING) throw InputError(where + ": not a string");
  std::vector<std::string> out;
  if (H5Tis_variable_str(ftype) > 0) {
    Hid t = vlen_string_type();
    std::vector<char*> ptrs(count, nullptr);
    if (count > 0 && read_fn(t.get(), ptrs.data()) < 0)
      read_failed(where, "cannot read strings", count * sizeof(char*));
    for (auto* p : ptrs) out.emplace_back(p ? p : "");
    for (auto* p : ptrs) std::free(p);
  } else {
    const std::size_t size = H5Tget_size(ftype);
    Hid t(H5Tcopy(H5T_C_S1));
    H5Tset_size(t.get(), size);
    std::vector<char> buf(size * count + 1, '\0');
    if (count > 0 && read_fn(t.get(), buf.data()) < 0) read_failed(where, "cannot read strings", buf.size());
    for (hsize_t k = 0; k < count; ++k)
      out.emplace_back(strnlen(buf.data() + k * size, size)
                           ? std::string(buf.data() + k * size, strnlen(buf.data() + k * size, size))
                           : "");
  }
  return out;
}
}  // namespace

std::vector<std::string> Group::read_strings(std::string_view name) const {
  if (!has(name)) throw InputError(where(name) + ": no such dataset");
  Hid d(H5Dopen2(id(), std::string(name).c_str(), H5P_DEFAULT));
  if (d.get() < 0) throw InputError(where(name) + ": not a dataset");
  Hid ftype(H5Dget_type(d.get()));
  Hid space(H5Dget_space(d.get()));
  const int r = H5Sget_simple_extent_ndims(space.get());
  if (r < 0 || r > H5S_MAX_RANK) throw InputError(where(name) + ": damaged dataspace");
  std::vector<hsize_t> dims(static_cast<std::size_t>(r));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  const hsize_t count = checked_extent(d.get(), ftype.get(), dims, where(name));
  if (const auto* walked = walked_strings(d.get(), ftype.get(), "", where(name))) return *walked;
  return read_string_values(
      ftype.get(), count,
      [&](hid_t mt, void* buf) {
        return H5Dread(d.get(), mt, H5S_ALL, H5S_ALL, transfer_for(mt, ftype.get(), count).get(), buf);
      },
      where(name));
}

namespace {
// The elements of an attribute, refused when its storage cannot hold them (each takes at least one
// byte; a fixed-size element, its size): a damaged size never drives an allocation.
std::size_t attribute_points(const Hid& a, const Hid& ftype, const std::string& what) {
  Hid space(H5Aget_space(a.get()));
  const hssize_t points = H5Sget_simple_extent_npoints(space.get());
  const hsize_t storage = H5Aget_storage_size(a.get());
  const bool variable = H5Tis_variable_str(ftype.get()) > 0;
  const std::size_t element = variable ? 1 : std::max<std::size_t>(H5Tget_size(ftype.get()), 1);
  if (points < 0 || static_cast<hsize_t>(points) > storage / element) throw InputError(what + ": damaged attribute");
  return static_cast<std::size_t>(points);
}
}  // namespace

Hid Group::open_object(std::string_view object) const {
  if (object != "." && !has(object)) throw InputError(where(object) + ": no such object");
  Hid o(H5Oopen(id(), std::string(object).c_str(), H5P_DEFAULT));
  if (o.get() < 0) throw InputError(where(object) + ": cannot open object");
  return o;
}

void Group::write_attr_raw(std::string_view name, std::string_view object, hid_t type, const void* data,
                           const std::vector<hsize_t>& dims) {
  Hid o = open_object(object);
  const std::string n(name);
  if (H5Aexists(o.get(), n.c_str()) > 0) H5Adelete(o.get(), n.c_str());
  Hid space = simple_space(dims);
  Hid a(H5Acreate2(o.get(), n.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT));
  if (a.get() < 0 || H5Awrite(a.get(), type, data) < 0)
    throw RuntimeError(where(object) + ": cannot write attribute '" + n + "' (" + write_failure(file_, errno) + ")");
}

void Group::set_attr(std::string_view name, std::string_view value, std::string_view object) {
  const std::string v(value);
  const char* p = v.c_str();
  Hid t = vlen_string_type();
  write_attr_raw(name, object, t.get(), &p, {});
}
void Group::set_attr(std::string_view name, double value, std::string_view object) {
  write_attr_raw(name, object, H5T_NATIVE_DOUBLE, &value, {});
}
void Group::set_attr(std::string_view name, std::int64_t value, std::string_view object) {
  write_attr_raw(name, object, H5T_NATIVE_INT64, &value, {});
}
void Group::set_attr(std::string_view name, const std::vector<std::int64_t>& value, std::string_view object) {
  write_attr_raw(name, object, H5T_NATIVE_INT64, value.data(), {value.size()});
}
void Group::set_attr(std::string_view name, const std::vector<double>& value, std::string_view object) {
  write_attr_raw(name, object, H5T_NATIVE_DOUBLE, value.data(), {value.size()});
}
void Group::set_attr(std::string_view name, const std::vector<std::string>& value, std::string_view object) {
  std::vector<const char*> ptrs;
  for (const auto& s : value) ptrs.push_back(s.c_str());
  Hid t = vlen_string_type();
  write_attr_raw(name, object, t.get(), ptrs.data(), {value.size()});
}

bool Group::has_attr(std::string_view name, std::string_view object) const {
  if (object != "." && !has(object)) return false;
  return H5Aexists_by_name(id(), std::string(object).c_str(), std::string(name).c_str(), H5P_DEFAULT) > 0;
}

Hid Group::open_attr(std::string_view name, std::string_view object) const {
  if (!has_attr(name, object)) throw InputError(where(object) + ": no attribute '" + std::string(name) + "'");
  Hid a(H5Aopen_by_name(id(), std::string(object).c_str(), std::string(name).c_str(), H5P_DEFAULT, H5P_DEFAULT));
  if (a.get() < 0) throw InputError(where(object) + ": cannot open attribute '" + std::string(name) + "'");
  return a;
}

const std::vector<std::string>* Group::walked_strings(hid_t o, hid_t ftype, const std::string& attr,
                                                      const std::string& what) const {
  if (!walked_ || H5Tget_class(ftype) != H5T_STRING || H5Tis_variable_str(ftype) <= 0) return nullptr;
  H5O_info_t info;
  if (H5Oget_info2(o, &info, H5O_INFO_BASIC) < 0) throw InputError(what + ": damaged object header");
  const auto it = walked_->find({info.addr, attr});
  if (it == walked_->end()) throw InputError(what + ": strings the file's walk did not find (damaged file)");
  return &it->second;
}

std::string Group::attr_string(std::string_view name, std::string_view object) const {
  Hid a = open_attr(name, object);
  Hid ftype(H5Aget_type(a.get()));
  const hsize_t count = attribute_points(a, ftype, where(object) + " attribute '" + std::string(name) + "'");
  if (const auto* walked = walked_strings(open_object(object).get(), ftype.get(), std::string(name),
                                          where(object) + " attribute '" + std::string(name) + "'"))
    return walked->empty() ? std::string() : walked->front();
  auto values = read_string_values(
      ftype.get(), count, [&](hid_t mt, void* buf) { return H5Aread(a.get(), mt, buf); },
      where(object) + " attribute '" + std::string(name) + "'");
  return values.empty() ? std::string() : values.front();
}

namespace {
template <class T>
std::vector<T> read_numeric_attr(const Hid& a, const std::string& what) {
  Hid ftype(H5Aget_type(a.get()));
  const H5T_class_t cls = H5Tget_class(ftype.get());
  if (cls != H5T_INTEGER && cls != H5T_FLOAT) throw InputError(what + ": not numeric");
  if (!standard_number_type(ftype.get())) throw InputError(what + ": damaged or unusual number type");
  const std::size_t count = attribute_points(a, ftype, what);
  std::vector<T> out(count);
  if (count > 0 && H5Aread(a.get(), native_type<T>(), out.data()) < 0)
    read_failed(what, "cannot read", count * sizeof(T));
  return out;
}
}  // namespace

double Group::attr_double(std::string_view name, std::string_view object) const {
  auto v = read_numeric_attr<double>(open_attr(name, object), where(object) + " attribute '" + std::string(name) + "'");
  if (v.size() != 1) throw InputError(where(object) + " attribute '" + std::string(name) + "': expected one value");
  return v[0];
}
std::int64_t Group::attr_int(std::string_view name, std::string_view object) const {
  auto v = read_numeric_attr<std::int64_t>(open_attr(name, object),
                                           where(object) + " attribute '" + std::string(name) + "'");
  if (v.size() != 1) throw InputError(where(object) + " attribute '" + std::string(name) + "': expected one value");
  return v[0];
}
std::vector<std::int64_t> Group::attr_ints(std::string_view name, std::string_view object) const {
  return read_numeric_attr<std::int64_t>(open_attr(name, object),
                                         where(object) + " attribute '" + std::string(name) + "'");
}
std::vector<double> Group::attr_doubles(std::string_view name, std::string_view object) const {
  return read_numeric_attr<double>(open_attr(name, object), where(object) + " attribute '" + std::string(name) + "'");
}

namespace {

// An input that is no regular file (standard input, a FIFO, a device): read into memory, checked, opened in
// place.
Group open_stream(std::FILE* in, const std::string& name) {
  auto image = read_hdf5_image(in, name);
  auto strings = probe_hdf5_file(name, image.get());
  // Open the bytes in place: no copy; the buffer lives as long as any group of this file.
  const hid_t fid =
      H5LTopen_file_image(image->data(), image->size(), H5LT_FILE_IMAGE_DONT_COPY | H5LT_FILE_IMAGE_DONT_RELEASE);
  if (fid < 0 && hdf5_out_of_memory()) throw OutOfMemory("opening " + name, image->size());
  if (fid < 0) throw InputError(name + ": holds a damaged HDF5 file");
  Hid file(fid);
  Hid root(H5Gopen2(fid, "/", H5P_DEFAULT));
  return Group(std::move(root), name, "/", image, std::move(strings));
}

}  // namespace

Group open_input(const std::string& path) {
  silence_hdf5_errors();
  if (path == "-") return open_stream(stdin, "-");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory");
  if (!std::filesystem::is_regular_file(path, ec)) {
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(path.c_str(), "rbe"), std::fclose);
    if (!in) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
    return open_stream(in.get(), path);
  }
  auto strings = probe_hdf5_file(path, nullptr);
  if (H5Fis_hdf5(path.c_str()) <= 0) throw InputError(path + ": not an HDF5 file");
  Hid file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  if (file.get() < 0 && hdf5_out_of_memory()) throw OutOfMemory("opening " + path, 0);
  if (file.get() < 0) throw InputError(path + ": cannot open (damaged HDF5 file, or no permission)");
  Hid root(H5Gopen2(file.get(), "/", H5P_DEFAULT));
  return Group(std::move(root), path, "/", {}, std::move(strings));
}

}  // namespace frac::io

#pragma once
// A small RAII layer over the HDF5 C API: identifiers that close themselves, groups that know their
// file's name (so every error names the file and dataset at fault), typed dataset and attribute I/O.
// Reading errors throw InputError; writing errors throw RuntimeError.
#include <hdf5.h>

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace frac::io {

// Owns an HDF5 identifier and closes it with the function that matches its type.
class Hid {
 public:
  Hid() = default;
  explicit Hid(hid_t id);  // type (file, group, dataset, ...) looked up with H5Iget_type
  Hid(const Hid&) = delete;
  Hid& operator=(const Hid&) = delete;
  Hid(Hid&& o) noexcept : id_(o.id_) { o.id_ = H5I_INVALID_HID; }
  Hid& operator=(Hid&& o) noexcept;
  ~Hid() { reset(); }
  hid_t get() const { return id_; }
  // Gives up ownership without closing.
  hid_t release() {
    const hid_t id = id_;
    id_ = H5I_INVALID_HID;
    return id;
  }
  void reset();

 private:
  hid_t id_ = H5I_INVALID_HID;
};

// Silences HDF5's own error printing: we report errors ourselves, naming file and object.
void silence_hdf5_errors();

// Whether the HDF5 call that just failed ran out of memory (a resource error on its error stack): a reader
// then reports core/memory's OutOfMemory, not a damaged file.
bool hdf5_out_of_memory();
// After a read of `where` failed: OutOfMemory (reading `bytes`) when libhdf5 ran out of memory, else
// InputError "where: why".
[[noreturn]] void read_failed(const std::string& where, const std::string& why, std::size_t bytes);

// Whether `t` is one of HDF5's standard integer or IEEE float types (8 to 64 bits, either byte order): the
// only number types the readers convert.
bool standard_number_type(hid_t t);

// InputError naming `where` unless a dataset of `file_type` reads as numbers: numeric, of a standard
// layout, and integer when `integers` (indices, counts, flags).
void require_number_type(hid_t file_type, bool integers, const std::string& where);
// InputError naming `where` unless `values` elements of `file_type` can fit the storage of dataset `d`.
void require_fits_storage(hid_t d, hid_t file_type, hsize_t values, const std::string& where);

// Whether chunks of a dataset of `file_type`, written from memory of `mem_type`, can be encoded by us
// (write_encoded_chunk): the two types must be the same bytes (native little-endian types to LE file types).
bool encodes_chunks(hid_t mem_type, hid_t file_type);
// Writes the chunk at `offset` of the chunked dataset `d`, whose pipeline is shuffle then deflate (the
// datasets io/ creates compressed): `data`, whole elements of `element_size` bytes, then zeros up to
// `chunk_bytes`, encoded by io/chunk_codec and written with H5Dwrite_chunk. The chunk must lie within the
// dataset's extent. Returns H5Dwrite_chunk's status.
herr_t write_encoded_chunk(hid_t d, const std::vector<hsize_t>& offset, std::span<const unsigned char> data,
                           std::size_t element_size, std::size_t chunk_bytes);

// The variable-length strings of an input file as the validating walk (io/hdf5_probe) read them, by
// object address and attribute name ("" for a string dataset's values). A reader of an input takes
// them from here and never lets libhdf5 follow a string's heap reference itself: an out-of-bounds
// reference that happened not to crash the walk could still crash the reader.
using WalkedStrings = std::map<std::pair<haddr_t, std::string>, std::vector<std::string>>;

// A group (or the root group of a file), with the file's name for messages.
class Group {
 public:
  Group(Hid id, std::string file, std::string path, std::shared_ptr<void> keep_alive = {},
        std::shared_ptr<const WalkedStrings> walked = {});

  hid_t id() const { return hid_.get(); }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  // "file.h5:/particles/cells/area": how messages name an object.
  std::string where(std::string_view name = "") const;

  bool has(std::string_view name) const;      // a link of that name (relative path allowed) exists
  Group group(std::string_view name) const;   // opens an existing group; InputError if missing
  Group create_group(std::string_view name);  // creates it and missing parents

  // Datasets, row-major data with the given shape; `unit` becomes the dataset's unit attribute.
  void write(std::string_view name, std::span<const double> data, const std::vector<hsize_t>& dims,
             std::string_view unit = "");
  void write(std::string_view name, std::span<const std::int64_t> data, const std::vector<hsize_t>& dims,
             std::string_view unit = "");
  void write(std::string_view name, std::span<const std::uint8_t> data, const std::vector<hsize_t>& dims,
             std::string_view unit = "");
  void write_strings(std::string_view name, const std::vector<std::string>& data);

  // Reads a whole numeric dataset converted to T (double, int64_t or uint8_t); its shape into dims.
  // `rank` > 0 requires that rank, and `columns` > 0 that many columns (last dimension).
  template <class T>
  std::vector<T> read(std::string_view name, std::vector<hsize_t>* dims = nullptr, int rank = 0,
                      hsize_t columns = 0) const;
  std::vector<std::string> read_strings(std::string_view name) const;

  // Attributes of the object `object` (relative to this group; "." is the group itself).
  void set_attr(std::string_view name, std::string_view value, std::string_view object = ".");
  void set_attr(std::string_view name, const char* value, std::string_view object = ".") {
    set_attr(name, std::string_view(value), object);
  }
  void set_attr(std::string_view name, double value, std::string_view object = ".");
  void set_attr(std::string_view name, std::int64_t value, std::string_view object = ".");
  void set_attr(std::string_view name, const std::vector<std::int64_t>& value, std::string_view object = ".");
  void set_attr(std::string_view name, const std::vector<double>& value, std::string_view object = ".");
  void set_attr(std::string_view name, const std::vector<std::string>& value, std::string_view object = ".");
  bool has_attr(std::string_view name, std::string_view object = ".") const;
  std::string attr_string(std::string_view name, std::string_view object = ".") const;
  double attr_double(std::string_view name, std::string_view object = ".") const;
  std::int64_t attr_int(std::string_view name, std::string_view object = ".") const;
  std::vector<std::int64_t> attr_ints(std::string_view name, std::string_view object = ".") const;
  std::vector<double> attr_doubles(std::string_view name, std::string_view object = ".") const;

 private:
  std::shared_ptr<void> keep_alive_;             // declared first: outlives hid_ (an in-memory file image)
  std::shared_ptr<const WalkedStrings> walked_;  // inputs only
  Hid hid_;
  std::string file_;
  std::string path_;

  Hid open_object(std::string_view object) const;
  Hid open_attr(std::string_view name, std::string_view object) const;
  // The walked strings of the object `o` (attribute `attr`, or "" for its values); null when this file
  // was not walked (an output) or the strings are of fixed length.
  const std::vector<std::string>* walked_strings(hid_t o, hid_t ftype, const std::string& attr,
                                                 const std::string& what) const;
  void write_raw(std::string_view name, hid_t mem_type, hid_t file_type, const void* data,
                 const std::vector<hsize_t>& dims, std::size_t count, std::string_view unit);
  void write_attr_raw(std::string_view name, std::string_view object, hid_t type, const void* data,
                      const std::vector<hsize_t>& dims);
};

// Opens an existing file for reading; "-" reads an HDF5 file image from standard input.
// InputError for a missing file, a file that is not HDF5 or empty standard input.
Group open_input(const std::string& path);

}  // namespace frac::io
